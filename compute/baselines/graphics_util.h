#pragma once
// The few pieces of the graphics pipeline the baselines need (tests and benchmarks only).

#include <vulkan/vulkan.h>

#include "compute/context.h"
#include "compute/gpu_memory.h"

namespace tessera {

/// A render-pass attachment: create_image and destroy_image of gpu_memory.h.
using Attachment = StorageImage;

/// Throws Error if the context's queue family cannot run graphics work.
void require_graphics_queue(const Context& ctx);

struct GraphicsPipelineDesc {
  const char* vertex_shader;  // embedded names (baseline_shaders.h)
  const char* fragment_shader;
  bool clip_space_positions;  // one vec4 vertex attribute at binding 0; else vertices pulled
  VkCullModeFlags cull;
  VkCompareOp depth_compare;  // depth test and write on
  VkColorComponentFlags color_mask;
  uint32_t brdf = 0;                        // specialization constants of the fragment shader:
  VkBool32 energy_compensation = VK_FALSE;  // TS_SPEC_BRDF, TS_SPEC_ENERGY_COMPENSATION
  bool mirrored = false;  // front faces wind clockwise in the world (is_mirroring, scene.h)
};

/// A triangle-list pipeline for `pass`'s subpass 0, one sample, dynamic viewport and scissor.
VkPipeline create_graphics_pipeline(const Context& ctx, VkRenderPass pass, VkPipelineLayout layout,
                                    const GraphicsPipelineDesc& desc);

}  // namespace tessera
