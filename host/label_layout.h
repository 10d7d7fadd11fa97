#pragma once
// Where a chart's point labels go, so that each is readable and plainly its own point's: clear
// of every other label and mark, beside its point or joined to it by a leader line, and, where
// a cluster leaves no such room, a number beside the point that a legend pairs with the label.

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
  /// Width of the number placed instead where the label finds no room (as wide as the largest
  /// number the caller may need; the height is the label's); 0: no number, the label takes the
  /// spot of least overlap instead.
  double number_width = 0;
  /// Width of a range of numbers ("12-34", as wide as the widest the caller may need) that a
  /// pile's labels share where even their numbers find no room; 0: number_width.
  double range_width = 0;
};

/// A line already drawn (a series' joining line) that labels should not lie across.
struct LabelSegment {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

struct LabelSpot {
  LabelRect box;        // where the text goes: drawn from its left edge, centred vertically
  bool leader = false;  // placed out of its point's first ring: join them with a line
  /// > 0: the label found no room, and `box` holds a number instead, for a legend to pair with
  /// the label: this one (1, 2, ... in the order of the labels given), or the range
  /// tag_first-tag_last (a pile's labels without room for their numbers share one box).
  int number = 0;
  int tag_first = 0, tag_last = 0;  // what `box` shows: tag_first alone where they are equal
};

/// Clearances place_labels keeps, pixels: a label beside its point is kLabelGap off its mark;
/// every label keeps kMarkClearance from the marks of other points (but those within half a
/// pixel of its own: the same place), and from other labels kLabelClearanceX side by side
/// (more than a space, or two would read as one) or kLabelClearanceY one above the other (the
/// text is shorter than its box); lines and leaders keep kLineClearance from labels, and
/// leaders from the marks of other clumps.
constexpr double kLabelGap = 2;
constexpr double kMarkClearance = 5;
constexpr double kLabelClearanceX = 6;
constexpr double kLabelClearanceY = 2;
constexpr double kLineClearance = 3;

/// The line joining a label placed out of its first ring to its point: from the point to the
/// nearest point of the box.
LabelSegment leader_line(const LabelRequest& label, const LabelRect& box);

/// Length of the part of `s` inside `r` (0 where it misses).
double length_inside(const LabelSegment& s, const LabelRect& r);

/// Whether segments `a` and `b` meet, and where (`at`, where not null): for segments along one
/// line, the end of their common part furthest along `a`.
bool segments_meet(const LabelSegment& a, const LabelSegment& b, double* at_x = nullptr,
                   double* at_y = nullptr);

/// Places labels[i] at result[i]. A spot is free when it lies inside `bounds`, keeps the
/// clearances above from every mark, from every label placed before it and from `lines` and
/// the leaders placed before it, and its own leader (spots out of the first ring) keeps
/// kLineClearance from every label and from every mark outside its point's clump, and meets
/// no earlier leader but on a mark of the clump of either. A clump: marks less than
/// kMarkClearance apart, and marks that near those; its inner points have no room beside them,
/// and their leaders cross it to reach them.
/// Three passes, each over the labels in the order given (callers list the labels that matter
/// most first), each label taking the first free spot of its pass: beside its point (right and
/// above, as charts usually label, then the other corners and sides); then further out with a
/// leader, ring by ring, a text line apart, up to about nine lines out (a clump's points trying
/// the side away from its centre first); then, where neither is free, a number
/// (LabelRequest::number_width) in the first free spot of the same rings. The labels of a
/// clump left without room even for their numbers share one range of numbers
/// (LabelRequest::range_width), placed the same way. Where some are still left without a free
/// spot, the layout is tried again: up to three times with those first (greedy placing can hem
/// a label in with the leaders of those before it); then with their clumps' labels in the range
/// alone, without numbers of their own; then with only as many labels out on leaders (the
/// first in the order) as leave none without a free spot, the others numbered. The try with
/// fewest left stands, and those take the spot of least overlap (area outside `bounds`
/// counting ten times), as does a label without room where number_width is 0. Deterministic;
/// each try checks some 150 spots a label against every mark, label, line and leader. Sizes
/// are pixels.
std::vector<LabelSpot> place_labels(const std::vector<LabelRequest>& labels,
                                    const LabelRect& bounds,
                                    const std::vector<LabelSegment>& lines = {});

}  // namespace tessera
