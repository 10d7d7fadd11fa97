#pragma once
// A minimal Vulkan graphics pipeline, the device's hardware rasterizer, used only as a baseline
// by tests and benchmarks: never in the product path.

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "compute/context.h"

namespace tessera {

/// Rasterizes triangles given directly in clip space (3 consecutive positions each) with the
/// device's graphics pipeline into a width x height image of triangle indices: the nearest
/// triangle by a D32 depth test (LESS; the projection must map nearer to smaller z), no
/// culling, one sample per pixel at its centre. Empty pixels hold 0xFFFFFFFF. Throws Error if
/// the device has no graphics queue in its family or lacks the formats.
std::vector<uint32_t> hardware_triangle_ids(const Context& ctx,
                                            const std::vector<glm::vec4>& clip_positions,
                                            uint32_t width, uint32_t height);

}  // namespace tessera
