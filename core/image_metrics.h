#pragma once
// Image comparison: error metrics, ownership mismatches and false-colour difference images,
// for image tests written with Tessera (no Vulkan, no test framework).

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/image.h"

namespace tessera {

struct ImageDifference {
  size_t pixels = 0;                  // pixels compared
  double max_abs_error = 0.0;         // largest |actual - expected| over the RGB channels
  double rmse = 0.0;                  // root mean square error over the RGB channels
  double psnr_db = 0.0;               // 20 log10(peak / rmse); +infinity for identical images
  size_t pixels_over = 0;             // pixels with a channel error above `threshold`
  double fraction_over = 0.0;         // pixels_over / pixels
  double max_relative_error = 0.0;    // largest |a - e| / max(|e|, relative_floor) (float images)
  uint32_t worst_x = 0, worst_y = 0;  // where max_abs_error is reached (first such pixel)
  glm::vec4 worst_actual{0.0f}, worst_expected{0.0f};
};

/// Compares the RGB channels of two 8-bit images of the same size (throws Error otherwise).
/// Errors are in levels (0..255); `threshold` too; PSNR uses a peak of 255. `mask`, if given,
/// has one entry per pixel and only pixels whose entry is non-zero are compared.
ImageDifference compare_images(const Image8& actual, const Image8& expected, double threshold,
                               const std::vector<uint8_t>* mask = nullptr);

/// The same for float images; PSNR uses a peak of 1. `relative_floor` keeps the relative error
/// of values near zero from exploding.
ImageDifference compare_images(const ImageF& actual, const ImageF& expected, double threshold,
                               const std::vector<uint8_t>* mask = nullptr,
                               double relative_floor = 1e-3);

/// Number of positions where two id images (one id per pixel) differ. Sizes must match.
size_t count_mismatches(const std::vector<uint32_t>& actual, const std::vector<uint32_t>& expected);

/// False-colour image of the per-pixel largest channel error: black where equal, then blue,
/// green, yellow and red as the error grows to `full_scale` and beyond; masked-out pixels grey.
Image8 difference_image(const Image8& actual, const Image8& expected, double full_scale,
                        const std::vector<uint8_t>* mask = nullptr);
Image8 difference_image(const ImageF& actual, const ImageF& expected, double full_scale,
                        const std::vector<uint8_t>* mask = nullptr);

}  // namespace tessera
