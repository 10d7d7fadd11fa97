#include "host/label_layout.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tessera {
namespace {

double overlap(const LabelRect& a, const LabelRect& b) {
  const double w = std::min(a.x + a.w, b.x + b.w) - std::max(a.x, b.x);
  const double h = std::min(a.y + a.h, b.y + b.h) - std::max(a.y, b.y);
  return w > 0 && h > 0 ? w * h : 0.0;
}

double outside(const LabelRect& r, const LabelRect& bounds) {
  return r.w * r.h - overlap(r, bounds);
}

LabelRect grown(const LabelRect& r, double d) {
  return {r.x - d, r.y - d, r.w + 2 * d, r.h + 2 * d};
}

bool contains(const LabelRect& r, double x, double y) {
  return x >= r.x && x <= r.x + r.w && y >= r.y && y <= r.y + r.h;
}

// Liang-Barsky: the parameter range [t0, t1] of `s` within `r`; false where it misses.
bool clip(const LabelSegment& s, const LabelRect& r, double& t0, double& t1) {
  const double dx = s.x1 - s.x0, dy = s.y1 - s.y0;
  t0 = 0.0;
  t1 = 1.0;
  const double p[] = {-dx, dx, -dy, dy};
  const double q[] = {s.x0 - r.x, r.x + r.w - s.x0, s.y0 - r.y, r.y + r.h - s.y0};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0.0) {
      if (q[i] <= 0.0) return false;  // parallel to this edge and outside it (or on it)
      continue;
    }
    const double t = q[i] / p[i];
    if (p[i] < 0.0) {
      t0 = std::max(t0, t);
    } else {
      t1 = std::min(t1, t);
    }
  }
  return t1 > t0;
}

// Points this close stand at the same place: their labels may lie beside either mark.
bool same_place(const LabelRequest& a, const LabelRequest& b) {
  return std::abs(a.x - b.x) < 0.5 && std::abs(a.y - b.y) < 0.5;
}

LabelRect mark_of(const LabelRequest& l) {
  return {l.x - l.mark, l.y - l.mark, 2 * l.mark, 2 * l.mark};
}

// Ring 0 lies beside the mark; the others a text line further out each, nine of them: about
// a hundred pixels at 10 px text, as far as a leader stays easy to follow.
constexpr int kRings = 10;
// Below this a spot's cost is rounding, not overlap.
constexpr double kFree = 1e-6;

// The spots of ring `ring` around `l`'s point for a box of w x h, in order of preference.
std::vector<LabelRect> ring_spots(const LabelRequest& l, double w, double h, int ring) {
  const double d = l.mark + kLabelGap + ring * (h + 2);
  const double x = l.x, y = l.y;
  std::vector<LabelRect> out = {
      {x + d, y - d - h / 2, w, h},      // right, above (the usual place)
      {x + d, y + d - h / 2, w, h},      // right, below
      {x - d - w, y - d - h / 2, w, h},  // left, above
      {x - d - w, y + d - h / 2, w, h},  // left, below
      {x - w / 2, y - d - h, w, h},      // above
      {x - w / 2, y + d, w, h},          // below
      {x + d, y - h / 2, w, h},          // right
      {x - d - w, y - h / 2, w, h},      // left
  };
  if (ring > 0) {
    // Further out the gaps between those are wide: more places where a cluster fills some.
    const LabelRect between[] = {
        {x + d, y - d / 2 - h / 2, w, h},      // right, a little above
        {x + d, y + d / 2 - h / 2, w, h},      // right, a little below
        {x - d - w, y - d / 2 - h / 2, w, h},  // left, a little above
        {x - d - w, y + d / 2 - h / 2, w, h},  // left, a little below
        {x, y - d - h, w, h},                  // above, to the right
        {x - w, y - d - h, w, h},              // above, to the left
        {x, y + d, w, h},                      // below, to the right
        {x - w, y + d, w, h},                  // below, to the left
    };
    out.insert(out.end(), std::begin(between), std::end(between));
  }
  return out;
}

