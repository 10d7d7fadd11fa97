#pragma once
// The few pieces of the graphics pipeline the baselines need (tests and benchmarks only).

#include <cstdint>
#include <span>

#include <vulkan/vulkan.h>

#include "compute/context.h"
#include "compute/gpu_memory.h"
#include "compute/passes.h"

namespace tessera {

/// A render-pass attachment: create_image and destroy_image of gpu_memory.h.
using Attachment = StorageImage;

/// Throws Error if the context's queue family cannot run graphics work.
void require_graphics_queue(const Context& ctx);

struct GraphicsPipelineDesc {
  const char* vertex_shader;  // embedded names (baseline_shaders.h), or labels of the code below
  const char* fragment_shader;
  bool clip_space_positions;  // one vec4 vertex attribute at binding 0; else `vertex_input`'s
  VkCullModeFlags cull;
  VkCompareOp depth_compare;  // depth test and write on
  VkColorComponentFlags color_mask;
  bool mirrored = false;  // front faces wind clockwise in the world (is_mirroring, scene.h)
  // Specialization constants (TS_SPEC_*) of both stages; shaders ignore those they lack.
  Specialization shading{};
  // SPIR-V of the two stages when they are not the baselines' own (empty: found by name).
  std::span<const uint32_t> vertex_code{}, fragment_code{};
  // Vertex-input bindings and attributes (none: vertices pulled from storage buffers).
  std::span<const VkVertexInputBindingDescription> bindings{};
  std::span<const VkVertexInputAttributeDescription> attributes{};
};

/// The GPU time in ms between two timestamps the context's queue wrote.
double timestamp_interval_ms(const Context& ctx, uint64_t begin, uint64_t end);

/// A triangle-list pipeline for `pass`'s subpass 0, one sample, dynamic viewport and scissor.
VkPipeline create_graphics_pipeline(const Context& ctx, VkRenderPass pass, VkPipelineLayout layout,
                                    const GraphicsPipelineDesc& desc);

}  // namespace tessera
