#pragma once
// Scene families for performance studies, each parameterised by its object count N.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/scene.h"

namespace tessera {

struct BenchFamilyInfo {
  std::string_view name;
  std::string_view description;
};

/// The families: "grid", "scatter", "huge", "yardstick".
std::span<const BenchFamilyInfo> bench_families();

/// True if `name` is one of bench_families().
bool is_bench_family(std::string_view name);

/// The families' names, comma-separated ("grid, scatter, huge, yardstick"), for messages.
std::string bench_family_names();

/// Builds family `family` with `objects` objects (>= 1) for an image of aspect `aspect`
/// (width / height). Spheres are uv spheres of `segments` slices and segments / 2 stacks
/// (2 * segments * (segments / 2 - 1) triangles: 960 for the default 32). Deterministic.
/// Throws Error for an unknown family, zero objects or fewer than 4 segments.
///  - grid: N spheres on a grid that fills the view; triangles shrink as N grows.
///  - scatter: N small spheres scattered in depth inside the view: heavy overdraw.
///  - huge: N triangles, each many times the screen, stacked in depth: the large-triangle path.
///  - yardstick: the minimal graphics program's scene (bench/minimal_graphics.cpp, issue 13):
///    N spheres placed by yardstick_placement, camera at (0, 0, 3) looking at the origin with
///    a 60 degree vertical field of view, the four lights of
///    kYardstickLightDistance, material i % 49
///    of the 7 x 7 palette. It ignores `aspect` (its layout is fixed in world units).
Scene make_bench_scene(std::string_view family, uint32_t objects, uint32_t segments, float aspect);

/// Refuses `copies` copies of something of `per_copy` triangles where their triangle instances
/// would pass the 2^32 - 1 Tessera can number: throws Error "--objects N: P triangles per
/// `copy_name` make T triangle instances, more than ... (at most M `copies_name`)". For checking
/// a sweep's counts from one copy, before a scene that can take a minute to build.
void check_triangle_numbering(uint64_t per_copy, uint32_t copies, const std::string& copy_name,
                              const std::string& copies_name);

/// Where the yardstick family puts sphere `i` (< `objects`) of `objects`: on a side x side grid,
/// side = ceil(sqrt(objects)), centre (((i mod side) + 0.5) / side * 2 - 1) * 3,
/// (((i div side) + 0.5) / side * 2 - 1) * 1.7, 0) and radius 0.45 * min(6, 3.4) / side (world
/// units; the grid spans 6 x 3.4). The unit sphere mesh is scaled by `radius`.
struct YardstickPlacement {
  glm::vec3 centre{0.0f};
  float radius = 0.0f;
};
YardstickPlacement yardstick_placement(uint32_t i, uint32_t objects);

/// The yardstick's four point lights: white, inverse-square, at (+-d, +-d, d) with d = 4 and
/// intensity 3 d^2 = 48 W/sr (as the other families' lights at their distance).
constexpr float kYardstickLightDistance = 4.0f;

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

/// The lights make_instanced_bench_scene gives `copies` copies of `content`: the content's,
/// moved about the centre of its bounding sphere with their positions, ranges and classic
/// attenuation's lengths (Kl by 1/length, Kq by 1/length^2) scaled by `length`, and
/// inverse-square intensities by length^2, so that they light each copy as they lit the
/// content. Scaled, a light within validate_scene's limits can be past them: the bench says so.
/// Throws as make_instanced_bench_scene does.
struct InstancedLights {
  std::vector<Light> lights;
  float length = 1.0f;
};
InstancedLights instanced_bench_lights(const Scene& content, uint32_t copies, float aspect);

}  // namespace tessera
