#pragma once
// Scene families for performance studies, each parameterised by its object count N.

#include <cstdint>
#include <span>
#include <string_view>

#include "core/scene.h"

namespace tessera {

struct BenchFamilyInfo {
  std::string_view name;
  std::string_view description;
};

/// The families: "grid", "scatter", "huge".
std::span<const BenchFamilyInfo> bench_families();

/// Builds family `family` with `objects` objects (>= 1) for an image of aspect `aspect`
/// (width / height). Spheres are uv spheres of `segments` slices and segments / 2 stacks
/// (2 * segments * (segments / 2 - 1) triangles: 960 for the default 32). Deterministic.
/// Throws Error for an unknown family, zero objects or fewer than 4 segments.
///  - grid: N spheres on a grid that fills the view; triangles shrink as N grows.
///  - scatter: N small spheres scattered in depth inside the view: heavy overdraw.
///  - huge: N triangles, each many times the screen, stacked in depth: the large-triangle path.
Scene make_bench_scene(std::string_view family, uint32_t objects, uint32_t segments, float aspect);

struct Sphere {
  glm::vec3 center{0.0f};
  float radius = 0.0f;
};

/// A sphere around every vertex of every object of `scene`, in world space: centred on their
/// bounding box, its radius the farthest vertex. Throws Error if no object has a vertex.
Sphere bounding_sphere(const Scene& scene);

/// `copies` copies of `content` (all its objects, keeping their relative transforms) on the
/// grid family's layout for aspect `aspect`: each copy is scaled and moved so its bounding
/// sphere is the unit sphere of one grid cell. Meshes, materials, textures, the environment and
/// the lights are the content's (lights moved with the content to the whole grid; four lights
/// as the grid family's when it has none); the camera is the grid family's. Throws Error for
/// zero copies, a bad aspect or content without vertices.
Scene make_instanced_bench_scene(const Scene& content, uint32_t copies, float aspect);

}  // namespace tessera
