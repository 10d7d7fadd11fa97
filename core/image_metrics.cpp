#include "core/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
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

// The fraction of pixel i that `object` covers.
double share_of(const Ownership& o, size_t i, uint32_t object) {
  const auto begin = o.shares.begin() + ptrdiff_t(o.first[i]),
             end = o.shares.begin() + ptrdiff_t(o.first[i + 1]);
  auto it = std::lower_bound(begin, end, object,
                             [](const OwnerShare& s, uint32_t v) { return s.object < v; });
  return it != end && it->object == object ? double(it->samples) / double(o.samples) : 0.0;
}

// Appends the objects of pixel i not yet in `out` (a handful at most: a pixel meets few
// outlines).
void add_objects(const Ownership& o, size_t i, std::vector<uint32_t>& out) {
  for (size_t k = o.first[i]; k < o.first[i + 1]; ++k) {
    if (std::find(out.begin(), out.end(), o.shares[k].object) == out.end())
      out.push_back(o.shares[k].object);
  }
}

bool single_object(const Ownership& o, size_t i, uint32_t object) {
  return o.first[i + 1] - o.first[i] == 1 && o.shares[o.first[i]].object == object;
}

void check_ownership(const Ownership& o) {
  TESSERA_CHECK(o.samples > 0);
  TESSERA_CHECK(o.first.size() == size_t(o.width) * o.height + 1);
  TESSERA_CHECK(o.first.back() == o.shares.size());
}

}  // namespace

RadianceError radiance_error(const ImageF& actual, const ImageF& expected,
                             const std::vector<uint8_t>* mask, double guard_fraction) {
  check_same_size(actual, expected, mask);
  TESSERA_CHECK(guard_fraction > 0.0);
  auto brightest = [](glm::vec4 v) {
    return std::max({std::abs(double(v.r)), std::abs(double(v.g)), std::abs(double(v.b))});
  };
  RadianceError r;
  double sum = 0.0;
  for (size_t i = 0; i < expected.pixels.size(); ++i) {
    if (mask && !(*mask)[i]) continue;
    r.pixels++;
    sum += brightest(expected.pixels[i]);
  }
  if (r.pixels == 0) return r;
  // 1e-30: an all-black truth still divides by something positive.
  r.guard = std::max(guard_fraction * sum / double(r.pixels), 1e-30);
  std::vector<double> errors;
  errors.reserve(r.pixels);
  for (size_t i = 0; i < expected.pixels.size(); ++i) {
    if (mask && !(*mask)[i]) continue;
    const glm::vec4 a = actual.pixels[i], e = expected.pixels[i];
    double err = 0.0;
    for (int c = 0; c < 3; ++c) err = std::max(err, std::abs(double(a[c]) - double(e[c])));
    errors.push_back(err / std::max(brightest(e), r.guard));
  }
  double total = 0.0;
  for (double e : errors) total += e;
  r.mean_relative = total / double(errors.size());
  const size_t rank = size_t(std::ceil(0.99 * double(errors.size())));  // 1-based, >= 1
  std::nth_element(errors.begin(), errors.begin() + ptrdiff_t(rank - 1), errors.end());
  r.p99_relative = errors[rank - 1];
  r.max_relative = *std::max_element(errors.begin() + ptrdiff_t(rank - 1), errors.end());
  return r;
}

Ownership make_ownership(uint32_t width, uint32_t height, uint32_t samples_per_pixel,
                         const std::vector<uint32_t>& objects) {
  const size_t pixels = size_t(width) * height;
  if (samples_per_pixel == 0 || objects.size() != pixels * samples_per_pixel) {
    throw Error("an ownership image of " + std::to_string(width) + "x" + std::to_string(height) +
                " pixels at " + std::to_string(samples_per_pixel) + " samples needs " +
                std::to_string(pixels * samples_per_pixel) + " object ids, not " +
                std::to_string(objects.size()));
  }
  Ownership o{width, height, samples_per_pixel, {}, {}};
  o.first.reserve(pixels + 1);
  std::vector<uint32_t> sorted(samples_per_pixel);
  for (size_t i = 0; i < pixels; ++i) {
    o.first.push_back(o.shares.size());
    const auto begin = objects.begin() + ptrdiff_t(i * samples_per_pixel);
    std::copy(begin, begin + samples_per_pixel, sorted.begin());
    std::sort(sorted.begin(), sorted.end());
    for (uint32_t id : sorted) {
      if (o.shares.size() > o.first.back() && o.shares.back().object == id)
        o.shares.back().samples++;
      else
        o.shares.push_back({id, 1});
    }
  }
  o.first.push_back(o.shares.size());
  return o;
}