// Which clump each mark is in: marks closer than kMarkClearance, and marks close to those.
// A label keeps kMarkClearance from every other mark, so the points of a clump other than its
// edge have no room beside them; their leaders cross the clump's other marks to reach them.
std::vector<size_t> clumps(const std::vector<LabelRect>& marks) {
  std::vector<size_t> clump(marks.size());
  for (size_t i = 0; i < marks.size(); ++i) clump[i] = i;
  auto root = [&](size_t i) {
    while (clump[i] != i) i = clump[i] = clump[clump[i]];
    return i;
  };
  for (size_t i = 0; i < marks.size(); ++i) {
    for (size_t j = i + 1; j < marks.size(); ++j) {
      if (overlap(grown(marks[i], kMarkClearance), marks[j]) > 0) clump[root(j)] = root(i);
    }
  }
  for (size_t i = 0; i < marks.size(); ++i) clump[i] = root(i);
  return clump;
}

struct Layout {
  const std::vector<LabelRequest>& labels;
  LabelRect bounds;
  std::vector<LabelSegment> lines;  // labels keep off these
  std::vector<LabelRect> marks;
  std::vector<size_t> clump;  // of each mark
  // Per label, the way out of its clump: from the clump's centre to the point, unit length;
  // zero for a point alone or at the centre.
  std::vector<std::pair<double, double>> outward;

  struct Leader {
    LabelSegment line;
    size_t owner;
  };
  std::vector<Leader> leaders;
  std::vector<LabelRect> boxes;  // of the labels placed so far
  std::vector<LabelSpot> spots;
  std::vector<bool> placed;
  std::vector<bool> stuck;     // no free spot for the label, its number or its range
  std::vector<size_t> tag_of;  // the first label of the box each label is shown in
  size_t led_out = 0;          // labels of limited clumps that tried the second pass
  // By clump: its labels without room beside their points share one range, with no numbers
  // of their own on the plot.
  std::vector<bool> ranged;
  // By clump: its labels count against run's budget of labels out on leaders.
  std::vector<bool> limited;

  // The spots of ring `ring` for label i's box (or number) of width `width`, in the order
  // tried. Out of the first ring, a clump's points take those away from its centre first:
  // leaders that leave a pile by the side their point is on cross the others' least.
  std::vector<LabelRect> candidates(size_t i, double width, int ring) const {
    const LabelRequest& l = labels[i];
    std::vector<LabelRect> out = ring_spots(l, width, l.height, ring);
    const auto [ux, uy] = outward[i];
    if (ring == 0 || (ux == 0 && uy == 0)) return out;
    auto along = [&](const LabelRect& r) {
      const double dx = r.x + r.w / 2 - l.x, dy = r.y + r.h / 2 - l.y;
      return (dx * ux + dy * uy) / std::hypot(dx, dy);
    };
    std::stable_sort(out.begin(), out.end(),
                     [&](const LabelRect& a, const LabelRect& b) { return along(a) > along(b); });
    return out;
  }

  // 0 for a free spot for label i's box `r` (with a leader or not); else how far from free.
  double cost(size_t i, const LabelRect& r, bool with_leader) const {
    const LabelRequest& l = labels[i];
    double c = 10 * outside(r, bounds);
    for (size_t j = 0; j < marks.size(); ++j) {
      const bool own = j == i || same_place(l, labels[j]);
      c += overlap(r, own ? marks[j] : grown(marks[j], kMarkClearance));
    }
    const LabelRect spaced{r.x - kLabelClearanceX, r.y - kLabelClearanceY,
                           r.w + 2 * kLabelClearanceX, r.h + 2 * kLabelClearanceY};
    for (const LabelRect& b : boxes) c += overlap(spaced, b);
    // Lines a little off the text: a stroke's width, or a glyph's edge at the box's, would
    // touch it.
    const LabelRect padded = grown(r, kLineClearance);
    for (const LabelSegment& s : lines) c += length_inside(s, padded) * r.h / 2;
    for (const Leader& s : leaders) c += length_inside(s.line, padded) * r.h / 2;
    if (!with_leader) return c;
    const LabelSegment leader = leader_line(l, r);
    for (const LabelRect& b : boxes) c += length_inside(leader, grown(b, kLineClearance)) * b.h / 2;
    for (size_t j = 0; j < marks.size(); ++j) {
      if (clump[j] != clump[i])
        c += length_inside(leader, grown(marks[j], kLineClearance)) * marks[j].h;
    }
    for (const Leader& s : leaders) {
      double x, y;
      if (segments_meet(leader, s.line, &x, &y) && !in_clump_mark(clump[i], x, y) &&
          !in_clump_mark(clump[s.owner], x, y))
        c += r.h * r.h;
    }
    return c;
  }

