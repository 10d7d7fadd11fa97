#include "compute/swapchain.h"

#include <algorithm>

#include "compute/vk_check.h"
#include "core/check.h"

namespace tessera {
namespace {

// The output image holds sRGB-encoded RGBA8 bytes; a blit into a UNORM image keeps the bytes
// (swizzling R and B where needed), so the window shows the same values as the PNG. An _SRGB
// swapchain image would encode them a second time.
constexpr VkFormat kFormats[] = {VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM};

VkSurfaceFormatKHR choose_format(const Context& ctx, VkSurfaceKHR surface) {
  uint32_t count = 0;
  VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(ctx.physical_device, surface, &count, nullptr));
  std::vector<VkSurfaceFormatKHR> formats(count);
  VK_CHECK(
      vkGetPhysicalDeviceSurfaceFormatsKHR(ctx.physical_device, surface, &count, formats.data()));
  for (VkFormat wanted : kFormats) {
    for (const VkSurfaceFormatKHR& f : formats) {
      if (f.format == wanted && f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) return f;
    }
  }
  std::string offered;
  for (const VkSurfaceFormatKHR& f : formats) {
    offered += (offered.empty() ? "" : ", ") + format_name(f.format);
  }
  throw Error("the window's surface offers no B8G8R8A8_UNORM or R8G8B8A8_UNORM format (it offers " +
              offered + ")");
}

VkPresentModeKHR choose_present_mode(const Context& ctx, VkSurfaceKHR surface, bool vsync) {
  if (vsync) return VK_PRESENT_MODE_FIFO_KHR;  // always supported
  uint32_t count = 0;
  VK_CHECK(
      vkGetPhysicalDeviceSurfacePresentModesKHR(ctx.physical_device, surface, &count, nullptr));
  std::vector<VkPresentModeKHR> modes(count);
  VK_CHECK(vkGetPhysicalDeviceSurfacePresentModesKHR(ctx.physical_device, surface, &count,
                                                     modes.data()));
  for (VkPresentModeKHR wanted : {VK_PRESENT_MODE_MAILBOX_KHR, VK_PRESENT_MODE_IMMEDIATE_KHR}) {
    if (std::find(modes.begin(), modes.end(), wanted) != modes.end()) return wanted;
  }
  return VK_PRESENT_MODE_FIFO_KHR;
}

void destroy_views(const Context& ctx, Swapchain& chain) {
  for (VkImageView view : chain.views) vkDestroyImageView(ctx.device, view, nullptr);
  for (VkSemaphore s : chain.rendered) vkDestroySemaphore(ctx.device, s, nullptr);
  chain.views.clear();
  chain.rendered.clear();
  chain.images.clear();
}

}  // namespace

std::string format_name(VkFormat format) {
  switch (format) {
    case VK_FORMAT_B8G8R8A8_UNORM:
      return "B8G8R8A8_UNORM";
    case VK_FORMAT_B8G8R8A8_SRGB:
      return "B8G8R8A8_SRGB";
    case VK_FORMAT_R8G8B8A8_UNORM:
      return "R8G8B8A8_UNORM";
    case VK_FORMAT_R8G8B8A8_SRGB:
      return "R8G8B8A8_SRGB";
    case VK_FORMAT_A2B10G10R10_UNORM_PACK32:
      return "A2B10G10R10_UNORM";
    case VK_FORMAT_R16G16B16A16_SFLOAT:
      return "R16G16B16A16_SFLOAT";
    default:
      return "format " + std::to_string(int(format));
  }
}

void create_swapchain(const Context& ctx, Swapchain& chain, uint32_t width, uint32_t height,
                      bool vsync) {
  TESSERA_CHECK(chain.surface != VK_NULL_HANDLE && width > 0 && height > 0);
  VkBool32 can_present = VK_FALSE;
  VK_CHECK(vkGetPhysicalDeviceSurfaceSupportKHR(ctx.physical_device, ctx.queue_family,
                                                chain.surface, &can_present));
  if (!can_present) {
    throw Error(std::string("device '") + ctx.properties.deviceName +
                "' cannot present to the window from its compute queue");
  }
  VkSurfaceCapabilitiesKHR caps;
  VK_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(ctx.physical_device, chain.surface, &caps));
  if ((caps.supportedUsageFlags & kSwapchainUsage) != kSwapchainUsage) {
    throw Error("the window's surface does not allow swapchain images to be copied to and drawn");
  }
  const VkSurfaceFormatKHR format = choose_format(ctx, chain.surface);
  VkExtent2D extent = caps.currentExtent;
  // 0xFFFFFFFF: the surface takes the swapchain's size, which the framebuffer's size decides.
  if (extent.width == 0xFFFFFFFFu) {
    extent.width = std::clamp(width, caps.minImageExtent.width, caps.maxImageExtent.width);
    extent.height = std::clamp(height, caps.minImageExtent.height, caps.maxImageExtent.height);
  }
  uint32_t image_count = caps.minImageCount + 1;
  if (caps.maxImageCount > 0) image_count = std::min(image_count, caps.maxImageCount);

  VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  info.surface = chain.surface;
  info.minImageCount = image_count;
  info.imageFormat = format.format;
  info.imageColorSpace = format.colorSpace;
  info.imageExtent = extent;
  info.imageArrayLayers = 1;
  info.imageUsage = kSwapchainUsage;
  info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.preTransform = caps.currentTransform;
  info.compositeAlpha = (caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR)
                            ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
                            : VkCompositeAlphaFlagBitsKHR(caps.supportedCompositeAlpha &
                                                          -caps.supportedCompositeAlpha);
  info.presentMode = choose_present_mode(ctx, chain.surface, vsync);
  info.clipped = VK_TRUE;
  info.oldSwapchain = chain.swapchain;
  VkSwapchainKHR created = VK_NULL_HANDLE;
  VK_CHECK(vkCreateSwapchainKHR(ctx.device, &info, nullptr, &created));
  destroy_swapchain(ctx, chain);
  chain.swapchain = created;
  chain.format = format.format;
  chain.extent = extent;
  chain.present_mode = info.presentMode;

  uint32_t count = 0;
  VK_CHECK(vkGetSwapchainImagesKHR(ctx.device, chain.swapchain, &count, nullptr));
  chain.images.resize(count);
  VK_CHECK(vkGetSwapchainImagesKHR(ctx.device, chain.swapchain, &count, chain.images.data()));
  for (VkImage image : chain.images) {
    VkImageViewCreateInfo view_info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    view_info.image = image;
    view_info.viewType = VK_IMAGE_VIEW_TYPE_2D;
    view_info.format = chain.format;
    view_info.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkImageView view = VK_NULL_HANDLE;
    VK_CHECK(vkCreateImageView(ctx.device, &view_info, nullptr, &view));
    chain.views.push_back(view);
    VkSemaphoreCreateInfo sem_info{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    VkSemaphore sem = VK_NULL_HANDLE;
    VK_CHECK(vkCreateSemaphore(ctx.device, &sem_info, nullptr, &sem));
    chain.rendered.push_back(sem);
  }
}

void destroy_swapchain(const Context& ctx, Swapchain& chain) {
  destroy_views(ctx, chain);
  if (chain.swapchain) vkDestroySwapchainKHR(ctx.device, chain.swapchain, nullptr);
  chain.swapchain = VK_NULL_HANDLE;
}

}  // namespace tessera
