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

}  // namespace tessera
