#pragma once
// Level of detail: a chain of coarser (and, for spheres, finer) versions of a mesh, each with
// its object-space error, and the choice of a level per object from its projected error in
// pixels (docs/architecture.md, "Level of detail"). The compute path makes the same choice on
// the GPU in float (shaders/lod.comp); select_lod_level is the double-precision statement of
// it that the reference renderer and the tests use. No Vulkan here.

#include <cstdint>
#include <memory>
#include <vector>

#include "core/frame_settings.h"
#include "core/scene.h"

namespace tessera {

/// One level of a chain.
struct LodLevel {
  /// The level's own mesh (a sphere tessellation, or the base mesh's vertices with the level's
  /// triangles). Shared: chains are cached and copied.
  std::shared_ptr<const Mesh> mesh;
  /// True if `mesh` has the base mesh's vertex arrays (so the GPU keeps them once and only
  /// the indices differ); false for a sphere tessellation with vertices of its own.
  bool shares_base_vertices = false;
  /// True for the base mesh itself, unchanged.
  bool is_base = false;
  /// Object-space error, in the mesh's units: for a sphere (Mesh::analytic_sphere) the
  /// largest distance between the true sphere and the level's facets (the chord error); for
  /// other meshes meshoptimizer's error estimate of the level against the base mesh
  /// (relative error times meshopt_simplifyScale), 0 for the base mesh.
  double error = 0.0;
};

/// Levels of one mesh, finest first: errors never decrease and triangle counts strictly fall
/// from each level to the next. Never empty: a mesh that cannot be simplified has its
/// base level only.
struct LodChain {
  std::vector<LodLevel> levels;
  /// Object-space sphere around every vertex of every level.
  glm::dvec3 centre{0.0};
  double radius = 0.0;
  /// The index of the base mesh in `levels`.
  uint32_t base_level = 0;
};

/// Chord error of make_uv_sphere(segments, rings) for a unit sphere: the largest distance
/// between the sphere and the mesh, 1 - min over the rings of stacks of the distance from the
/// centre to their facets' planes (derived in core/lod.cpp). Requires segments >= 3, rings >= 2.
double uv_sphere_chord_error(uint32_t segments, uint32_t rings);

/// Segment counts of the sphere levels (make_uv_sphere(s, s / 2)): 4 to 256.
inline constexpr uint32_t kSphereLodSegments[] = {4,  6,  8,  12,  16,  24, 32,
                                                  48, 64, 96, 128, 192, 256};

/// Builds the chain of `mesh` (which must have triangles):
///  - a sphere (Mesh::analytic_sphere): the base mesh, with its chord error measured from its
///    facets, among the uv spheres of kSphereLodSegments (uv_sphere_chord_error), placed on
///    the same analytic sphere; levels with more triangles than a level of no larger error
///    are left out;
///  - any other mesh: the base mesh, then meshopt_simplify to half the triangles of the
///    previous level (from the base each time, target error unbounded) while it still removes
///    at least a tenth of them and leaves a triangle.
/// Deterministic: a function of the mesh alone.
LodChain build_lod_chain(const Mesh& mesh);

/// The most pixels a world-space offset of length 1 at view depth 1 moves a visible point
/// under `camera` in an image `width` x `height`: (height / 2) / tan(fovy / 2) times the
/// obliquity factor sqrt(1 + tan^2(fovy / 2) (1 + aspect^2)) of the view's corners (derived
/// in core/lod.cpp). At depth z it is this over z.
double lod_pixels_per_unit(const Camera& camera, uint32_t width, uint32_t height);

/// The level `chain` is drawn at for an object placed by `transform`: the coarsest level
/// whose error, scaled by the transform's largest axis scale and projected at the view depth
/// of the near side of the object's bounding sphere (clamped to the near plane), is at most
/// `max_error_px`; the finest level if none is. Double precision; shaders/lod.comp computes
/// the same in float (the two can differ only where a level's projected error is within
/// float rounding of the bound).
uint32_t select_lod_level(const LodChain& chain, const glm::mat4& transform, const Camera& camera,
                          uint32_t width, uint32_t height, double max_error_px);

/// The chains of a scene's meshes, by mesh index (empty chains for meshes without triangles).
std::vector<LodChain> build_lod_chains(const Scene& scene);

/// Triangle instances a frame draws under `settings` (FrameSettings::lod auto: with the level
/// select_lod_level picks per object; off: the meshes as they are). `chains` from
/// build_lod_chains (only read under Lod::automatic).
uint64_t lod_triangle_count(const Scene& scene, const std::vector<LodChain>& chains,
                            const FrameSettings& settings);

}  // namespace tessera
