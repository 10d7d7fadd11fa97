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

/// A line already drawn (a series' joining line) that labels should not lie across.
struct LabelSegment {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

struct LabelSpot {
  LabelRect box;        // where the text goes: drawn from its left edge, centred vertically
  bool leader = false;  // placed out of its point's first ring: join them with a line
};

/// The line joining a label placed out of its first ring to its point: from the point to the
/// nearest point of the box.
LabelSegment leader_line(const LabelRequest& label, const LabelRect& box);

/// Length of the part of `s` inside `r` (0 where it misses).
double length_inside(const LabelSegment& s, const LabelRect& r);

/// Places labels[i] at result[i], greedily in the order given (callers list the labels that
/// matter most first): each takes the first of a fixed list of spots around its point, nearest
/// first (right and above, as charts usually label, then the other corners and sides, then two
/// rings further out), that overlaps no label placed before it, no point's mark, no line of
/// `lines` and no leader line of a label placed before it, whose own leader line (spots past
/// the first ring) crosses no label placed before it, and that stays inside `bounds`. Where
/// none does, it takes the spot with the least overlap (area outside `bounds` counting ten
/// times, a line across a label the line's length inside it times half the label's height).
/// Deterministic; O(n^2 + n m) in n labels and m lines. Sizes are pixels.
std::vector<LabelSpot> place_labels(const std::vector<LabelRequest>& labels,
                                    const LabelRect& bounds,
                                    const std::vector<LabelSegment>& lines = {});

}  // namespace tessera
