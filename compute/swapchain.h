#pragma once
// A swapchain on a window's surface, for presenting the compute-rendered image. The surface
// comes from the window system (host/window.h); this file knows only Vulkan.

#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "compute/context.h"

namespace tessera {

struct Swapchain {
  VkSurfaceKHR surface = VK_NULL_HANDLE;  // owned by the caller (destroy after the swapchain)
  VkSwapchainKHR swapchain = VK_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;  // B8G8R8A8_UNORM or R8G8B8A8_UNORM
  VkExtent2D extent{0, 0};
  VkPresentModeKHR present_mode = VK_PRESENT_MODE_FIFO_KHR;
  std::vector<VkImage> images;
  std::vector<VkImageView> views;
  /// One per image, signalled when the frame drawn into that image may be presented. Per
  /// image, not per frame: the presentation engine may still hold the previous one's wait.
  std::vector<VkSemaphore> rendered;
};

/// The image usage Tessera asks of swapchain images: the blit of the output image (transfer
/// destination), the screenshot read-back (transfer source) and the overlay (colour
/// attachment).
constexpr VkImageUsageFlags kSwapchainUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                                              VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                              VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;

/// (Re)creates `chain`'s swapchain on `chain.surface` for a framebuffer of `width` x `height`
/// pixels (both > 0; the surface's current extent wins where it has one), replacing the old
/// one, which must be idle. `vsync` picks FIFO, otherwise MAILBOX or IMMEDIATE where offered.
/// Throws Error if the queue cannot present to the surface, or the surface offers no 8-bit
/// UNORM format (B8G8R8A8 or R8G8B8A8) with the usage above: the output image holds
/// sRGB-encoded bytes, which a blit copies unchanged only into a UNORM image.
void create_swapchain(const Context& ctx, Swapchain& chain, uint32_t width, uint32_t height,
                      bool vsync);

/// Destroys the swapchain, its views and semaphores (not the surface); the device must be idle.
void destroy_swapchain(const Context& ctx, Swapchain& chain);

/// "VK_FORMAT_B8G8R8A8_UNORM"-like name of the formats a surface may offer, for messages.
std::string format_name(VkFormat format);

}  // namespace tessera
