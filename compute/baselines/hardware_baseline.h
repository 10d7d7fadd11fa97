#pragma once
// The graphics-pipeline baseline, for benchmarks and tests only (never the product path): a
// renderer's current scene drawn by the device's graphics pipeline (vertex and fragment shaders
// with the same BRDF code, reverse depth, the same face culling) into an RGBA16F colour
// attachment of its own, copied bit for bit into the renderer's HDR image after the timed render
// pass, then the renderer's own resolve pass. Renderer::read_hdr() / read_ldr() then return its
// images.

#include <array>
#include <cstdint>
#include <map>

#include <vulkan/vulkan.h>

#include "compute/baselines/graphics_util.h"
#include "compute/renderer.h"

namespace tessera {

struct BaselineStats {
  bool has_timestamps = false;
  double render_pass_ms = 0.0;  // GPU time of the level-of-detail passes (--lod auto) and
                                // the render pass (clear, draws)
  double resolve_ms = 0.0;      // the copy into the renderer's HDR image and its resolve pass
  double gpu_total_ms = 0.0;
  double cpu_record_submit_ms = 0.0;
  uint32_t draws = 0;  // one instanced draw (multi-draw under level of detail) per mesh run
};

class HardwareBaseline {
 public:
  /// Draws with `renderer`'s scene, buffers and images; `renderer` must outlive it. Pipelines
  /// and targets are created on first use.
  explicit HardwareBaseline(Renderer& renderer);
  ~HardwareBaseline();
  HardwareBaseline(const HardwareBaseline&) = delete;
  HardwareBaseline& operator=(const HardwareBaseline&) = delete;

  /// Renders the renderer's current scene with `settings`. Throws Error if the queue has no
  /// graphics support or settings.samples is not 1, and as Renderer::render does (no scene,
  /// bad settings).
  BaselineStats render(const FrameSettings& settings);

 private:
  void ensure_targets(uint64_t generation, uint32_t width, uint32_t height);
  void destroy_targets();

  Renderer& renderer_;
  const Context& ctx_;
  VkRenderPass pass_ = VK_NULL_HANDLE;
  // By the shading specialization's words and the variant (mirrored, double-sided).
  using PipelineKey = std::array<uint32_t, sizeof(Specialization) / 4 + 1>;
  std::map<PipelineKey, VkPipeline> pipelines_;
  Attachment color_, depth_;
  VkFramebuffer framebuffer_ = VK_NULL_HANDLE;
  uint64_t images_generation_ = 0;  // of the renderer's images the framebuffer holds
  VkQueryPool queries_ = VK_NULL_HANDLE;
};

}  // namespace tessera
