#include "compute/swapchain.h"

#include <algorithm>

#include "compute/vk_check.h"
#include "core/check.h"

namespace tessera {
namespace {

// The display image holds sRGB-encoded bytes, and every format here keeps them as they are: a
// UNORM image through a byte copy or the resolve pass's stores, an sRGB one through a byte copy
// or a UNORM view (the presentation engine then decodes what the PNG holds). A blit or an sRGB
// view would encode them a second time.
constexpr VkFormat kUnormFormats[] = {VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM};
constexpr VkFormat kSrgbFormats[] = {VK_FORMAT_B8G8R8A8_SRGB, VK_FORMAT_R8G8B8A8_SRGB};

// The resolve pass's stores go through a view of this format (shaders/resolve.comp declares
// its image rgba8); OUTPUT_BGRA orders the bytes for a B8G8R8A8 image.
constexpr VkFormat kStorageViewFormat = VK_FORMAT_R8G8B8A8_UNORM;

// The UNORM format with the same bytes as `format`.
VkFormat unorm_twin(VkFormat format) {
  if (format == VK_FORMAT_B8G8R8A8_SRGB) return VK_FORMAT_B8G8R8A8_UNORM;
  if (format == VK_FORMAT_R8G8B8A8_SRGB) return VK_FORMAT_R8G8B8A8_UNORM;
  return format;
}

VkSurfaceFormatKHR choose_format(const Context& ctx, VkSurfaceKHR surface, SurfaceFormat kind) {
  uint32_t count = 0;
  VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(ctx.physical_device, surface, &count, nullptr));
  std::vector<VkSurfaceFormatKHR> formats(count);
  VK_CHECK(
      vkGetPhysicalDeviceSurfaceFormatsKHR(ctx.physical_device, surface, &count, formats.data()));
  std::vector<VkFormat> wanted;
  if (kind != SurfaceFormat::srgb)
    wanted.insert(wanted.end(), std::begin(kUnormFormats), std::end(kUnormFormats));
  if (kind != SurfaceFormat::unorm)
    wanted.insert(wanted.end(), std::begin(kSrgbFormats), std::end(kSrgbFormats));
  for (VkFormat w : wanted) {
    for (const VkSurfaceFormatKHR& f : formats) {
      if (f.format == w && f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) return f;
    }
  }
  std::string asked, offered;
  for (VkFormat w : wanted) asked += (asked.empty() ? "" : ", ") + format_name(w);
  for (const VkSurfaceFormatKHR& f : formats) {
    offered += (offered.empty() ? "" : ", ") + format_name(f.format);
  }
  throw Error("the window's surface offers none of " + asked + " (it offers " + offered + ")");
}

// Why the resolve pass cannot write `format` swapchain images on this surface, or "".
std::string direct_obstacle(const Context& ctx, const VkSurfaceCapabilitiesKHR& caps,
                            VkFormat format) {
  if (!(caps.supportedUsageFlags & VK_IMAGE_USAGE_STORAGE_BIT))
    return "the surface does not allow storage use of its images";
  VkFormatProperties features;
  vkGetPhysicalDeviceFormatProperties(ctx.physical_device, kStorageViewFormat, &features);
  if (!(features.optimalTilingFeatures & VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT))
    return "the device cannot store to R8G8B8A8_UNORM images";
  const bool mutable_format = format != kStorageViewFormat;
  if (mutable_format && !ctx.swapchain_mutable_format) {
    return "writing " + format_name(format) +
           " images through an R8G8B8A8_UNORM view needs VK_KHR_swapchain_mutable_format, "
           "which the device lacks";
  }
  VkImageFormatProperties properties;
  const VkImageCreateFlags flags =
      mutable_format ? VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT | VK_IMAGE_CREATE_EXTENDED_USAGE_BIT : 0;
  if (vkGetPhysicalDeviceImageFormatProperties(
          ctx.physical_device, format, VK_IMAGE_TYPE_2D, VK_IMAGE_TILING_OPTIMAL,
          kSwapchainUsage | VK_IMAGE_USAGE_STORAGE_BIT, flags, &properties) != VK_SUCCESS)
    return "the device cannot make " + format_name(format) + " images with storage use";
  return "";
}

VkImageView create_view(const Context& ctx, VkImage image, VkFormat format,
                        VkImageUsageFlags usage) {
  // Only the usage this view serves: the other formats of a mutable image may not support all
  // of the image's usage.
  VkImageViewUsageCreateInfo usage_info{VK_STRUCTURE_TYPE_IMAGE_VIEW_USAGE_CREATE_INFO};
  usage_info.usage = usage;
  VkImageViewCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  info.pNext = &usage_info;
  info.image = image;
  info.viewType = VK_IMAGE_VIEW_TYPE_2D;
  info.format = format;
  info.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  VkImageView view = VK_NULL_HANDLE;
  VK_CHECK(vkCreateImageView(ctx.device, &info, nullptr, &view));
  return view;
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
  for (VkImageView view : chain.storage_views) vkDestroyImageView(ctx.device, view, nullptr);
  for (VkSemaphore s : chain.rendered) vkDestroySemaphore(ctx.device, s, nullptr);
  chain.views.clear();
  chain.storage_views.clear();
  chain.rendered.clear();
  chain.images.clear();
}

}  // namespace

