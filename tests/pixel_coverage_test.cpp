// core/pixel_coverage.h: polygon areas inside a pixel and the analytic anti-aliasing weights,
// against values worked out by hand.
#include <array>
#include <vector>

#include <gtest/gtest.h>

#include "core/pixel_coverage.h"

namespace tessera {
namespace {

using glm::dvec2;

TEST(PixelCoverage, AreaInPixelOfPolygonsWorkedOutByHand) {
  // Half the pixel under its diagonal, either winding.
  EXPECT_DOUBLE_EQ(area_in_pixel({{0, 0}, {1, 0}, {0, 1}}), 0.5);
  EXPECT_DOUBLE_EQ(area_in_pixel({{0, 0}, {0, 1}, {1, 0}}), 0.5);
  // A triangle holding the whole pixel: x + y <= 2 everywhere in it.
  EXPECT_DOUBLE_EQ(area_in_pixel({{0, 0}, {2, 0}, {0, 2}}), 1.0);
  // A vertical edge at x = 0.3125 of a large quad: the strip left of it.
  EXPECT_DOUBLE_EQ(area_in_pixel({{-5, -5}, {0.3125, -5}, {0.3125, 6}, {-5, 6}}), 0.3125);
  // A triangle crossing the corner (1, 1): the part inside is the triangle (0.5, 1), (1, 0.5),
  // (1, 1), of area 0.125.
  EXPECT_DOUBLE_EQ(area_in_pixel({{0.5, 1}, {1, 0.5}, {3, 3}}), 0.125);
  // Entirely outside, and degenerate.
  EXPECT_EQ(area_in_pixel({{2, 2}, {3, 2}, {2, 3}}), 0.0);
  EXPECT_EQ(area_in_pixel({{0, 0}, {1, 1}}), 0.0);
}

TEST(PixelCoverage, OutlineCoverageCutsOnlyAlongEdgesBetweenCoveredAndEmptySamples) {
  // A triangle whose edge x = 0.3125 crosses the pixel, the empty sample right of it: the
  // pixel left of the line, 0.3125, as the triangle's own area in the pixel would give.
  const std::vector<dvec2> strip = {{-5, -5}, {0.3125, -5}, {0.3125, 6}};
  EXPECT_DOUBLE_EQ(outline_coverage(strip, {{0.875, 0.5}}, {{0.125, 0.5}}), 0.3125);
  // A small triangle: only the edge y = 0.75, which the empty sample at y = 0.875 lies beyond,
  // cuts; its other edges face no empty sample, so the surface is taken to continue across
  // them and covers the pixel above the line, 0.75, where the triangle itself covers 0.0625.
  const std::vector<dvec2> small = {{0.25, 0.5}, {0.75, 0.75}, {0.25, 0.75}};
  EXPECT_DOUBLE_EQ(outline_coverage(small, {{0.5, 0.875}}, {{0.3, 0.7}}), 0.75);
  // Two empty samples beyond different edges: cut by y <= 0.75 and by the line through
  // (0.25, 0.5) and (0.75, 0.75), y >= 0.375 + x / 2, the empty sample (0.8, 0.2) beyond it
  // (0.2 < 0.775). Between them: the triangle (0, 0.375), (0, 0.75), (0.75, 0.75), of area
  // 0.75 * 0.375 / 2 = 0.140625. Either winding.
  EXPECT_DOUBLE_EQ(outline_coverage(small, {{0.5, 0.875}, {0.8, 0.2}}, {{0.3, 0.7}}), 0.140625);
  EXPECT_DOUBLE_EQ(
      outline_coverage({{0.25, 0.5}, {0.25, 0.75}, {0.75, 0.75}}, {{0.5, 0.875}}, {{0.3, 0.7}}),
      0.75);
  // An edge with a covered sample beyond it is not the surface's end: y = 0.75 does not cut
  // when (0.1, 0.9) is covered (by the surface continuing past the triangle), and with no
  // other edge facing the empty sample there is no outline.
  EXPECT_EQ(outline_coverage(small, {{0.5, 0.875}}, {{0.1, 0.9}}), -1.0);
  // No area, no coverage.
  EXPECT_EQ(outline_coverage({{0, 0}, {1, 1}, {2, 2}}, {{0.5, 0.875}}, {}), 0.0);
}

// Triangles by id for silhouette_coverage, in pixels relative to the pixel, and their
// neighbours across edges 0-1, 1-2, 2-0.
struct TriangleSet {
  std::vector<std::vector<dvec2>> corners;
  std::vector<std::array<uint64_t, 3>> across;
  double coverage(const std::vector<uint64_t>& seen, size_t max_triangles = 24,
                  size_t max_steps = 24) const {
    return silhouette_coverage(
        seen, [&](uint64_t id) { return corners[id]; }, [&](uint64_t id) { return across[id]; },
        max_triangles, max_steps);
  }
};

TEST(PixelCoverage, SilhouetteCoverageAddsTheSliversNoSampleSees) {
  const uint64_t none = kNoNeighbourId;
  // A surface ending at x = 0.75, counter-clockwise on screen: triangle 0 (seen by the
  // samples) covers x <= 0.5 of the rows, triangles 1 and 2 the strip 0.5 <= x <= 0.75
  // between them (a sliver the samples at x = 0.125, 0.375, 0.625, 0.875 might miss), and
  // triangle 3, across 2's outer edge, winds the other way (facing away: beyond the
  // silhouette). The area up to x = 0.75: 0.75, where triangle 0 alone cuts at 0.5.
  TriangleSet s;
  s.corners = {{{-2, -2}, {0.5, -2}, {0.5, 3}, {-2, 3}},  // a quad stands for a triangle pair
               {{0.5, -2}, {0.75, -2}, {0.5, 3}},
               {{0.75, -2}, {0.75, 3}, {0.5, 3}},
               {{0.75, -2}, {0.75, 3}, {2, 3}}};  // clockwise
  s.across = {{none, 1, none}, {none, 2, 0}, {3, none, 1}, {2, none, none}};
  EXPECT_NEAR(s.coverage({0}), 0.75, 1e-12);
  // Seen from a sliver: the same.
  EXPECT_NEAR(s.coverage({1, 0}), 0.75, 1e-12);
  // Without the adjacency the walk stops at triangle 0: its own area.
  TriangleSet alone = s;
  alone.across = {{none, none, none}, {none, none, none}, {none, none, none}, {none, none, none}};
  EXPECT_NEAR(alone.coverage({0}), 0.5, 1e-12);
  // A seen triangle the walk cannot reach (another piece of surface): no coverage, -1.
  EXPECT_EQ(alone.coverage({0, 1}), -1.0);
  // A walk that would list more than the limit: -1.
  EXPECT_EQ(s.coverage({0}, 2), -1.0);
  // Steps: triangle 0 is step 0, 1 step 1, 2 step 2 (3 faces away). Three steps reach the
  // whole strip. Two stop at 1, 0.25 wide at y = -2 narrowing to 0 at y = 3, whose area in the
  // pixel is the mean of 0.25 (3 - y) / 5 over y in [0, 1], 0.125: 0.5 + 0.125. From the
  // sliver 1 (step 0), 0 and 2 are both step 1: two steps reach the whole strip.
  EXPECT_NEAR(s.coverage({0}, 24, 3), 0.75, 1e-12);
  EXPECT_NEAR(s.coverage({0}, 24, 2), 0.625, 1e-12);
  EXPECT_NEAR(s.coverage({1}, 24, 2), 0.75, 1e-12);
  // Triangles outside the pixel add nothing and are not walked across: triangle 1 moved to
  // x >= 1 keeps 2 (inside) from being reached.
  TriangleSet outside = s;
  outside.corners[1] = {{1.0, -2}, {1.25, -2}, {1.0, 3}};
  EXPECT_NEAR(outside.coverage({0}), 0.5, 1e-12);
}

}  // namespace
}  // namespace tessera
