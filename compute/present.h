#pragma once
// Presenting the renderer's frame in a swapchain. Each frame acquires an image and records the
// renderer's resolve pass (tone mapping, sRGB encoding; RendererOptions::resolve off) either
// straight into the swapchain image (Swapchain::direct) or into the renderer's display image
// followed by a byte copy, in the swapchain's byte order either way; optionally reads the image
// back for a screenshot, lets an overlay draw over it, and presents it. One frame in flight:
// present_frame waits for its commands, so the renderer may render again as soon as it returns.

#include <functional>
#include <vector>

#include "compute/gpu_memory.h"
#include "compute/renderer.h"
#include "compute/swapchain.h"
#include "core/image.h"

namespace tessera {

struct Presenter {
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  VkFence done = VK_NULL_HANDLE;
  VkSemaphore acquired = VK_NULL_HANDLE;
  Buffer readback;  // screenshots; grown on demand
  // Direct path: per swapchain image, a copy of the renderer's shared descriptor set whose
  // display-image binding is that image's storage view, and the renderer's set generation it
  // was copied from.
  VkDescriptorPool pool = VK_NULL_HANDLE;
  std::vector<VkDescriptorSet> sets;
  std::vector<uint64_t> set_generations;
  VkQueryPool queries = VK_NULL_HANDLE;  // the resolve pass's two timestamps
};

void create_presenter(const Context& ctx, Presenter& p);
void destroy_presenter(const Context& ctx, Presenter& p);

/// Makes the per-image descriptor sets for `chain` (after each create_swapchain; the device
/// must be idle). `renderer` must have rendered a frame (its shared set exists).
void prepare_presenter(const Context& ctx, Presenter& p, const Swapchain& chain,
                       const Renderer& renderer);

/// Records what is drawn over the swapchain image `image_index` (in
/// COLOR_ATTACHMENT_OPTIMAL on entry; it must leave it in PRESENT_SRC_KHR), after the
/// screenshot's read-back.
using OverlayRecorder = std::function<void(VkCommandBuffer cmd, uint32_t image_index)>;

enum class PresentResult {
  presented,
  presented_suboptimal,  // shown, but the swapchain should be recreated
  out_of_date,           // nothing shown: recreate the swapchain and render again
};

/// Resolves and presents the frame `renderer` (created with RendererOptions::resolve off) last
/// rendered, at the size of `chain`, in `chain`. With `screenshot` set, the swapchain image is
/// read back after the resolve (and copy) and before the overlay, converted to RGBA8. `overlay`
/// may be empty. Where the queue has timestamps, adds the resolve pass's GPU time to `stats`
/// (may be null). Waits until the commands have run. Throws Error on device loss or other
/// failures.
PresentResult present_frame(const Context& ctx, Presenter& p, const Swapchain& chain,
                            Renderer& renderer, const OverlayRecorder& overlay, Image8* screenshot,
                            FrameStats* stats);

}  // namespace tessera
