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

constexpr int kRings = 3;

// The spots around a point, nearest first: ring 0 touches the mark (2 px off), rings 1 and 2
// are a text line further out each.
std::vector<LabelRect> spots(const LabelRequest& l) {
  std::vector<LabelRect> out;
  const double w = l.width, h = l.height;
  for (int ring = 0; ring < kRings; ++ring) {
    const double d = l.mark + 2 + ring * (h + 2);
    const double x = l.x, y = l.y;
    const LabelRect ring_spots[] = {
        {x + d, y - d - h / 2, w, h},      // right, above (the usual place)
        {x + d, y + d - h / 2, w, h},      // right, below
        {x - d - w, y - d - h / 2, w, h},  // left, above
        {x - d - w, y + d - h / 2, w, h},  // left, below
        {x - w / 2, y - d - h, w, h},      // above
        {x - w / 2, y + d, w, h},          // below
        {x + d, y - h / 2, w, h},          // right
        {x - d - w, y - h / 2, w, h},      // left
    };
    out.insert(out.end(), std::begin(ring_spots), std::end(ring_spots));
  }
  return out;
}

}  // namespace

LabelSegment leader_line(const LabelRequest& label, const LabelRect& box) {
  return {label.x, label.y, std::clamp(label.x, box.x, box.x + box.w),
          std::clamp(label.y, box.y, box.y + box.h)};
}

double length_inside(const LabelSegment& s, const LabelRect& r) {
  // Liang-Barsky: the segment's parameter range [t0, t1] within each slab of the rectangle.
  const double dx = s.x1 - s.x0, dy = s.y1 - s.y0;
  double t0 = 0.0, t1 = 1.0;
  const double p[] = {-dx, dx, -dy, dy};
  const double q[] = {s.x0 - r.x, r.x + r.w - s.x0, s.y0 - r.y, r.y + r.h - s.y0};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0.0) {
      if (q[i] <= 0.0) return 0.0;  // parallel to this edge and outside it (or on it)
      continue;
    }
    const double t = q[i] / p[i];
    if (p[i] < 0.0) {
      t0 = std::max(t0, t);
    } else {
      t1 = std::min(t1, t);
    }
  }
  return t1 > t0 ? (t1 - t0) * std::sqrt(dx * dx + dy * dy) : 0.0;
}

std::vector<LabelSpot> place_labels(const std::vector<LabelRequest>& labels,
                                    const LabelRect& bounds,
                                    const std::vector<LabelSegment>& lines) {
  std::vector<LabelRect> marks;
  marks.reserve(labels.size());
  for (const LabelRequest& l : labels) {
    marks.push_back({l.x - l.mark, l.y - l.mark, 2 * l.mark, 2 * l.mark});
  }
  std::vector<LabelSpot> placed;
  placed.reserve(labels.size());
  // The lines labels keep off: `lines`, then each leader as it is drawn.
  std::vector<LabelSegment> drawn = lines;
  for (const LabelRequest& l : labels) {
    const std::vector<LabelRect> candidates = spots(l);
    const size_t per_ring = candidates.size() / kRings;
    double best_cost = std::numeric_limits<double>::infinity();
    size_t best = 0;
    for (size_t c = 0; c < candidates.size() && best_cost > 0; ++c) {
      const LabelRect& r = candidates[c];
      double cost = 10 * outside(r, bounds);
      for (const LabelRect& m : marks) cost += overlap(r, m);
      for (const LabelSpot& p : placed) cost += overlap(r, p.box);
      for (const LabelSegment& s : drawn) cost += length_inside(s, r) * r.h / 2;
      if (c >= per_ring) {
        const LabelSegment leader = leader_line(l, r);
        for (const LabelSpot& p : placed) cost += length_inside(leader, p.box) * p.box.h / 2;
      }
      if (cost < best_cost) {
        best_cost = cost;
        best = c;
      }
    }
    placed.push_back({candidates[best], best >= per_ring});
    if (placed.back().leader) drawn.push_back(leader_line(l, placed.back().box));
  }
  return placed;
}

}  // namespace tessera
