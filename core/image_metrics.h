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

// --- Error against a ground truth (docs/accuracy.md, "Error metrics") ----------------------

/// Relative error of linear radiance, per pixel: max_c |a_c - e_c| / max(max_c |e_c|, guard),
/// over the RGB channels, with guard = guard_fraction * (mean over the compared pixels of
/// max_c |e_c|). The denominator is the pixel's brightest channel, so a saturated colour's
/// dark channels do not explode; the guard keeps pixels far darker than the image (a black
/// background beside an edge) from dividing by ~0, at a level that scales with the image, so
/// the figure does not depend on exposure.
struct RadianceError {
  size_t pixels = 0;
  double guard = 0.0;          // the denominator floor used, in the images' radiance units
  double mean_relative = 0.0;  // mean of the per-pixel relative errors
  double p99_relative = 0.0;   // 99th percentile, nearest rank: the ceil(0.99 n)-th smallest
  double max_relative = 0.0;
};

/// Compares two float images of the same size (throws Error otherwise). `mask` as for
/// compare_images. guard_fraction > 0. An all-black `expected` uses a guard of 1e-30 (so
/// any non-zero error is large, any zero one 0).
RadianceError radiance_error(const ImageF& actual, const ImageF& expected,
                             const std::vector<uint8_t>* mask = nullptr,
                             double guard_fraction = 0.01);

/// Object id of pixels (or samples) no object covers.
constexpr uint32_t kNoObject = 0xFFFFFFFFu;

/// How much of each pixel each object covers, counted in samples: pixel i's shares are
/// shares[first[i]] .. shares[first[i + 1] - 1], sorted by object, each with samples > 0, their
/// samples summing to `samples` (the background is the object kNoObject). Objects are any ids
/// the caller chooses, e.g. ObjectNumbering slots (object_ids).
struct OwnerShare {
  uint32_t object;
  uint32_t samples;
};
struct Ownership {
  uint32_t width = 0, height = 0;
  uint32_t samples = 1;       // per pixel
  std::vector<size_t> first;  // width * height + 1 offsets into `shares`
  std::vector<OwnerShare> shares;
};

/// Builds an Ownership from the object of every sample: `objects` holds width * height *
/// samples_per_pixel ids, pixel after pixel in row-major order, each pixel's samples together
/// (throws Error if the size does not match or samples_per_pixel is 0).
Ownership make_ownership(uint32_t width, uint32_t height, uint32_t samples_per_pixel,
                         const std::vector<uint32_t>& objects);

/// Silhouette error, in pixels: for each object o (the background included), A_o = sum over
/// pixels of |c_o(actual) - c_o(expected)|, c_o the fraction of the pixel o covers, and P_o =
/// the length of o's outline in `expected`: the sum over pixel corners of |grad c_o|, the
/// gradient from the four pixels around the corner (x: the mean of the two differences across
/// it, y likewise; pixels beyond the border repeat the border's, and corners on the border
/// weigh 1/2). An outline moved sideways by d pixels changes A_o by d per pixel of length, so
/// A_o / P_o is the mean displacement of o's outline. P_o is exact for hard axis-aligned edges
/// and for box-filtered straight edges at 0 and 45 degrees, and within about 1 % for a
/// supersampled disk; hard edges at other angles count long (a staircase), so `expected`
/// should be the supersampled truth.
struct SilhouetteError {
  double mean_px = 0.0;        // sum_o A_o / sum_o P_o (0 if both are 0; inf if only P is)
  double length_px = 0.0;      // 1/2 sum_o P_o: every outline borders two objects
  double area_px = 0.0;        // 1/2 sum_o A_o: pixels' worth of coverage that changed object
  double worst_object_px = 0;  // largest A_o / P_o over objects other than kNoObject with P_o > 0
  uint32_t worst_object = kNoObject;
};

/// Both Ownerships must have the same size (throws Error otherwise); their sample counts may
/// differ.
SilhouetteError silhouette_error(const Ownership& actual, const Ownership& expected);

/// The pixels an outline crosses: 1 where `o` has two or more shares (two objects, or an object
/// and the background, each hold some of the pixel's samples), else 0; one entry per pixel, a
/// mask for compare_images and radiance_error. On a supersampled truth these are the pixels
/// whose value depends on how the renderer resolves edges (docs/tradeoffs.md, "Anti-aliasing").
std::vector<uint8_t> outline_pixels(const Ownership& o);

/// The errors issue 12's trade-off charts plot, of one image against the ground truth.
/// PSNR is that of the 8-bit images (compare_images); silhouette_px is the mean of
/// silhouette_error, or NaN when no ownership is given.
struct TruthError {
  double mean_relative = 0.0, p99_relative = 0.0;
  double psnr_db = 0.0;
  double silhouette_px = 0.0;
};
TruthError error_against_truth(const ImageF& hdr, const Image8& ldr, const ImageF& truth_hdr,
                               const Image8& truth_ldr, const Ownership* ownership = nullptr,
                               const Ownership* truth_ownership = nullptr);

/// False-colour image of the per-pixel largest channel error: black where equal, then blue,
/// green, yellow and red as the error grows to `full_scale` and beyond; masked-out pixels grey.
Image8 difference_image(const Image8& actual, const Image8& expected, double full_scale,
                        const std::vector<uint8_t>* mask = nullptr);
Image8 difference_image(const ImageF& actual, const ImageF& expected, double full_scale,
                        const std::vector<uint8_t>* mask = nullptr);

}  // namespace tessera
