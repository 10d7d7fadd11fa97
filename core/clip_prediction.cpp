#include "core/clip_prediction.h"

#include <algorithm>
#include <cmath>

namespace tessera {

MeshBox mesh_box(const Mesh& mesh) {
  MeshBox box;
  if (mesh.positions.empty()) return box;
  box.min = box.max = mesh.positions.front();
  for (const glm::vec3& p : mesh.positions) {
    box.min = glm::min(box.min, p);
    box.max = glm::max(box.max, p);
  }
  return box;
}

bool may_need_clipping(const MeshBox& box, const glm::dmat4& clip_from_world,
                       const glm::dmat4& world_from_object, double near_plane,
                       glm::dvec2 guard_band) {
  if (box.min.x > box.max.x || box.min.y > box.max.y || box.min.z > box.max.z) return false;
  // The largest magnitude of each object coordinate in the box, and with it the largest sum of
  // the magnitudes of the terms of each clip coordinate at any point of the box: the GPU's
  // rounding is relative to these sums, not to the (possibly cancelling) results.
  const glm::dvec3 extent = glm::max(glm::abs(glm::dvec3(box.min)), glm::abs(glm::dvec3(box.max)));
  glm::dmat4 abs_world(0.0), abs_clip(0.0);
  for (int c = 0; c < 4; ++c) {
    abs_world[c] = glm::abs(world_from_object[c]);
    abs_clip[c] = glm::abs(clip_from_world[c]);
  }
  const glm::dvec4 magnitude = abs_clip * (abs_world * glm::dvec4(extent, 1.0));
  const glm::dmat4 clip_from_object = clip_from_world * world_from_object;
  constexpr double kMargin = 1e-5;
  const double near_margin = kMargin * (magnitude.w + std::abs(near_plane));
  const double x_margin = kMargin * (guard_band.x * magnitude.w + magnitude.x);
  const double y_margin = kMargin * (guard_band.y * magnitude.w + magnitude.y);
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec4 p((corner & 1) ? box.max.x : box.min.x, (corner & 2) ? box.max.y : box.min.y,
                       (corner & 4) ? box.max.z : box.min.z, 1.0);
    const glm::dvec4 c = clip_from_object * p;
    if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.w)) return true;
    if (c.w - near_plane <= near_margin) return true;
    if (guard_band.x * c.w - std::abs(c.x) <= x_margin) return true;
    if (guard_band.y * c.w - std::abs(c.y) <= y_margin) return true;
  }
  return false;
}

}  // namespace tessera
