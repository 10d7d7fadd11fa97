// core/pixel_coverage.h: polygon areas inside a pixel and the analytic anti-aliasing weights,
// against values worked out by hand.
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

}  // namespace
}  // namespace tessera