  // Whether (x, y) lies on a mark of clump `k` (or within a pixel of one).
  bool in_clump_mark(size_t k, double x, double y) const {
    for (size_t j = 0; j < marks.size(); ++j)
      if (clump[j] == k && contains(grown(marks[j], 1), x, y)) return true;
    return false;
  }

  // Places every label, in `order`, in the passes place_labels describes (of the labels of
  // limited clumps, only the first `budget` that reach the second pass try it, the others go
  // by number); returns how many labels, numbers or ranges found no free spot (`stuck`).
  size_t run(const std::vector<size_t>& order, size_t budget) {
    const size_t none = labels.size();
    leaders.clear();
    boxes.clear();
    spots.assign(labels.size(), {});
    placed.assign(labels.size(), false);
    stuck.assign(labels.size(), false);
    tag_of.assign(labels.size(), none);
    LabelRect box;
    bool leader = false;
    size_t count = 0;
    // Places the box of `tag`'s labels at the first free spot for tag[0], or at the spot of
    // least overlap.
    auto place_anyhow = [&](const std::vector<size_t>& tag, double width, bool numbered) {
      if (!find_free(tag[0], width, 0, kRings, box, leader)) {
        least_cost(tag[0], width, box, leader);
        for (size_t j : tag) stuck[j] = true;
        ++count;
      }
      place(tag, box, leader, numbered);
    };
    auto range_width = [&](size_t i) {
      return labels[i].range_width > 0 ? labels[i].range_width : labels[i].number_width;
    };
    // Beside their points first, so that no leader takes a place a label needs there.
    for (size_t i : order) {
      if (find_free(i, labels[i].width, 0, 1, box, leader)) place({i}, box, leader, false);
    }
    // Which of the others go out on leaders: all but those of limited clumps past the first
    // `budget` of those.
    std::vector<bool> out(labels.size(), false);
    led_out = 0;
    for (size_t i : order) {
      if (placed[i]) continue;
      if (!limited[clump[i]]) {
        out[i] = true;
      } else if (led_out < budget) {
        out[i] = true;
        ++led_out;
      }
    }
    // A ranged clump's range before the leaders, where some of its labels cannot go out: the
    // leaders then leave it room.
    std::vector<size_t> range_root(labels.size(), none);  // by clump
    for (size_t i : order) {
      if (placed[i] || out[i] || labels[i].number_width <= 0 || !ranged[clump[i]] ||
          range_root[clump[i]] != none)
        continue;
      range_root[clump[i]] = i;
      place_anyhow({i}, range_width(i), true);
    }
    for (size_t i : order) {
      if (out[i] && find_free(i, labels[i].width, 1, kRings, box, leader))
        place({i}, box, leader, false);
    }
    std::vector<size_t> homeless;  // no free spot for the label, nor for its number
    for (size_t i : order) {
      if (placed[i]) continue;
      if (labels[i].number_width > 0 && range_root[clump[i]] != none) {
        join(i, range_root[clump[i]]);
      } else if (labels[i].number_width > 0 && !ranged[clump[i]] &&
                 find_free(i, labels[i].number_width, 0, kRings, box, leader)) {
        place({i}, box, leader, true);
      } else {
        homeless.push_back(i);
      }
    }
    // The homeless of one clump share one range.
    std::vector<bool> seen(labels.size(), false);
    for (size_t i : homeless) {
      if (seen[i]) continue;
      const bool numbered = labels[i].number_width > 0;
      std::vector<size_t> tag = {i};
      seen[i] = true;
      for (size_t j : homeless) {
        if (numbered && !seen[j] && clump[j] == clump[i]) {
          seen[j] = true;
          tag.push_back(j);
        }
      }
      place_anyhow(tag,
                   !numbered        ? labels[i].width
                   : tag.size() > 1 ? range_width(i)
                                    : labels[i].number_width,
                   numbered);
    }
    // The numbers, 1, 2, ... in the order given; a range's labels one after another, its
    // box's own (whose point its leader joins) first.
    int n = 0;
    for (size_t i : order) {
      if (spots[i].number != -1) continue;
      const size_t root = tag_of[i];
      const int first = n + 1;
      spots[root].number = ++n;
      for (size_t j : order) {
        if (spots[j].number == -1 && tag_of[j] == root) spots[j].number = ++n;
      }
      for (size_t j = 0; j < labels.size(); ++j) {
        if (tag_of[j] == root) {
          spots[j].tag_first = first;
          spots[j].tag_last = n;
        }
      }
    }
    return count;
  }