std::vector<uint8_t> outline_pixels(const Ownership& o) {
  check_ownership(o);
  std::vector<uint8_t> mask(size_t(o.width) * o.height);
  for (size_t i = 0; i < mask.size(); ++i) mask[i] = o.first[i + 1] - o.first[i] > 1 ? 1 : 0;
  return mask;
}

SilhouetteError silhouette_error(const Ownership& actual, const Ownership& expected) {
  if (actual.width != expected.width || actual.height != expected.height) {
    throw Error("cannot compare the silhouettes of a " + std::to_string(actual.width) + "x" +
                std::to_string(actual.height) + " image with a " + std::to_string(expected.width) +
                "x" + std::to_string(expected.height) + " one");
  }
  check_ownership(actual);
  check_ownership(expected);
  struct Sums {
    double area = 0.0, perimeter = 0.0;
  };
  std::map<uint32_t, Sums> per_object;
  std::vector<uint32_t> objects;
  const int64_t w = expected.width, h = expected.height;
  auto pixel = [&](int64_t x, int64_t y) {
    return size_t(std::clamp<int64_t>(y, 0, h - 1) * w + std::clamp<int64_t>(x, 0, w - 1));
  };
  // Outline length: |gradient| of each object's coverage at every pixel corner, from the four
  // pixels around it (those beyond the border repeat the border's); corners on the border
  // weigh 1/2 (1/4 at the image's corners), so a straight hard edge of n pixels counts n.
  for (int64_t y = -1; y < h; ++y) {
    for (int64_t x = -1; x < w; ++x) {
      const size_t p00 = pixel(x, y), p10 = pixel(x + 1, y), p01 = pixel(x, y + 1),
                   p11 = pixel(x + 1, y + 1);
      const uint32_t here = expected.shares[expected.first[p00]].object;
      if (single_object(expected, p00, here) && single_object(expected, p10, here) &&
          single_object(expected, p01, here) && single_object(expected, p11, here))
        continue;
      const double weight =
          (x == -1 || x == w - 1 ? 0.5 : 1.0) * (y == -1 || y == h - 1 ? 0.5 : 1.0);
      objects.clear();
      for (size_t k : {p00, p10, p01, p11}) add_objects(expected, k, objects);
      for (uint32_t o : objects) {
        const double c00 = share_of(expected, p00, o), c10 = share_of(expected, p10, o),
                     c01 = share_of(expected, p01, o), c11 = share_of(expected, p11, o);
        const double gx = 0.5 * ((c10 - c00) + (c11 - c01)), gy = 0.5 * ((c01 - c00) + (c11 - c10));
        per_object[o].perimeter += weight * std::sqrt(gx * gx + gy * gy);
      }
    }
  }
  for (size_t i = 0; i < expected.first.size() - 1; ++i) {
    const uint32_t here = expected.shares[expected.first[i]].object;
    if (single_object(actual, i, here) && single_object(expected, i, here)) continue;
    objects.clear();
    add_objects(actual, i, objects);
    add_objects(expected, i, objects);
    for (uint32_t o : objects)
      per_object[o].area += std::abs(share_of(actual, i, o) - share_of(expected, i, o));
  }
  SilhouetteError e;
  for (const auto& [object, sums] : per_object) {
    e.area_px += sums.area / 2.0;
    e.length_px += sums.perimeter / 2.0;
    if (object != kNoObject && sums.perimeter > 0.0 &&
        sums.area / sums.perimeter > e.worst_object_px) {
      e.worst_object_px = sums.area / sums.perimeter;
      e.worst_object = object;
    }
  }
  e.mean_px = e.length_px > 0.0 ? e.area_px / e.length_px
              : e.area_px > 0.0 ? std::numeric_limits<double>::infinity()
                                : 0.0;
  return e;
}

TruthError error_against_truth(const ImageF& hdr, const Image8& ldr, const ImageF& truth_hdr,
                               const Image8& truth_ldr, const Ownership* ownership,
                               const Ownership* truth_ownership) {
  const RadianceError r = radiance_error(hdr, truth_hdr);
  TruthError e;
  e.mean_relative = r.mean_relative;
  e.p99_relative = r.p99_relative;
  e.psnr_db = compare_images(ldr, truth_ldr, 0.0).psnr_db;
  e.silhouette_px = ownership && truth_ownership
                        ? silhouette_error(*ownership, *truth_ownership).mean_px
                        : std::numeric_limits<double>::quiet_NaN();
  return e;
}

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
