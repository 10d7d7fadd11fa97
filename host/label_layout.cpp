#include "host/label_layout.h"

#include <algorithm>
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

// The spots around a point, nearest first: ring 0 touches the mark (2 px off), rings 1 and 2
// are a text line further out each.
std::vector<LabelRect> spots(const LabelRequest& l) {
  std::vector<LabelRect> out;
  const double w = l.width, h = l.height;
  for (int ring = 0; ring < 3; ++ring) {
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

std::vector<LabelSpot> place_labels(const std::vector<LabelRequest>& labels,
                                    const LabelRect& bounds) {
  std::vector<LabelRect> marks;
  marks.reserve(labels.size());
  for (const LabelRequest& l : labels) {
    marks.push_back({l.x - l.mark, l.y - l.mark, 2 * l.mark, 2 * l.mark});
  }
  std::vector<LabelSpot> placed;
  placed.reserve(labels.size());
  for (const LabelRequest& l : labels) {
    const std::vector<LabelRect> candidates = spots(l);
    const size_t per_ring = candidates.size() / 3;
    double best_cost = std::numeric_limits<double>::infinity();
    size_t best = 0;
    for (size_t c = 0; c < candidates.size() && best_cost > 0; ++c) {
      const LabelRect& r = candidates[c];
      double cost = 10 * outside(r, bounds);
      for (const LabelRect& m : marks) cost += overlap(r, m);
      for (const LabelSpot& p : placed) cost += overlap(r, p.box);
      if (cost < best_cost) {
        best_cost = cost;
        best = c;
      }
    }
    placed.push_back({candidates[best], best >= per_ring});
  }
  return placed;
}

}  // namespace tessera
