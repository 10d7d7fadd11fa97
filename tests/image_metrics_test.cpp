// Image metrics, the image assertions and golden images.
#include <cmath>
#include <cstdlib>
#include <filesystem>

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
