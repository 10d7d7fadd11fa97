#pragma once
// Where a chart's point labels go, so that they overlap neither each other nor the points.

#include <vector>

namespace tessera {

/// A rectangle in pixels: top-left corner, width and height (y down).
struct LabelRect {
  double x = 0, y = 0, w = 0, h = 0;
};

struct LabelRequest {
  double x = 0, y = 0;           // the point the label names
  double mark = 0;               // half the side of the point's square mark, pixels
  double width = 0, height = 0;  // the label's text extent, pixels
};

struct LabelSpot {
  LabelRect box;        // where the text goes: drawn from its left edge, centred vertically
  bool leader = false;  // placed out of its point's first ring: join them with a line
};

/// Places labels[i] at result[i], greedily in the order given (callers list the labels that
/// matter most first): each takes the first of a fixed list of spots around its point, nearest
/// first (right and above, as charts usually label, then the other corners and sides, then two
/// rings further out), that overlaps no label placed before it, no point's mark and stays inside
/// `bounds`. Where none does, it takes the spot with the least overlap (area outside `bounds`
/// counting ten times). Deterministic; O(n^2) in the number of labels. Sizes are pixels.
std::vector<LabelSpot> place_labels(const std::vector<LabelRequest>& labels,
                                    const LabelRect& bounds);

}  // namespace tessera