bool is_bgra(VkFormat format) {
  return format == VK_FORMAT_B8G8R8A8_UNORM || format == VK_FORMAT_B8G8R8A8_SRGB;
}

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
                      const SwapchainOptions& options) {
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
  const VkSurfaceFormatKHR format = choose_format(ctx, chain.surface, options.format);
  std::string obstacle = direct_obstacle(ctx, caps, format.format);
  if (options.path == PresentPath::copy) {
    obstacle = "the copy path was asked for (--present copy)";
  } else if (options.path == PresentPath::automatic && obstacle.empty() &&
             unorm_twin(format.format) != format.format) {
    // Valid (the images of a mutable-format swapchain are created as if with
    // VK_IMAGE_CREATE_EXTENDED_USAGE_BIT, so storage use through the UNORM view is allowed),
    // but the validation layer the tests run with reports it as
    // VUID-VkSwapchainCreateInfoKHR-imageFormat-01778; the copy costs one image copy.
    obstacle = "sRGB swapchain images take the copy path unless --present direct is given";
  }
  if (options.path == PresentPath::direct && !obstacle.empty()) {
    throw Error("cannot present directly (--present direct): " + obstacle);
  }
  const bool direct = obstacle.empty();
  const VkFormat twin = ctx.swapchain_mutable_format ? unorm_twin(format.format) : format.format;
  std::vector<VkFormat> view_formats = {format.format};
  if (direct && format.format != kStorageViewFormat) view_formats.push_back(kStorageViewFormat);
  if (twin != format.format && twin != view_formats.back()) view_formats.push_back(twin);
  const bool mutable_format = view_formats.size() > 1;

  VkExtent2D extent = caps.currentExtent;
  // 0xFFFFFFFF: the surface takes the swapchain's size, which the framebuffer's size decides.
  if (extent.width == 0xFFFFFFFFu) {
    extent.width = std::clamp(width, caps.minImageExtent.width, caps.maxImageExtent.width);
    extent.height = std::clamp(height, caps.minImageExtent.height, caps.maxImageExtent.height);
  }
  uint32_t image_count = caps.minImageCount + 1;
  if (caps.maxImageCount > 0) image_count = std::min(image_count, caps.maxImageCount);

  VkImageFormatListCreateInfo format_list{VK_STRUCTURE_TYPE_IMAGE_FORMAT_LIST_CREATE_INFO};
  format_list.viewFormatCount = uint32_t(view_formats.size());
  format_list.pViewFormats = view_formats.data();
  VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  if (mutable_format) {
    info.pNext = &format_list;
    info.flags = VK_SWAPCHAIN_CREATE_MUTABLE_FORMAT_BIT_KHR;
  }
  info.surface = chain.surface;
  info.minImageCount = image_count;
  info.imageFormat = format.format;
  info.imageColorSpace = format.colorSpace;
  info.imageExtent = extent;
  info.imageArrayLayers = 1;
  info.imageUsage = kSwapchainUsage | (direct ? VK_IMAGE_USAGE_STORAGE_BIT : 0);
  info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.preTransform = caps.currentTransform;
  info.compositeAlpha = (caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR)
                            ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
                            : VkCompositeAlphaFlagBitsKHR(caps.supportedCompositeAlpha &
                                                          -caps.supportedCompositeAlpha);
  info.presentMode = choose_present_mode(ctx, chain.surface, options.vsync);
  info.clipped = VK_TRUE;
  info.oldSwapchain = chain.swapchain;
  VkSwapchainKHR created = VK_NULL_HANDLE;
  VK_CHECK(vkCreateSwapchainKHR(ctx.device, &info, nullptr, &created));
  destroy_swapchain(ctx, chain);
  chain.swapchain = created;
  chain.format = format.format;
  chain.view_format = twin;
  chain.extent = extent;
  chain.present_mode = info.presentMode;
  chain.direct = direct;
  chain.path_reason = obstacle;

  uint32_t count = 0;
  VK_CHECK(vkGetSwapchainImagesKHR(ctx.device, chain.swapchain, &count, nullptr));
  chain.images.resize(count);
  VK_CHECK(vkGetSwapchainImagesKHR(ctx.device, chain.swapchain, &count, chain.images.data()));
  for (VkImage image : chain.images) {
    chain.views.push_back(
        create_view(ctx, image, chain.view_format, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT));
    if (direct) {
      chain.storage_views.push_back(
          create_view(ctx, image, kStorageViewFormat, VK_IMAGE_USAGE_STORAGE_BIT));
    }
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
