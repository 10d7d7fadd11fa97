#pragma once
// Copies of GPU buffers and images back to the host, for read-back after a frame.

#include <cstring>
#include <vector>

#include "compute/gpu_memory.h"

namespace tessera {

/// Copies `count` elements of `src` from element `first` on to the host (waits for the copy).
template <typename T>
std::vector<T> download_buffer(const Context& ctx, const Buffer& src, uint64_t count,
                               uint64_t first = 0) {
  std::vector<T> out(count);
  if (count == 0) return out;
  const VkDeviceSize bytes = count * sizeof(T);
  Buffer staging =
      create_buffer(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryKind::readback);
  submit_and_wait(ctx, [&](VkCommandBuffer cmd) {
    memory_barrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_WRITE_BIT,
                   VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
    VkBufferCopy region{first * sizeof(T), 0, bytes};
    vkCmdCopyBuffer(cmd, src.buffer, staging.buffer, 1, &region);
    memory_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                   VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
  });
  std::memcpy(out.data(), staging.mapped, bytes);
  destroy_buffer(ctx, staging);
  return out;
}

/// Copies all texels of `image` (in VK_IMAGE_LAYOUT_GENERAL) to the host, as
/// `elements_per_texel` values of T each, rows top to bottom.
template <typename T>
std::vector<T> download_image(const Context& ctx, const StorageImage& image,
                              uint32_t elements_per_texel) {
  const uint64_t count = uint64_t(image.width) * image.height * elements_per_texel;
  std::vector<T> out(count);
  const VkDeviceSize bytes = count * sizeof(T);
  Buffer staging =
      create_buffer(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryKind::readback);
  submit_and_wait(ctx, [&](VkCommandBuffer cmd) {
    // To TRANSFER_SRC_OPTIMAL for the copy and back to GENERAL, where the passes expect it.
    VkImageMemoryBarrier to_copy{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    to_copy.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
    to_copy.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
    to_copy.oldLayout = VK_IMAGE_LAYOUT_GENERAL;
    to_copy.newLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    to_copy.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    to_copy.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    to_copy.image = image.image;
    to_copy.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0,
                         0, nullptr, 0, nullptr, 1, &to_copy);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {image.width, image.height, 1};
    vkCmdCopyImageToBuffer(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.buffer,
                           1, &region);
    VkImageMemoryBarrier back = to_copy;
    back.srcAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
    back.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
    back.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    back.newLayout = VK_IMAGE_LAYOUT_GENERAL;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT,
                         VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT, 0,
                         0, nullptr, 0, nullptr, 1, &back);
    memory_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                   VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
  });
  std::memcpy(out.data(), staging.mapped, bytes);
  destroy_buffer(ctx, staging);
  return out;
}

}  // namespace tessera
