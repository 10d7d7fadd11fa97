#include "compute/gpu_memory.h"

#include <string>
#include <thread>

#include "compute/vk_check.h"
#include "core/check.h"

namespace tessera {
namespace {

constexpr VkMemoryPropertyFlags kMappable =
    VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;

uint32_t find_memory_type(const Context& ctx, uint32_t type_bits, VkMemoryPropertyFlags wanted,
                          VkMemoryPropertyFlags preferred) {
  const VkPhysicalDeviceMemoryProperties& props = ctx.memory_properties;
  for (VkMemoryPropertyFlags flags : {wanted | preferred, wanted}) {
    for (uint32_t i = 0; i < props.memoryTypeCount; ++i) {
      if ((type_bits & (1u << i)) && (props.memoryTypes[i].propertyFlags & flags) == flags)
        return i;
    }
  }
  throw Error("the device has no memory type with the properties " + std::to_string(wanted));
}

VkDeviceMemory allocate(const Context& ctx, VkMemoryRequirements req, MemoryKind kind,
                        bool& mappable, VkMemoryAllocateFlags flags = 0) {
  VkMemoryPropertyFlags wanted = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
  VkMemoryPropertyFlags preferred = 0;
  if (kind == MemoryKind::device_mapped) preferred = kMappable;
  if (kind == MemoryKind::upload) {
    wanted = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  } else if (kind == MemoryKind::readback) {
    wanted = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    preferred = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
  }
  VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  info.allocationSize = req.size;
  info.memoryTypeIndex = find_memory_type(ctx, req.memoryTypeBits, wanted, preferred);
  VkMemoryAllocateFlagsInfo flags_info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
  flags_info.flags = flags;
  if (flags) info.pNext = &flags_info;
  mappable = (ctx.memory_properties.memoryTypes[info.memoryTypeIndex].propertyFlags & kMappable) ==
             kMappable;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkResult result = vkAllocateMemory(ctx.device, &info, nullptr, &memory);
  if (result == VK_ERROR_OUT_OF_DEVICE_MEMORY || result == VK_ERROR_OUT_OF_HOST_MEMORY) {
    throw Error("out of memory allocating " + std::to_string(req.size >> 20) + " MiB on " +
                ctx.properties.deviceName);
  }
  vk_check(result, "vkAllocateMemory");
  return memory;
}

}  // namespace

Buffer create_buffer(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage,
                     MemoryKind kind) {
  TESSERA_CHECK(size > 0);
  Buffer b;
  b.size = size;
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = size;
  info.usage = usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VK_CHECK(vkCreateBuffer(ctx.device, &info, nullptr, &b.buffer));
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(ctx.device, b.buffer, &req);
  bool mappable = false;
  const bool by_address = usage & VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
  try {
    b.memory =
        allocate(ctx, req, kind, mappable, by_address ? VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT : 0);
  } catch (...) {
    vkDestroyBuffer(ctx.device, b.buffer, nullptr);
    throw;
  }
  VK_CHECK(vkBindBufferMemory(ctx.device, b.buffer, b.memory, 0));
  if (by_address) {
    VkBufferDeviceAddressInfo address{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
    address.buffer = b.buffer;
    b.address = vkGetBufferDeviceAddress(ctx.device, &address);
  }
  if (kind != MemoryKind::device && mappable)
    VK_CHECK(vkMapMemory(ctx.device, b.memory, 0, size, 0, &b.mapped));
  return b;
}

void destroy_buffer(const Context& ctx, Buffer& b) {
  if (b.buffer) vkDestroyBuffer(ctx.device, b.buffer, nullptr);
  if (b.memory) vkFreeMemory(ctx.device, b.memory, nullptr);
  b = Buffer{};
}

StorageImage create_image(const Context& ctx, uint32_t width, uint32_t height, VkFormat format,
                          VkImageUsageFlags usage, VkImageAspectFlags aspect) {
  return create_image(ctx, width, height, 1, false, format, usage, aspect);
}

StorageImage create_image(const Context& ctx, uint32_t width, uint32_t height, uint32_t levels,
                          bool cube, VkFormat format, VkImageUsageFlags usage,
                          VkImageAspectFlags aspect) {
  StorageImage img;
  img.format = format;
  img.width = width;
  img.height = height;
  img.levels = levels;
  img.layers = cube ? 6 : 1;
  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.flags = cube ? VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT : 0;
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = format;
  info.extent = {width, height, 1};
  info.mipLevels = levels;
  info.arrayLayers = img.layers;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = usage;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  VK_CHECK(vkCreateImage(ctx.device, &info, nullptr, &img.image));
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(ctx.device, img.image, &req);
  bool mappable = false;  // not mapped: images are only read back through copies
  try {
    img.memory = allocate(ctx, req, MemoryKind::device, mappable);
  } catch (...) {
    vkDestroyImage(ctx.device, img.image, nullptr);
    throw;
  }
  VK_CHECK(vkBindImageMemory(ctx.device, img.image, img.memory, 0));
  VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  view.image = img.image;
  view.viewType = cube ? VK_IMAGE_VIEW_TYPE_CUBE : VK_IMAGE_VIEW_TYPE_2D;
  view.format = format;
  view.subresourceRange = {aspect, 0, levels, 0, img.layers};
  VK_CHECK(vkCreateImageView(ctx.device, &view, nullptr, &img.view));
  return img;
}

StorageImage create_storage_image(const Context& ctx, uint32_t width, uint32_t height,
                                  VkFormat format, VkImageUsageFlags extra_usage) {
  StorageImage img =
      create_image(ctx, width, height, format,
                   VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | extra_usage,
                   VK_IMAGE_ASPECT_COLOR_BIT);
  submit_and_wait(ctx, [&](VkCommandBuffer cmd) {
    VkImageMemoryBarrier barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    barrier.srcAccessMask = 0;
    barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
    barrier.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    barrier.newLayout = VK_IMAGE_LAYOUT_GENERAL;
    barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.image = img.image;
    barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT,
                         VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0, nullptr, 0, nullptr, 1,
                         &barrier);
  });
  return img;
}

void destroy_image(const Context& ctx, StorageImage& img) {
  if (img.view) vkDestroyImageView(ctx.device, img.view, nullptr);
  if (img.image) vkDestroyImage(ctx.device, img.image, nullptr);
  if (img.memory) vkFreeMemory(ctx.device, img.memory, nullptr);
  img = StorageImage{};
}

void submit_and_wait(const Context& ctx, const std::function<void(VkCommandBuffer)>& record) {
  Submission& sub = *ctx.submission;
  // A `record` that submits again would re-record the buffer it is recording into.
  TESSERA_CHECK(sub.recording.load() != std::this_thread::get_id());
  std::lock_guard lock(sub.mutex);
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  // Beginning resets the buffer (the pool has VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT).
  VK_CHECK(vkBeginCommandBuffer(sub.cmd, &begin));
  sub.recording = std::this_thread::get_id();
  try {
    record(sub.cmd);
  } catch (...) {
    // Leave the buffer initial, not recording, for the next submission to begin.
    sub.recording = std::thread::id();
    vkResetCommandBuffer(sub.cmd, 0);
    throw;
  }
  sub.recording = std::thread::id();
  VK_CHECK(vkEndCommandBuffer(sub.cmd));
  VK_CHECK(vkResetFences(ctx.device, 1, &sub.fence));
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &sub.cmd;
  VkResult result = vkQueueSubmit(ctx.queue, 1, &submit, sub.fence);
  if (result == VK_SUCCESS) {
    result = vkWaitForFences(ctx.device, 1, &sub.fence, VK_TRUE, UINT64_MAX);
  }
  vk_check(result, "vkQueueSubmit/vkWaitForFences");
}

void memory_barrier(VkCommandBuffer cmd, VkPipelineStageFlags src_stage, VkAccessFlags src_access,
                    VkPipelineStageFlags dst_stage, VkAccessFlags dst_access) {
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = src_access;
  barrier.dstAccessMask = dst_access;
  vkCmdPipelineBarrier(cmd, src_stage, dst_stage, 0, 1, &barrier, 0, nullptr, 0, nullptr);
}

}  // namespace tessera