  // Shows label i in the box of label `root`'s range.
  void join(size_t i, size_t root) {
    spots[i] = spots[root];
    placed[i] = true;
    tag_of[i] = root;
    stuck[i] = stuck[root];
  }

  // Places the labels of `tag` (one, or a pile's sharing a range of numbers) at `box`, with a
  // leader from the first's point if `leader`; `numbered`: the box holds their numbers.
  void place(const std::vector<size_t>& tag, const LabelRect& box, bool leader, bool numbered) {
    for (size_t i : tag) {
      spots[i] = {box, leader, numbered ? -1 : 0, 0, 0};
      placed[i] = true;
      tag_of[i] = tag[0];
    }
    boxes.push_back(box);
    if (leader) leaders.push_back({leader_line(labels[tag[0]], box), tag[0]});
  }

  // The first free spot of rings [first, last) for label i's box (or number) of width
  // `width`, and whether it needs a leader; false where none is.
  bool find_free(size_t i, double width, int first, int last, LabelRect& box, bool& leader) const {
    for (int ring = first; ring < last; ++ring) {
      for (const LabelRect& r : candidates(i, width, ring)) {
        if (cost(i, r, ring > 0) < kFree) {
          box = r;
          leader = ring > 0;
          return true;
        }
      }
    }
    return false;
  }

  // The spot of least cost of every ring.
  void least_cost(size_t i, double width, LabelRect& box, bool& leader) const {
    double best_cost = std::numeric_limits<double>::infinity();
    for (int ring = 0; ring < kRings; ++ring) {
      for (const LabelRect& r : candidates(i, width, ring)) {
        const double c = cost(i, r, ring > 0);
        if (c < best_cost) {
          best_cost = c;
          box = r;
          leader = ring > 0;
        }
      }
    }
  }
};

}  // namespace

LabelSegment leader_line(const LabelRequest& label, const LabelRect& box) {
  return {label.x, label.y, std::clamp(label.x, box.x, box.x + box.w),
          std::clamp(label.y, box.y, box.y + box.h)};
}

double length_inside(const LabelSegment& s, const LabelRect& r) {
  double t0, t1;
  if (!clip(s, r, t0, t1)) return 0.0;
  return (t1 - t0) * std::hypot(s.x1 - s.x0, s.y1 - s.y0);
}

bool segments_meet(const LabelSegment& a, const LabelSegment& b, double* at_x, double* at_y) {
  const double rx = a.x1 - a.x0, ry = a.y1 - a.y0;
  const double sx = b.x1 - b.x0, sy = b.y1 - b.y0;
  const double qx = b.x0 - a.x0, qy = b.y0 - a.y0;
  const double denom = rx * sy - ry * sx;
  double t;  // where along `a` they meet
  if (denom != 0.0) {
    t = (qx * sy - qy * sx) / denom;
    const double u = (qx * ry - qy * rx) / denom;
    if (t < 0 || t > 1 || u < 0 || u > 1) return false;
  } else {
    // Parallel: they meet only on one line, where their spans along it overlap.
    if (qx * ry - qy * rx != 0.0 || qx * sy - qy * sx != 0.0) return false;
    const double rr = rx * rx + ry * ry;
    if (rr == 0.0) {  // `a` is a point: on `b`?
      const double ss = sx * sx + sy * sy;
      if (ss == 0.0) {
        if (qx != 0.0 || qy != 0.0) return false;
      } else {
        const double u = -(qx * sx + qy * sy) / ss;
        if (u < 0 || u > 1) return false;
      }
      t = 0.0;
    } else {
      double u0 = (qx * rx + qy * ry) / rr, u1 = u0 + (sx * rx + sy * ry) / rr;
      if (u0 > u1) std::swap(u0, u1);
      if (u1 < 0 || u0 > 1) return false;
      t = std::min(1.0, u1);
    }
  }
  if (at_x) *at_x = a.x0 + rx * t;
  if (at_y) *at_y = a.y0 + ry * t;
  return true;
}

