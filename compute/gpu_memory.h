#pragma once
// Buffers, storage images and one-off command submission. Each resource owns one dedicated
// allocation: Tessera makes a few dozen of them, far below any allocation-count limit.

#include <functional>

#include <vulkan/vulkan.h>

#include "compute/context.h"

namespace tessera {

enum class MemoryKind {
  device,    // device-local, for GPU-only data
  upload,    // host-visible and coherent, mapped: staging and per-frame constants
  readback,  // host-visible (cached when available), mapped: copies back to the host
  // Device-local and, where the device has such a type (resizable BAR, integrated and CPU
  // devices), also host-visible, coherent and mapped: GPU-side data the host resets between
  // submissions. `Buffer::mapped` stays null where no such type exists.
  device_mapped,
};

struct Buffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkDeviceSize size = 0;
  void* mapped = nullptr;  // set for MemoryKind::upload and ::readback (and ::device_mapped where
                           // the device has a host-visible device-local type)
  // Where the shaders find it (a buffer reference): set for a buffer created with
  // VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT, whose memory is then allocated with
  // VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT (the context enables bufferDeviceAddress).
  VkDeviceAddress address = 0;
};

/// Creates a buffer of `size` bytes (> 0). Throws Error if the device is out of memory.
Buffer create_buffer(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage,
                     MemoryKind kind);
/// Destroys `buffer` (if any) and resets it to empty.
void destroy_buffer(const Context& ctx, Buffer& buffer);

struct StorageImage {
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;
  uint32_t width = 0;
  uint32_t height = 0;
  uint32_t levels = 1;  // mip levels
  uint32_t layers = 1;  // 6 for a cube
};

/// Creates a device-local 2D image of `usage` with a view on `aspect`, in layout UNDEFINED.
StorageImage create_image(const Context& ctx, uint32_t width, uint32_t height, VkFormat format,
                          VkImageUsageFlags usage, VkImageAspectFlags aspect);

/// The same with `levels` mip levels, and as a cube (6 layers, a cube view) if `cube`.
StorageImage create_image(const Context& ctx, uint32_t width, uint32_t height, uint32_t levels,
                          bool cube, VkFormat format, VkImageUsageFlags usage,
                          VkImageAspectFlags aspect);

/// Creates a 2D image usable as a storage image and as a copy and blit source (so a window can
/// present it), and leaves it in VK_IMAGE_LAYOUT_GENERAL, where it stays.
StorageImage create_storage_image(const Context& ctx, uint32_t width, uint32_t height,
                                  VkFormat format, VkImageUsageFlags extra_usage = 0);
void destroy_image(const Context& ctx, StorageImage& image);

/// Records commands with `record` into the context's command buffer (Context::submission),
/// submits it and waits for it. One submission at a time per context; `record` must not submit.
void submit_and_wait(const Context& ctx, const std::function<void(VkCommandBuffer)>& record);

/// A global memory barrier from `src` stages/accesses to `dst` stages/accesses.
void memory_barrier(VkCommandBuffer cmd, VkPipelineStageFlags src_stage, VkAccessFlags src_access,
                    VkPipelineStageFlags dst_stage, VkAccessFlags dst_access);

}  // namespace tessera
