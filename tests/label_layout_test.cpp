// place_labels (host/label_layout.h): chart labels that overlap neither each other nor the
// points' marks, inside the plot, next to their points where there is room.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "host/label_layout.h"

namespace tessera {
namespace {

bool overlaps(const LabelRect& a, const LabelRect& b) {
  return a.x < b.x + b.w && b.x < a.x + a.w && a.y < b.y + b.h && b.y < a.y + a.h;
}

bool inside(const LabelRect& r, const LabelRect& bounds) {
  return r.x >= bounds.x && r.y >= bounds.y && r.x + r.w <= bounds.x + bounds.w &&
         r.y + r.h <= bounds.y + bounds.h;
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
  ASSERT_EQ(spots.size(), labels.size());
  for (size_t i = 0; i < spots.size(); ++i) {
    EXPECT_TRUE(inside(spots[i].box, kPlot)) << i;
    for (size_t j = 0; j < labels.size(); ++j) {
      const LabelRect mark{labels[j].x - 5, labels[j].y - 5, 10, 10};
      EXPECT_FALSE(overlaps(spots[i].box, mark)) << "label " << i << ", mark " << j;
      if (j < i) {
        EXPECT_FALSE(overlaps(spots[i].box, spots[j].box)) << i << " and " << j;
      }
    }
  }
  // The first keeps the usual place; some of the later ones had to go further out.
  EXPECT_FALSE(spots[0].leader);
  bool any_leader = false;
  for (const LabelSpot& s : spots) any_leader |= s.leader;
  EXPECT_TRUE(any_leader);
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
  bool any_leader = false;
  for (size_t i = 0; i < spots.size(); ++i) {
    for (size_t j = 0; j < labels.size(); ++j) {
      const LabelRect mark{labels[j].x - 3, labels[j].y - 3, 6, 6};
      EXPECT_FALSE(overlaps(spots[i].box, mark)) << "label " << i << ", mark " << j;
      if (j < i) {
        EXPECT_FALSE(overlaps(spots[i].box, spots[j].box)) << i << " and " << j;
      }
    }
    if (!spots[i].leader) continue;
    any_leader = true;
    const LabelSegment leader = leader_line(labels[i], spots[i].box);
    for (size_t j = 0; j < spots.size(); ++j) {
      if (j != i) {
        EXPECT_EQ(length_inside(leader, spots[j].box), 0.0) << "leader " << i << ", label " << j;
      }
    }
  }
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

}  // namespace
}  // namespace tessera
