#pragma once
// GoogleTest assertions for image tests written with Tessera.
//
//   EXPECT_IMAGES_NEAR(actual, expected, tolerance);
//   EXPECT_MATCHES_GOLDEN(actual, "tests/golden/my_scene.png", tolerance);
//
// On failure the message gives the metrics and the worst pixel, and actual, expected and a
// false-colour difference image are written to test_output/<Suite>.<Test>/ (relative to the
// working directory), named after the `actual` expression, so a person can look.
//
// Golden images: EXPECT_MATCHES_GOLDEN compares with a PNG stored with the test. Run the test
// with TESSERA_UPDATE_GOLDENS=1 to write (or overwrite) the golden files from the actual
// images instead; review the new PNGs before committing them. A missing golden fails with a
// message saying so.

#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/image.h"
#include "core/image_metrics.h"

namespace tessera::testing {

/// Allowed difference, per pixel as the largest channel error (levels for 8-bit images, the
/// value's unit for float images). Converts from a number: `EXPECT_IMAGES_NEAR(a, b, 1)`.
struct ImageTolerance {
  double max_error = 0.0;              // a pixel is "over" above this
  double allowed_fraction_over = 0.0;  // fraction of pixels allowed over max_error
  double hard_max_error = -1.0;        // no pixel may exceed this (< 0: max_error if no fraction)
  ImageTolerance(double max = 0.0) : max_error(max) {}  // NOLINT: implicit on purpose
  ImageTolerance(double max, double fraction, double hard)
      : max_error(max), allowed_fraction_over(fraction), hard_max_error(hard) {}
};

::testing::AssertionResult ImagesNear(const char* actual_expr, const char* expected_expr,
                                      const char* tolerance_expr, const Image8& actual,
                                      const Image8& expected, const ImageTolerance& tolerance);
::testing::AssertionResult ImagesNear(const char* actual_expr, const char* expected_expr,
                                      const char* tolerance_expr, const ImageF& actual,
                                      const ImageF& expected, const ImageTolerance& tolerance);
::testing::AssertionResult MatchesGolden(const char* actual_expr, const char* path_expr,
                                         const char* tolerance_expr, const Image8& actual,
                                         const std::string& golden_path,
                                         const ImageTolerance& tolerance);

/// True if `a` and `b` have the same size and every channel of every pixel the same bits (so
/// +0 and -0, or two NaNs, are told apart): what determinism and bit-identity tests assert.
bool same_bits(const ImageF& a, const ImageF& b);

/// test_output/<Suite>.<Test>/<name>, its folder created.
std::string test_output_path(const std::string& name);

}  // namespace tessera::testing

#define EXPECT_IMAGES_NEAR(actual, expected, tolerance) \
  EXPECT_PRED_FORMAT3(::tessera::testing::ImagesNear, actual, expected, tolerance)
#define ASSERT_IMAGES_NEAR(actual, expected, tolerance) \
  ASSERT_PRED_FORMAT3(::tessera::testing::ImagesNear, actual, expected, tolerance)
#define EXPECT_MATCHES_GOLDEN(actual, golden_path, tolerance) \
  EXPECT_PRED_FORMAT3(::tessera::testing::MatchesGolden, actual, golden_path, tolerance)
