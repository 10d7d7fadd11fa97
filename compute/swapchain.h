#pragma once
// A swapchain on a window's surface, for presenting the compute-rendered image. The surface
// comes from the window system (host/window.h); this file knows only Vulkan.

#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "compute/context.h"

namespace tessera {

/// How a frame reaches the swapchain image (compute/present.h).
enum class PresentPath {
  automatic,  // direct where the surface and device allow it and the format is UNORM, else copy
  copy,       // the resolve pass writes Tessera's display image, which is copied into the image
  direct,     // the resolve pass writes the swapchain image itself (a storage image)
};

/// Which kind of 8-bit swapchain format to ask the surface for.
enum class SurfaceFormat {
  automatic,  // UNORM where offered, else sRGB
  unorm,      // B8G8R8A8_UNORM or R8G8B8A8_UNORM only
  srgb,       // B8G8R8A8_SRGB or R8G8B8A8_SRGB only (the presentation engine decodes them)
};

struct SwapchainOptions {
  bool vsync = true;  // FIFO; otherwise MAILBOX or IMMEDIATE where offered
  PresentPath path = PresentPath::automatic;
  SurfaceFormat format = SurfaceFormat::automatic;
};

struct Swapchain {
  VkSurfaceKHR surface = VK_NULL_HANDLE;  // owned by the caller (destroy after the swapchain)
  VkSwapchainKHR swapchain = VK_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;  // B8G8R8A8 or R8G8B8A8, UNORM or SRGB
  VkExtent2D extent{0, 0};
  VkPresentModeKHR present_mode = VK_PRESENT_MODE_FIFO_KHR;
  /// The resolve pass writes the images directly, through `storage_views`; otherwise they are
  /// copied into.
  bool direct = false;
  std::string path_reason;  // why the copy path was taken ("" when direct)
  std::vector<VkImage> images;
  /// Colour-attachment views for the overlay, in `view_format`: the UNORM twin of an sRGB
  /// `format` where the images are mutable (so the panel's colours are not encoded twice),
  /// else `format`.
  std::vector<VkImageView> views;
  VkFormat view_format = VK_FORMAT_UNDEFINED;
  /// R8G8B8A8_UNORM views, for the resolve pass's stores (direct only).
  std::vector<VkImageView> storage_views;
  /// One per image, signalled when the frame drawn into that image may be presented. Per
  /// image, not per frame: the presentation engine may still hold the previous one's wait.
  std::vector<VkSemaphore> rendered;
};

/// The image usage Tessera asks of every swapchain: the copy of the display image (transfer
/// destination), the screenshot read-back (transfer source) and the overlay (colour
/// attachment). The direct path adds VK_IMAGE_USAGE_STORAGE_BIT.
constexpr VkImageUsageFlags kSwapchainUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                                              VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                              VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;

/// (Re)creates `chain`'s swapchain on `chain.surface` for a framebuffer of `width` x `height`
/// pixels (both > 0; the surface's current extent wins where it has one), replacing the old
/// one, which must be idle. The images hold the sRGB-encoded bytes of Tessera's display image
/// in every format: an sRGB format is written through a UNORM view or by a byte copy, never
/// encoded a second time. The direct path needs the surface's storage usage, storage support
/// for R8G8B8A8_UNORM, and (for any other format) VK_KHR_swapchain_mutable_format.
/// Throws Error if the queue cannot present to the surface, the surface offers no 8-bit RGBA
/// or BGRA format of the kind asked for or lacks the usage above, or PresentPath::direct was
/// asked for where it is not possible (the message says why).
void create_swapchain(const Context& ctx, Swapchain& chain, uint32_t width, uint32_t height,
                      const SwapchainOptions& options);

/// Destroys the swapchain, its views and semaphores (not the surface); the device must be idle.
void destroy_swapchain(const Context& ctx, Swapchain& chain);

/// True for the formats whose first byte is blue (B8G8R8A8_UNORM, B8G8R8A8_SRGB).
bool is_bgra(VkFormat format);

/// "VK_FORMAT_B8G8R8A8_UNORM"-like name of the formats a surface may offer, for messages.
std::string format_name(VkFormat format);

}  // namespace tessera