std::vector<LabelSpot> place_labels(const std::vector<LabelRequest>& labels,
                                    const LabelRect& bounds,
                                    const std::vector<LabelSegment>& lines) {
  Layout layout{labels, bounds, lines, {}, {}, {}, {}, {}, {}, {}, {}, {}, 0, {}, {}};
  for (const LabelRequest& l : labels) layout.marks.push_back(mark_of(l));
  layout.clump = clumps(layout.marks);
  std::vector<double> sum_x(labels.size()), sum_y(labels.size()), count(labels.size());
  for (size_t i = 0; i < labels.size(); ++i) {
    sum_x[layout.clump[i]] += labels[i].x;
    sum_y[layout.clump[i]] += labels[i].y;
    count[layout.clump[i]] += 1;
  }
  for (size_t i = 0; i < labels.size(); ++i) {
    const size_t k = layout.clump[i];
    const double dx = labels[i].x - sum_x[k] / count[k], dy = labels[i].y - sum_y[k] / count[k];
    const double length = std::hypot(dx, dy);
    layout.outward.push_back(length > 0.5 ? std::pair{dx / length, dy / length}
                                          : std::pair{0.0, 0.0});
  }
  layout.ranged.assign(labels.size(), false);
  layout.limited.assign(labels.size(), false);
  std::vector<size_t> order(labels.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  size_t fewest = labels.size() + 1;
  std::vector<LabelSpot> best;
  // Keeps the try with fewest labels left without a free spot (the first of equals).
  auto keep = [&](size_t stuck) {
    if (stuck < fewest) {
      fewest = stuck;
      best = layout.spots;
    }
    return stuck == 0;
  };
  for (int attempt = 0; !keep(layout.run(order, labels.size())); ++attempt) {
    if (attempt < 3) {
      // Greedy placing can hem a label in with the leaders of those placed before it: those
      // left without a free spot go first in the next try.
      std::stable_partition(order.begin(), order.end(), [&](size_t i) { return layout.stuck[i]; });
      if (attempt == 2) {
        // The tries below drop labels last in the order first: the order given again.
        for (size_t i = 0; i < order.size(); ++i) order[i] = i;
      }
      continue;
    }
    bool more_ranged = false;
    for (size_t i : order) {
      if (layout.stuck[i] && labels[i].number_width > 0 && !layout.ranged[layout.clump[i]]) {
        // The numbers of a cluster crowd out its range: its labels without room beside their
        // points share the range alone.
        layout.ranged[layout.clump[i]] = true;
        more_ranged = true;
      }
    }
    if (more_ranged) continue;
    // Clusters too dense for their labels: as many of theirs out on leaders (the first in the
    // order) as leave none without a free spot, the others numbered; found by halving.
    for (size_t i : order) {
      if (layout.stuck[i]) layout.limited[layout.clump[i]] = true;
    }
    layout.run(order, labels.size());  // the same as the last, counting theirs out
    size_t fails = layout.led_out;
    if (fails == 0 || !keep(layout.run(order, 0))) break;
    size_t works = 0;
    while (fails - works > 1) {
      const size_t mid = works + (fails - works) / 2;
      if (layout.run(order, mid) == 0) {
        works = mid;
        fewest = labels.size() + 1;  // a larger budget with none stuck is better
        keep(0);
      } else {
        fails = mid;
      }
    }
    break;
  }
  return best;
}

}  // namespace tessera
