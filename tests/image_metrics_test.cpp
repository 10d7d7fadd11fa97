// Image metrics, the image assertions and golden images.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>

#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include "core/check.h"
#include "core/image_metrics.h"
#include "tests/support/image_assertions.h"

namespace tessera {
namespace {

Image8 flat(uint32_t w, uint32_t h, glm::u8vec4 c) {
  return Image8{w, h, std::vector<glm::u8vec4>(size_t(w) * h, c)};
}

TEST(ImageMetrics, ValuesByHand) {
  Image8 a = flat(2, 2, {100, 100, 100, 255});
  Image8 e = a;
  a.at(1, 0).r = 103;  // error 3
  a.at(0, 1).g = 90;   // error 10
  ImageDifference d = compare_images(a, e, 3.0);
  EXPECT_EQ(d.pixels, 4u);
  EXPECT_DOUBLE_EQ(d.max_abs_error, 10.0);
  EXPECT_EQ(d.worst_x, 0u);
  EXPECT_EQ(d.worst_y, 1u);
  EXPECT_DOUBLE_EQ(d.rmse, std::sqrt((9.0 + 100.0) / 12.0));
  EXPECT_DOUBLE_EQ(d.psnr_db, 20.0 * std::log10(255.0 / std::sqrt(109.0 / 12.0)));
  EXPECT_EQ(d.pixels_over, 1u);  // only the error of 10 is above 3
  EXPECT_DOUBLE_EQ(d.fraction_over, 0.25);
  EXPECT_TRUE(std::isinf(compare_images(e, e, 0.0).psnr_db));
  std::vector<uint8_t> mask = {1, 1, 0, 1};
  EXPECT_DOUBLE_EQ(compare_images(a, e, 3.0, &mask).max_abs_error, 3.0);
  EXPECT_EQ(count_mismatches({1, 2, 3}, {1, 5, 3}), 1u);
}

TEST(ImageMetrics, FloatImagesAndRelativeError) {
  ImageF a{1, 2, {glm::vec4(1.0f), glm::vec4(0.0f)}};
  ImageF e{1, 2, {glm::vec4(0.5f), glm::vec4(0.0005f)}};
  ImageDifference d = compare_images(a, e, 0.1, nullptr, 1e-3);
  EXPECT_DOUBLE_EQ(d.max_abs_error, 0.5);
  EXPECT_NEAR(d.max_relative_error, 1.0, 1e-6);  // 0.5 / 0.5; the tiny value uses the floor
  EXPECT_THROW(compare_images(a, ImageF{2, 1, a.pixels}, 0.1), Error);
}

TEST(ImageMetrics, RelativeRadianceErrorByHand) {
  // Mean brightest channel of the truth: (1 + 2 + 0 + 1) / 4 = 1, so the guard is 0.01.
  const ImageF e{
      4,
      1,
      {glm::vec4(1, 1, 1, 1), glm::vec4(2, 2, 2, 1), glm::vec4(0, 0, 0, 1), glm::vec4(1, 0, 0, 1)}};
  const ImageF a{4,
                 1,
                 {glm::vec4(1.1f, 1, 1, 1), glm::vec4(2, 2, 2.5f, 1), glm::vec4(0.001f, 0, 0, 1),
                  glm::vec4(1, 0.5f, 0, 1)}};
  const RadianceError r = radiance_error(a, e);
  EXPECT_EQ(r.pixels, 4u);
  EXPECT_DOUBLE_EQ(r.guard, 0.01);
  // 0.1 / 1; 0.5 / 2; 0.001 / guard; 0.5 / 1 (the dark green channel of a red pixel is
  // measured against the red).
  EXPECT_NEAR(r.mean_relative, (0.1 + 0.25 + 0.1 + 0.5) / 4.0, 1e-6);
  EXPECT_NEAR(r.p99_relative, 0.5, 1e-6);  // rank ceil(3.96) = 4 of 4
  EXPECT_NEAR(r.max_relative, 0.5, 1e-6);
  // Scaling both images (another exposure) changes nothing.
  ImageF a2 = a, e2 = e;
  for (auto& p : a2.pixels) p *= 8.0f;
  for (auto& p : e2.pixels) p *= 8.0f;
  EXPECT_NEAR(radiance_error(a2, e2).mean_relative, r.mean_relative, 1e-6);

  // 99th percentile by nearest rank: of 100 pixels, one outlier does not reach it, two do.
  ImageF truth{100, 1, std::vector<glm::vec4>(100, glm::vec4(1.0f))};
  ImageF test = truth;
  for (auto& p : test.pixels) p = glm::vec4(1.1f, 1.0f, 1.0f, 1.0f);
  test.pixels[7] = glm::vec4(4.0f, 1.0f, 1.0f, 1.0f);
  EXPECT_NEAR(radiance_error(test, truth).p99_relative, 0.1, 1e-6);
  EXPECT_NEAR(radiance_error(test, truth).max_relative, 3.0, 1e-6);
  test.pixels[8] = test.pixels[7];
  EXPECT_NEAR(radiance_error(test, truth).p99_relative, 3.0, 1e-6);
}

// Ownership of a w x h image at n x n samples per pixel: object 5 where inside(x, y) holds at
// the sample position, the background elsewhere.
template <typename Inside>
Ownership sampled(uint32_t w, uint32_t h, uint32_t n, Inside inside) {
  std::vector<uint32_t> ids;
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x)
      for (uint32_t j = 0; j < n; ++j)
        for (uint32_t i = 0; i < n; ++i)
          ids.push_back(inside(x + (i + 0.5) / n, y + (j + 0.5) / n) ? 5u : kNoObject);
  return make_ownership(w, h, n * n, ids);
}

TEST(ImageMetrics, SilhouetteErrorOfShiftedEdgesIsTheShift) {
  const uint32_t w = 16, h = 12;
  auto right_of = [](double edge) { return [edge](double x, double) { return x >= edge; }; };
  const Ownership truth = sampled(w, h, 1, right_of(6.0));
  for (double shift : {1.0, 2.0, -3.0}) {
    const SilhouetteError e = silhouette_error(sampled(w, h, 1, right_of(6.0 + shift)), truth);
    EXPECT_DOUBLE_EQ(e.mean_px, std::abs(shift));
    EXPECT_DOUBLE_EQ(e.length_px, h);
    EXPECT_DOUBLE_EQ(e.area_px, std::abs(shift) * h);
    EXPECT_EQ(e.worst_object, 5u);
    EXPECT_DOUBLE_EQ(e.worst_object_px, std::abs(shift));
  }
  // Horizontal edges, and a truth at 4 x 4 samples against an image at 1: half a pixel.
  auto below = [](double edge) { return [edge](double, double y) { return y >= edge; }; };
  EXPECT_DOUBLE_EQ(
      silhouette_error(sampled(w, h, 1, below(5.0)), sampled(w, h, 1, below(4.0))).mean_px, 1.0);
  const Ownership fine = sampled(w, h, 4, right_of(6.5));
  EXPECT_DOUBLE_EQ(silhouette_error(sampled(w, h, 1, right_of(6.0)), fine).mean_px, 0.5);
  EXPECT_DOUBLE_EQ(silhouette_error(fine, fine).mean_px, 0.0);
  EXPECT_EQ(silhouette_error(fine, fine).worst_object, kNoObject);
}

TEST(ImageMetrics, SilhouetteLengthOfADiskAndOfA45DegreeEdge) {
  // A disk of radius 9 px at 16 x 16 samples: its outline, 2 pi 9 px, within 2 %.
  const Ownership disk = sampled(32, 32, 16, [](double x, double y) {
    return (x - 15.3) * (x - 15.3) + (y - 16.2) * (y - 16.2) <= 81.0;
  });
  EXPECT_NEAR(silhouette_error(disk, disk).length_px, 2.0 * 3.14159265 * 9.0, 0.02 * 56.5);
  // The region x + y >= 20.25, x >= 2, y >= 2 of a 24 x 24 image: its diagonal runs from
  // (2, 18.25) to (18.25, 2). A pixel's sampled coverage of it depends on x + y only, so the
  // differences in x and y are equal and the estimate exact but where it meets the sides.
  const Ownership diagonal =
      sampled(24, 24, 16, [](double x, double y) { return x + y >= 20.25 && x >= 2 && y >= 2; });
  const double expected_diagonal = (20.25 - 4.0) * std::sqrt(2.0);
  const SilhouetteError d = silhouette_error(diagonal, diagonal);
  // Also counted: the two straight sides along x = 2 and y = 2, from the line to the border.
  const double sides = 2.0 * (24.0 - (20.25 - 2.0));
  EXPECT_NEAR(d.length_px, expected_diagonal + sides, 0.02 * (expected_diagonal + sides));
}

TEST(ImageMetrics, ErrorAgainstTruthBundlesTheMetrics) {
  const ImageF hdr{2, 1, {glm::vec4(1.0f), glm::vec4(0.5f)}};
  const ImageF truth_hdr{2, 1, {glm::vec4(1.0f), glm::vec4(1.0f)}};
  const Image8 ldr = flat(2, 1, {100, 100, 100, 255});
  Image8 truth_ldr = ldr;
  truth_ldr.at(1, 0) = {110, 100, 100, 255};
  const TruthError e = error_against_truth(hdr, ldr, truth_hdr, truth_ldr);
  EXPECT_NEAR(e.mean_relative, 0.25, 1e-6);
  EXPECT_NEAR(e.p99_relative, 0.5, 1e-6);
  EXPECT_DOUBLE_EQ(e.psnr_db, compare_images(ldr, truth_ldr, 0.0).psnr_db);
  EXPECT_TRUE(std::isnan(e.silhouette_px));
  const Ownership a = make_ownership(2, 1, 1, {kNoObject, 1});
  const Ownership b = make_ownership(2, 1, 1, {1, 1});
  EXPECT_DOUBLE_EQ(error_against_truth(hdr, ldr, truth_hdr, truth_ldr, &a, &b).silhouette_px,
                   std::numeric_limits<double>::infinity());  // no outline in the truth
  EXPECT_THROW(make_ownership(2, 1, 1, {1}), Error);
  EXPECT_THROW(make_ownership(2, 1, 0, {}), Error);
  EXPECT_THROW(silhouette_error(a, make_ownership(1, 2, 1, {1, 1})), Error);
}

TEST(ImageMetrics, DifferenceImageIsFalseColour) {
  Image8 a = flat(3, 1, {0, 0, 0, 255});
  Image8 e = a;
  a.at(1, 0).r = 2;
  a.at(2, 0).r = 200;
  Image8 d = difference_image(a, e, 4.0);
  EXPECT_EQ(d.at(0, 0), glm::u8vec4(0, 0, 0, 255));     // equal: black
  EXPECT_EQ(d.at(2, 0), glm::u8vec4(255, 0, 0, 255));   // beyond full scale: red
  EXPECT_GT(int(d.at(1, 0).g) + int(d.at(1, 0).b), 0);  // in between: a cold colour
}

TEST(ImageAssertions, PassesWithinToleranceAndExplainsFailures) {
  Image8 expected = flat(8, 8, {10, 20, 30, 255});
  Image8 actual = expected;
  actual.at(3, 4).b = 32;
  EXPECT_IMAGES_NEAR(actual, expected, 2);
  actual.at(5, 6).r = 200;
  EXPECT_NONFATAL_FAILURE(EXPECT_IMAGES_NEAR(actual, expected, 2), "max error 190 at (5, 6)");
  // The failure wrote the three images for people to look at.
  EXPECT_TRUE(std::filesystem::exists(testing::test_output_path("actual_actual.png")));
  EXPECT_TRUE(std::filesystem::exists(testing::test_output_path("actual_expected.png")));
  EXPECT_TRUE(std::filesystem::exists(testing::test_output_path("actual_difference.png")));
  // A fraction of pixels may be allowed over the tolerance, below a hard maximum.
  EXPECT_IMAGES_NEAR(actual, expected, testing::ImageTolerance(2, 0.02, 255));
}

TEST(GoldenImages, CreateCompareAndDetectChange) {
  const std::string golden = testing::test_output_path("golden/flat.png");
  std::filesystem::remove(golden);
  Image8 image = flat(4, 4, {1, 2, 3, 255});
  EXPECT_NONFATAL_FAILURE(EXPECT_MATCHES_GOLDEN(image, golden, 0), "TESSERA_UPDATE_GOLDENS=1");
  setenv("TESSERA_UPDATE_GOLDENS", "1", 1);
  EXPECT_MATCHES_GOLDEN(image, golden, 0);
  unsetenv("TESSERA_UPDATE_GOLDENS");
  ASSERT_TRUE(std::filesystem::exists(golden));
  EXPECT_MATCHES_GOLDEN(image, golden, 0);
  image.at(2, 2).g = 50;
  EXPECT_NONFATAL_FAILURE(EXPECT_MATCHES_GOLDEN(image, golden, 0), "max error 48 at (2, 2)");
}

}  // namespace
}  // namespace tessera
