#pragma once
// Predicting, on the CPU, that a frame has nothing to clip: the clip pass (shaders/clip.comp)
// clips the triangles setup finds crossing the near plane or the guard band, and when an
// object's bounding box lies inside all five planes none of its triangles can. The renderer
// then leaves the pass (a dispatch and a barrier) out of the frame; if the GPU still lists a
// triangle to clip, it redoes the frame with the pass, so a wrong prediction costs time, never
// a triangle.

#include <vector>

#include <glm/glm.hpp>

#include "core/scene.h"

namespace tessera {

/// Axis-aligned bounds of a mesh's positions, in object space; min > max for a mesh without
/// positions.
struct MeshBox {
  glm::vec3 min{1.0f};
  glm::vec3 max{-1.0f};
};

/// The bounds of `mesh`'s positions (all of them, indexed or not).
MeshBox mesh_box(const Mesh& mesh);

/// Whether a vertex inside `box`, taken to clip space by `clip_from_world * world_from_object`
/// (projection * view, and the object's model matrix) in single precision as the GPU does
/// (shaders/object_clip.comp, view_clip.glsl), may lie behind the near plane (clip w <
/// `near_plane`) or outside the guard band (|x| > guard_band.x * w or |y| > guard_band.y * w):
/// the clip pass's planes (view_clip.glsl, plane_distance). False only if every corner of the
/// box lies inside all five planes by more than a margin that bounds the rounding of the
/// single-precision products: 1e-5 of the sum of the magnitudes of every term that goes into
/// the clip coordinates (|clip_from_world| |world_from_object| |vertex|), about 80 times
/// float's rounding of such sums. The distances to the planes are affine in the vertex, so the
/// corners bound every point of the box. A box with a non-finite corner: true; an empty box:
/// false.
bool may_need_clipping(const MeshBox& box, const glm::dmat4& clip_from_world,
                       const glm::dmat4& world_from_object, double near_plane,
                       glm::dvec2 guard_band);

}  // namespace tessera
