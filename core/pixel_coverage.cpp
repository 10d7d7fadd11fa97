#include "core/pixel_coverage.h"

#include <algorithm>
#include <cmath>

namespace tessera {

namespace {

// Clips the convex polygon `poly` to the half-plane inside(p) >= 0, inside affine in p
// (one step of Sutherland & Hodgman 1974).
template <typename Inside>
std::vector<glm::dvec2> clip_half_plane(const std::vector<glm::dvec2>& poly, Inside inside) {
  std::vector<glm::dvec2> next;
  for (size_t k = 0; k < poly.size(); ++k) {
    const glm::dvec2 a = poly[k], b = poly[(k + 1) % poly.size()];
    const double da = inside(a), db = inside(b);
    if (da >= 0) next.push_back(a);
    if ((da >= 0) != (db >= 0)) next.push_back(a + (b - a) * (da / (da - db)));
  }
  return next;
}

// Twice the signed area of the polygon (the shoelace formula).
double twice_signed_area(const std::vector<glm::dvec2>& poly) {
  double twice = 0.0;
  for (size_t k = 0; k < poly.size(); ++k) {
    const glm::dvec2 a = poly[k], b = poly[(k + 1) % poly.size()];
    twice += a.x * b.y - a.y * b.x;
  }
  return twice;
}

double cross(glm::dvec2 a, glm::dvec2 b) {
  return a.x * b.y - a.y * b.x;
}

const std::vector<glm::dvec2> kPixel = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};

}  // namespace

double area_in_pixel(std::vector<glm::dvec2> corners) {
  for (int axis = 0; axis < 2; ++axis) {
    corners = clip_half_plane(corners, [axis](glm::dvec2 p) { return p[axis]; });
    corners = clip_half_plane(corners, [axis](glm::dvec2 p) { return 1.0 - p[axis]; });
  }
  return std::clamp(0.5 * std::abs(twice_signed_area(corners)), 0.0, 1.0);
}

double outline_coverage(const std::vector<glm::dvec2>& corners,
                        const std::vector<glm::dvec2>& empty_samples,
                        const std::vector<glm::dvec2>& covered_samples) {
  const double orientation = twice_signed_area(corners);
  if (orientation == 0.0) return 0.0;
  const double sign = orientation > 0 ? 1.0 : -1.0;
  std::vector<glm::dvec2> region = kPixel;
  bool cut = false;
  for (size_t k = 0; k < corners.size(); ++k) {
    const glm::dvec2 a = corners[k], b = corners[(k + 1) % corners.size()];
    const auto inside = [&](glm::dvec2 p) { return sign * cross(b - a, p - a); };
    const bool faces_empty = std::any_of(empty_samples.begin(), empty_samples.end(),
                                         [&](glm::dvec2 s) { return inside(s) <= 0.0; });
    const bool cuts_covered = std::any_of(covered_samples.begin(), covered_samples.end(),
                                          [&](glm::dvec2 s) { return inside(s) < 0.0; });
    if (!faces_empty || cuts_covered) continue;
    region = clip_half_plane(region, inside);
    cut = true;
  }
  if (!cut) return -1.0;
  return std::clamp(0.5 * std::abs(twice_signed_area(region)), 0.0, 1.0);
}

double silhouette_coverage(const std::vector<uint64_t>& seen,
                           const std::function<std::vector<glm::dvec2>(uint64_t)>& polygon,
                           const std::function<std::array<uint64_t, 3>(uint64_t)>& neighbours,
                           size_t max_triangles, size_t max_steps) {
  double facing = 0.0;
  // The area of triangle `id` in the pixel if it winds as `facing` says (0: set it), else 0.
  const auto front_face_area = [&](uint64_t id) {
    const std::vector<glm::dvec2> corners = polygon(id);
    const double twice = twice_signed_area(corners);
    if (facing == 0.0) facing = twice > 0.0 ? 1.0 : -1.0;
    if (twice * facing <= 0.0) return 0.0;
    // One that only touches the pixel along a line has no area in it: left out exactly, not by
    // rounding (as the GPU does).
    glm::dvec2 lo = corners[0], hi = corners[0];
    for (const glm::dvec2& c : corners) lo = glm::min(lo, c), hi = glm::max(hi, c);
    if (hi.x <= 0.0 || hi.y <= 0.0 || lo.x >= 1.0 || lo.y >= 1.0) return 0.0;
    return area_in_pixel(corners);
  };
  std::vector<uint64_t> taken = {*std::min_element(seen.begin(), seen.end())};
  std::vector<size_t> step = {0};  // of each triangle taken in
  double total = front_face_area(taken[0]);
  if (total <= 0.0) return -1.0;
  for (size_t head = 0; head < taken.size(); ++head) {
    if (step[head] + 1 >= max_steps) continue;  // the last step is not walked from
    for (uint64_t across : neighbours(taken[head])) {
      if (across == kNoNeighbourId || std::find(taken.begin(), taken.end(), across) != taken.end())
        continue;
      const double area = front_face_area(across);
      if (area <= 0.0) continue;  // outside the pixel, or past the silhouette
      if (taken.size() == max_triangles) return -1.0;
      taken.push_back(across);
      step.push_back(step[head] + 1);
      total += area;
    }
  }
  for (uint64_t id : seen) {
    if (std::find(taken.begin(), taken.end(), id) == taken.end()) return -1.0;
  }
  return std::clamp(total, 0.0, 1.0);
}

}  // namespace tessera
