// place_labels (host/label_layout.h): chart labels that overlap neither each other nor the
// points' marks, inside the plot, next to their points where there is room, joined to them by
// leaders further out, and numbers for a legend where a cluster leaves no room for a label.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "host/label_layout.h"

namespace tessera {
namespace {

bool inside(const LabelRect& r, const LabelRect& bounds) {
  return r.x >= bounds.x && r.y >= bounds.y && r.x + r.w <= bounds.x + bounds.w &&
         r.y + r.h <= bounds.y + bounds.h;
}

LabelRect grow(const LabelRect& r, double d) {
  return {r.x - d, r.y - d, r.w + 2 * d, r.h + 2 * d};
}

LabelRect mark_of(const LabelRequest& l) {
  return {l.x - l.mark, l.y - l.mark, 2 * l.mark, 2 * l.mark};
}

// The widest empty band between two rectangles, along x or y (negative where they overlap).
double gap(const LabelRect& a, const LabelRect& b) {
  const double gx = std::max(b.x - (a.x + a.w), a.x - (b.x + b.w));
  const double gy = std::max(b.y - (a.y + a.h), a.y - (b.y + b.h));
  return std::max(gx, gy);
}

// The checks below walk lines in steps of this many pixels instead of solving for where they
// meet, as place_labels does.
constexpr double kStep = 0.05;

// The points of `s` kStep apart, both ends included.
std::vector<std::pair<double, double>> walk(const LabelSegment& s) {
  const int n = std::max(1, int(std::ceil(std::hypot(s.x1 - s.x0, s.y1 - s.y0) / kStep)));
  std::vector<std::pair<double, double>> out;
  for (int i = 0; i <= n; ++i) {
    const double t = double(i) / n;
    out.push_back({s.x0 + (s.x1 - s.x0) * t, s.y0 + (s.y1 - s.y0) * t});
  }
  return out;
}

bool strictly_in(const LabelRect& r, double x, double y) {
  return x > r.x && x < r.x + r.w && y > r.y && y < r.y + r.h;
}

// Whether `s` runs through the inside of `r` for more than a step.
bool enters(const LabelSegment& s, const LabelRect& r) {
  int in = 0;
  for (const auto& [x, y] : walk(s)) in += strictly_in(r, x, y);
  return in > 1;
}

double distance_to(const LabelSegment& s, double x, double y) {
  const double dx = s.x1 - s.x0, dy = s.y1 - s.y0, len2 = dx * dx + dy * dy;
  const double t = len2 == 0 ? 0 : std::clamp(((x - s.x0) * dx + (y - s.y0) * dy) / len2, 0.0, 1.0);
  return std::hypot(s.x0 + t * dx - x, s.y0 + t * dy - y);
}

// The clumps of the marks, as place_labels documents them: marks less than kMarkClearance
// apart, transitively (a flood fill here).
std::vector<int> clumps_of(const std::vector<LabelRequest>& labels) {
  std::vector<int> clump(labels.size(), -1);
  int next = 0;
  for (size_t seed = 0; seed < labels.size(); ++seed) {
    if (clump[seed] >= 0) continue;
    std::vector<size_t> todo = {seed};
    clump[seed] = next;
    while (!todo.empty()) {
      const size_t i = todo.back();
      todo.pop_back();
      for (size_t j = 0; j < labels.size(); ++j) {
        if (clump[j] < 0 && gap(mark_of(labels[i]), mark_of(labels[j])) < kMarkClearance) {
          clump[j] = next;
          todo.push_back(j);
        }
      }
    }
    ++next;
  }
  return clump;
}

// What a chart draws for the labels: a box each, but one for all the labels of a range, with
// the leader from the point of the range's first.
struct Drawn {
  size_t owner;                 // the label whose point the box belongs to
  std::vector<size_t> members;  // the labels shown in it
  LabelRect box;
  bool leader;
  LabelSegment line;  // the leader, where there is one
};

std::vector<Drawn> drawn(const std::vector<LabelRequest>& labels,
                         const std::vector<LabelSpot>& spots) {
  std::vector<Drawn> out;
  for (size_t i = 0; i < labels.size(); ++i) {
    const LabelSpot& s = spots[i];
    if (s.number > 0 && s.tag_first != s.number) continue;  // a range, drawn with its first
    Drawn d{i, {i}, s.box, s.leader, {}};
    for (size_t j = 0; j < labels.size(); ++j) {
      if (j != i && s.number > 0 && spots[j].number > 0 && spots[j].tag_first == s.tag_first)
        d.members.push_back(j);
    }
    // The nearest point of the box to the point, found independently of leader_line.
    d.line = {labels[i].x, labels[i].y, std::min(std::max(labels[i].x, s.box.x), s.box.x + s.box.w),
              std::min(std::max(labels[i].y, s.box.y), s.box.y + s.box.h)};
    out.push_back(d);
  }
  return out;
}

// Every label, number or range readable and plainly its own point's, as place_labels
// promises: inside `bounds`, kLabelClearanceX or -Y from every other, kMarkClearance from the
// marks of other points and off its own, kLineClearance from every line and leader; without a
// leader kLabelGap from its own mark; leaders kLineClearance from every other label and from
// the marks outside their clump, and meeting no other leader but on a mark of the clump of
// either. Numbers 1, 2, ... once each, a range's members one after another, and the boxes as
// wide as asked.
void expect_readable(const std::vector<LabelRequest>& labels, const std::vector<LabelSpot>& spots,
                     const LabelRect& bounds, const std::vector<LabelSegment>& lines = {}) {
  ASSERT_EQ(spots.size(), labels.size());
  const std::vector<int> clump = clumps_of(labels);
  const std::vector<Drawn> items = drawn(labels, spots);
  std::set<int> numbers;
  for (size_t a = 0; a < items.size(); ++a) {
    const Drawn& d = items[a];
    const size_t i = d.owner;
    SCOPED_TRACE("label " + std::to_string(i));
    const LabelSpot& s = spots[i];
    const LabelRect& box = d.box;
    EXPECT_TRUE(inside(box, bounds));
    if (s.number == 0) {
      EXPECT_DOUBLE_EQ(box.w, labels[i].width);
    } else if (d.members.size() == 1) {
      EXPECT_DOUBLE_EQ(box.w, labels[i].number_width);
      EXPECT_EQ(s.tag_last, s.number);
    } else {
      EXPECT_DOUBLE_EQ(box.w,
                       labels[i].range_width > 0 ? labels[i].range_width : labels[i].number_width);
      EXPECT_EQ(s.tag_last, s.tag_first + int(d.members.size()) - 1);
    }
    for (size_t m : d.members) {
      if (spots[m].number == 0) continue;
      EXPECT_TRUE(numbers.insert(spots[m].number).second) << "number " << spots[m].number;
      EXPECT_GE(spots[m].number, s.tag_first);
      EXPECT_LE(spots[m].number, s.tag_last);
    }
    for (size_t j = 0; j < labels.size(); ++j) {
      const bool same_place =
          std::abs(labels[i].x - labels[j].x) < 0.5 && std::abs(labels[i].y - labels[j].y) < 0.5;
      EXPECT_GE(gap(box, mark_of(labels[j])), j == i || same_place ? 0.0 : kMarkClearance - 1e-9)
          << "mark " << j;
    }
    for (size_t b = 0; b < items.size(); ++b) {
      if (b == a) continue;
      const LabelRect& other = items[b].box;
      const double gap_x = std::max(other.x - (box.x + box.w), box.x - (other.x + other.w));
      const double gap_y = std::max(other.y - (box.y + box.h), box.y - (other.y + other.h));
      EXPECT_TRUE(gap_x >= kLabelClearanceX - 1e-9 || gap_y >= kLabelClearanceY - 1e-9)
          << "label " << items[b].owner;
      if (items[b].leader) {
        EXPECT_FALSE(enters(items[b].line, grow(box, kLineClearance)))
            << "leader " << items[b].owner;
      }
    }
    for (const LabelSegment& l : lines) EXPECT_FALSE(enters(l, grow(box, kLineClearance)));
    if (!d.leader) {
      EXPECT_LE(gap(box, mark_of(labels[i])), kLabelGap + 1e-9) << "beside its mark";
      continue;
    }
    for (size_t j = 0; j < labels.size(); ++j) {
      if (clump[j] != clump[i]) {
        EXPECT_FALSE(enters(d.line, grow(mark_of(labels[j]), kLineClearance))) << "by mark " << j;
      }
    }
    for (size_t b = 0; b < items.size(); ++b) {
      if (b == a) continue;
      const Drawn& e = items[b];
      EXPECT_FALSE(enters(d.line, grow(e.box, kLineClearance))) << "by label " << e.owner;
      if (b < a || !e.leader) continue;
      // Where they meet, it must be on a mark of the clump of either.
      for (const auto& [x, y] : walk(d.line)) {
        if (distance_to(e.line, x, y) > kStep) continue;
        bool on_clump = false;
        for (size_t k = 0; k < labels.size(); ++k) {
          on_clump |= (clump[k] == clump[i] || clump[k] == clump[e.owner]) &&
                      strictly_in(grow(mark_of(labels[k]), 1 + kStep), x, y);
        }
        EXPECT_TRUE(on_clump) << "leaders " << i << " and " << e.owner << " meet at " << x << ", "
                              << y;
        if (!on_clump) break;
      }
    }
  }
  // 1, 2, ... with none left out.
  if (!numbers.empty()) {
    EXPECT_EQ(*numbers.begin(), 1);
    EXPECT_EQ(*numbers.rbegin(), int(numbers.size()));
  }
}

int numbered(const std::vector<LabelSpot>& spots) {
  return int(
      std::count_if(spots.begin(), spots.end(), [](const LabelSpot& s) { return s.number > 0; }));
}

const LabelRect kPlot{0, 0, 600, 400};

TEST(LabelLayout, ALoneLabelSitsRightOfItsPointAndAbove) {
  const std::vector<LabelSpot> spots = place_labels({{300, 200, 5, 40, 10}}, kPlot);
  ASSERT_EQ(spots.size(), 1u);
  // 2 px beyond the mark (half side 5), its middle the same distance above the point.
  EXPECT_DOUBLE_EQ(spots[0].box.x, 307);
  EXPECT_DOUBLE_EQ(spots[0].box.y + spots[0].box.h / 2, 193);
  EXPECT_FALSE(spots[0].leader);
}

TEST(LabelLayout, CrowdedPointsGetLabelsThatOverlapNothing) {
  // Eight points within a few pixels, as the tradeoff chart's settings of similar cost and
  // error are: each label must find its own place, clear of every mark.
  std::vector<LabelRequest> labels;
  for (int i = 0; i < 8; ++i) labels.push_back({300.0 + 2 * i, 200.0 + (i % 3), 5, 60, 10});
  const std::vector<LabelSpot> spots = place_labels(labels, kPlot);
  expect_readable(labels, spots, kPlot);
  // A label beside one mark of this pile would be beside all of them: each has a leader.
  for (size_t i = 0; i < spots.size(); ++i) EXPECT_TRUE(spots[i].leader) << i;
  EXPECT_EQ(numbered(spots), 0) << "the plot has room for all eight";
}

TEST(LabelLayout, LabelsStayInsideThePlot) {
  // A point at the right edge and one at the top-left corner.
  const std::vector<LabelSpot> spots =
      place_labels({{598, 200, 3, 50, 10}, {2, 2, 3, 50, 10}}, kPlot);
  EXPECT_TRUE(inside(spots[0].box, kPlot));
  EXPECT_LT(spots[0].box.x, 598);  // to the left of its point
  EXPECT_TRUE(inside(spots[1].box, kPlot));
  EXPECT_GT(spots[1].box.y + spots[1].box.h / 2, 2);  // its middle below its point
}

TEST(LabelLayout, LengthInsideARectangle) {
  const LabelRect r{10, 10, 20, 10};                         // x 10..30, y 10..20
  EXPECT_DOUBLE_EQ(length_inside({0, 15, 40, 15}, r), 20);   // straight across
  EXPECT_DOUBLE_EQ(length_inside({20, 15, 40, 15}, r), 10);  // from inside, out
  EXPECT_DOUBLE_EQ(length_inside({5, 5, 35, 25}, r), 0.0 + std::hypot(10, 10 * 2.0 / 3.0) * 1.5)
      << "the diagonal enters at x 12.5 and leaves at x 27.5";
  EXPECT_DOUBLE_EQ(length_inside({0, 0, 40, 0}, r), 0);     // above
  EXPECT_DOUBLE_EQ(length_inside({0, 10, 40, 10}, r), 0);   // along the top edge only
  EXPECT_DOUBLE_EQ(length_inside({15, 12, 15, 12}, r), 0);  // a point
}

TEST(LabelLayout, LabelsKeepOffTheLinesGiven) {
  // A series' line through the usual place (right of the point, above): the label goes
  // elsewhere, off the line.
  const LabelRequest point{300, 200, 3, 40, 10};
  const LabelSegment line{300, 190, 400, 190};
  const std::vector<LabelSpot> spots = place_labels({point}, kPlot, {line});
  EXPECT_EQ(length_inside(line, spots[0].box), 0.0);
  EXPECT_FALSE(spots[0].leader);
}

TEST(LabelLayout, LeadersCrossNoLabelWhereThereIsRoom) {
  // Four points within 30 px, as a knob's settings of like cost and error are: two labels go
  // out a ring, and their leaders must not run through the labels of the others (a place off
  // every label, mark and leader exists: this check finds it).
  const std::vector<LabelRequest> labels = {
      {328, 201, 3, 60, 10}, {320, 210, 3, 50, 10}, {348, 213, 3, 40, 10}, {329, 202, 3, 40, 10}};
  const std::vector<LabelSpot> spots = place_labels(labels, kPlot);
  expect_readable(labels, spots, kPlot);
  bool any_leader = false;
  for (const LabelSpot& s : spots) any_leader |= s.leader;
  EXPECT_TRUE(any_leader);
}

TEST(LabelLayout, WithoutRoomTheLeastOverlapIsTaken) {
  // A plot barely larger than one label: the second label cannot avoid the first, and is still
  // given a place (inside the plot as far as it goes).
  const LabelRect tiny{0, 0, 70, 30};
  const std::vector<LabelSpot> spots =
      place_labels({{10, 15, 2, 40, 10}, {12, 15, 2, 40, 10}}, tiny);
  ASSERT_EQ(spots.size(), 2u);
  EXPECT_TRUE(inside(spots[0].box, tiny));
  EXPECT_GT(spots[1].box.w, 0);
}

TEST(LabelLayout, SegmentsMeetWhereTheyCross) {
  double x = 0, y = 0;
  EXPECT_TRUE(segments_meet({0, 0, 10, 10}, {0, 10, 10, 0}, &x, &y));  // an X
  EXPECT_DOUBLE_EQ(x, 5);
  EXPECT_DOUBLE_EQ(y, 5);
  EXPECT_FALSE(segments_meet({0, 0, 4, 4}, {0, 10, 10, 0}));       // stops short of it
  EXPECT_TRUE(segments_meet({0, 0, 5, 0}, {5, 0, 5, 8}, &x, &y));  // end on end
  EXPECT_DOUBLE_EQ(x, 5);
  EXPECT_FALSE(segments_meet({0, 0, 10, 0}, {0, 1, 10, 1}));  // parallel
  // One line, overlapping from 6 to 10: where the common part ends along the first.
  EXPECT_TRUE(segments_meet({0, 0, 10, 0}, {6, 0, 20, 0}, &x, &y));
  EXPECT_DOUBLE_EQ(x, 10);
  EXPECT_TRUE(segments_meet({10, 0, 0, 0}, {6, 0, 20, 0}, &x, &y));
  EXPECT_DOUBLE_EQ(x, 6);
  EXPECT_FALSE(segments_meet({0, 0, 10, 0}, {11, 0, 20, 0}));  // one line, apart
  EXPECT_TRUE(segments_meet({3, 0, 3, 0}, {0, 0, 10, 0}));     // a point on it
  EXPECT_FALSE(segments_meet({3, 1, 3, 1}, {0, 0, 10, 0}));    // a point off it
}

// The tradeoff chart of the default scene at 256x256 on lavapipe (before this layout): four
// knobs' settings within 40 x 12 px, two fronts' joins through them, labels 20 to 140 px wide,
// as stb_easy_font measures "scene's own (64 slices)". Every label must be readable and its
// point's, off the joins.
TEST(LabelLayout, AClusterOnTwoFrontsIsReadable) {
  const std::vector<LabelRequest> labels = {
      {480, 436, 5, 20, 10, 12}, {482, 437, 5, 70, 10, 12},  {545, 436, 5, 60, 10, 12},
      {632, 437, 5, 60, 10, 12}, {512, 436, 5, 138, 10, 12}, {488, 436, 3, 40, 10, 12},
      {495, 436, 3, 30, 10, 12}, {502, 436, 3, 40, 10, 12},  {525, 437, 3, 30, 10, 12},
      {512, 436, 3, 30, 10, 12}, {411, 422, 5, 70, 10, 12},  {468, 480, 5, 50, 10, 12},
      {365, 435, 5, 40, 10, 12}, {330, 436, 3, 40, 10, 12},  {372, 422, 5, 60, 10, 12}};
  const std::vector<LabelSegment> joins = {{411, 422, 480, 436}, {480, 436, 545, 436},
                                           {545, 436, 632, 437}, {482, 437, 468, 480},
                                           {372, 422, 411, 422}, {365, 435, 482, 437}};
  const LabelRect plot{93, 40, 677, 487};
  const std::vector<LabelSpot> spots = place_labels(labels, plot, joins);
  expect_readable(labels, spots, plot, joins);
  // The point alone at the right end keeps the usual place: right of its mark, above.
  EXPECT_FALSE(spots[3].leader);
  EXPECT_DOUBLE_EQ(spots[3].box.x, 632 + 5 + kLabelGap);
}

TEST(LabelLayout, AClumpWithoutRoomForItsLabelsGoesByNumber) {
  // Thirty settings piled within 24 x 16 px in a plot with room for 22 of their 80 px labels
  // at most (two a 12 px row, with their clearances: three would take 3 x 80 + 2 x 6 px of the
  // 220): the others must be numbered, and the numbers, readable and their points' too,
  // counted from 1.
  std::vector<LabelRequest> labels;
  for (int i = 0; i < 30; ++i)
    labels.push_back({98.0 + 4 * (i % 6), 62.0 + 4 * (i / 6), 3, 80, 10, 12, 30});
  const LabelRect plot{0, 0, 220, 140};
  const std::vector<LabelSpot> spots = place_labels(labels, plot);
  expect_readable(labels, spots, plot);
  EXPECT_GE(numbered(spots), 30 - 22);
  EXPECT_LT(numbered(spots), 30) << "some labels fit";
  // The labels that matter most (listed first) keep their text.
  EXPECT_EQ(spots[0].number, 0);
}

TEST(LabelLayout, APileWithoutRoomForItsNumbersSharesARange) {
  // Forty settings at one place (every knob's default renders the same image at the same
  // cost): each box out of the first ring hides any further out in its direction from its
  // leader, so at most one box in each of the 16 directions a ring has; the rest must share
  // one range of numbers, which the legend's list spells out.
  std::vector<LabelRequest> labels(40, {300, 200, 3, 60, 10, 12, 30});
  const std::vector<LabelSpot> spots = place_labels(labels, kPlot);
  expect_readable(labels, spots, kPlot);
  int in_range = 0;
  for (const LabelSpot& s : spots) in_range += s.tag_last > s.tag_first;
  EXPECT_GE(in_range, 40 - 16);
}

TEST(LabelLayout, PointsAtOnePlaceEachGetTheirOwnLabel) {
  // Two settings of equal time and error (fp16 and fp32 where nothing saturates), and a third
  // a pixel off: three labels, none over another.
  const std::vector<LabelRequest> labels = {
      {200, 150, 5, 30, 10, 6}, {200, 150, 3, 30, 10, 6}, {201, 150, 3, 30, 10, 6}};
  const std::vector<LabelSpot> spots = place_labels(labels, kPlot);
  expect_readable(labels, spots, kPlot);
  EXPECT_EQ(numbered(spots), 0);
}

TEST(LabelLayout, TheLayoutIsDeterministic) {
  std::vector<LabelRequest> labels;
  for (int i = 0; i < 20; ++i)
    labels.push_back(
        {150.0 + 7 * (i % 5), 120.0 + 5 * (i / 5), 3.0 + 2 * (i % 2), 40.0 + i, 10, 12});
  const std::vector<LabelSpot> a = place_labels(labels, kPlot), b = place_labels(labels, kPlot);
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].box.x, b[i].box.x);
    EXPECT_EQ(a[i].box.y, b[i].box.y);
    EXPECT_EQ(a[i].number, b[i].number);
  }
  expect_readable(labels, a, kPlot);
}

}  // namespace
}  // namespace tessera
