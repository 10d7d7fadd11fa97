#pragma once
// Presenting the renderer's output image (RGBA8, sRGB-encoded) in a swapchain: each frame
// acquires an image, blits the output into it (a swizzle where the swapchain is B8G8R8A8, the
// bytes otherwise unchanged), optionally reads it back for a screenshot, lets an overlay draw
// over it, and presents it. One frame in flight: present_frame waits for its commands, so the
// renderer may write the output image again as soon as it returns.

#include <functional>

#include "compute/gpu_memory.h"
#include "compute/swapchain.h"
#include "core/image.h"

namespace tessera {

struct Presenter {
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  VkFence done = VK_NULL_HANDLE;
  VkSemaphore acquired = VK_NULL_HANDLE;
  Buffer readback;  // screenshots; grown on demand
};

void create_presenter(const Context& ctx, Presenter& p);
void destroy_presenter(const Context& ctx, Presenter& p);

/// Records what is drawn over the swapchain image `image_index` (in
/// COLOR_ATTACHMENT_OPTIMAL on entry; it must leave it in PRESENT_SRC_KHR), after the
/// screenshot's read-back.
using OverlayRecorder = std::function<void(VkCommandBuffer cmd, uint32_t image_index)>;

enum class PresentResult {
  presented,
  presented_suboptimal,  // shown, but the swapchain should be recreated
  out_of_date,           // nothing shown: recreate the swapchain and render again
};

/// Presents `source` (the renderer's output image, in GENERAL, written by compute shaders and
/// the same size as the swapchain) in `chain`. With `screenshot` set, the swapchain image is
/// read back after the blit and before the overlay, converted to RGBA8. `overlay` may be empty.
/// Waits until the commands have run. Throws Error on device loss or other failures.
PresentResult present_frame(const Context& ctx, Presenter& p, const Swapchain& chain,
                            const StorageImage& source, const OverlayRecorder& overlay,
                            Image8* screenshot);

}  // namespace tessera
