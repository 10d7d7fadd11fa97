#include "core/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/check.h"

namespace tessera {
namespace {

template <typename Image>
void check_same_size(const Image& a, const Image& b, const std::vector<uint8_t>* mask) {
  if (a.width != b.width || a.height != b.height) {
    throw Error("cannot compare a " + std::to_string(a.width) + "x" + std::to_string(a.height) +
                " image with a " + std::to_string(b.width) + "x" + std::to_string(b.height) +
                " one");
  }
  TESSERA_CHECK(a.pixels.size() == size_t(a.width) * a.height);
  TESSERA_CHECK(b.pixels.size() == a.pixels.size());
  TESSERA_CHECK(!mask || mask->size() == a.pixels.size());
}

template <typename Image>
ImageDifference compare(const Image& actual, const Image& expected, double threshold,
                        const std::vector<uint8_t>* mask, double peak, double relative_floor) {
  check_same_size(actual, expected, mask);
  ImageDifference d;
  double sum_squares = 0.0;
  for (size_t i = 0; i < actual.pixels.size(); ++i) {
    if (mask && !(*mask)[i]) continue;
    d.pixels++;
    double pixel_max = 0.0;
    for (int c = 0; c < 3; ++c) {
      const double a = double(actual.pixels[i][c]), e = double(expected.pixels[i][c]);
      const double err = std::abs(a - e);
      sum_squares += err * err;
      pixel_max = std::max(pixel_max, err);
      d.max_relative_error =
          std::max(d.max_relative_error, err / std::max(std::abs(e), relative_floor));
    }
    if (pixel_max > threshold) d.pixels_over++;
    if (pixel_max > d.max_abs_error || d.pixels == 1) {
      d.max_abs_error = pixel_max;
      d.worst_x = uint32_t(i % actual.width);
      d.worst_y = uint32_t(i / actual.width);
      d.worst_actual = glm::vec4(actual.pixels[i]);
      d.worst_expected = glm::vec4(expected.pixels[i]);
    }
  }
  if (d.pixels > 0) {
    d.rmse = std::sqrt(sum_squares / (3.0 * double(d.pixels)));
    d.fraction_over = double(d.pixels_over) / double(d.pixels);
  }
  d.psnr_db =
      d.rmse > 0.0 ? 20.0 * std::log10(peak / d.rmse) : std::numeric_limits<double>::infinity();
  return d;
}

// Black -> blue -> green -> yellow -> red as t goes 0 -> 1 (and red beyond).
glm::u8vec4 ramp(double t) {
  if (t <= 0.0) return {0, 0, 0, 255};
  t = std::min(t, 1.0);
  const glm::dvec3 stops[] = {{0, 0, 0.5}, {0, 0, 1}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}};
  const double s = t * 4.0;
  const int k = std::min(int(s), 3);
  const glm::dvec3 c = glm::mix(stops[k], stops[k + 1], s - k);
  return {uint8_t(c.r * 255 + 0.5), uint8_t(c.g * 255 + 0.5), uint8_t(c.b * 255 + 0.5), 255};
}

template <typename Image>
Image8 difference(const Image& actual, const Image& expected, double full_scale,
                  const std::vector<uint8_t>* mask) {
  check_same_size(actual, expected, mask);
  Image8 out{actual.width, actual.height, std::vector<glm::u8vec4>(actual.pixels.size())};
  for (size_t i = 0; i < actual.pixels.size(); ++i) {
    if (mask && !(*mask)[i]) {
      out.pixels[i] = {96, 96, 96, 255};
      continue;
    }
    double err = 0.0;
    for (int c = 0; c < 3; ++c) {
      err = std::max(err, std::abs(double(actual.pixels[i][c]) - double(expected.pixels[i][c])));
    }
    out.pixels[i] = ramp(err / full_scale);
  }
  return out;
}

}  // namespace

ImageDifference compare_images(const Image8& actual, const Image8& expected, double threshold,
                               const std::vector<uint8_t>* mask) {
  return compare(actual, expected, threshold, mask, 255.0, 1.0);
}

ImageDifference compare_images(const ImageF& actual, const ImageF& expected, double threshold,
                               const std::vector<uint8_t>* mask, double relative_floor) {
  return compare(actual, expected, threshold, mask, 1.0, relative_floor);
}

size_t count_mismatches(const std::vector<uint32_t>& actual,
                        const std::vector<uint32_t>& expected) {
  TESSERA_CHECK(actual.size() == expected.size());
  size_t n = 0;
  for (size_t i = 0; i < actual.size(); ++i) n += actual[i] != expected[i];
  return n;
}

Image8 difference_image(const Image8& actual, const Image8& expected, double full_scale,
                        const std::vector<uint8_t>* mask) {
  return difference(actual, expected, full_scale, mask);
}

Image8 difference_image(const ImageF& actual, const ImageF& expected, double full_scale,
                        const std::vector<uint8_t>* mask) {
  return difference(actual, expected, full_scale, mask);
}

}  // namespace tessera
