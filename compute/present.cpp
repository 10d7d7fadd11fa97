#include "compute/present.h"

#include <cstring>

#include "compute/vk_check.h"
#include "core/check.h"

namespace tessera {
namespace {

VkImageMemoryBarrier image_barrier(VkImage image, VkAccessFlags src, VkAccessFlags dst,
                                   VkImageLayout from, VkImageLayout to) {
  VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  b.srcAccessMask = src;
  b.dstAccessMask = dst;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  return b;
}

void barrier(VkCommandBuffer cmd, VkPipelineStageFlags src, VkPipelineStageFlags dst,
             const VkImageMemoryBarrier& b) {
  vkCmdPipelineBarrier(cmd, src, dst, 0, 0, nullptr, 0, nullptr, 1, &b);
}

void record_blit(VkCommandBuffer cmd, const StorageImage& source, VkImage target,
                 VkExtent2D extent) {
  // The compute passes wrote the source, which they keep in GENERAL; the swapchain image's
  // old content is not needed. The swapchain image's transition starts at the stage the
  // acquire semaphore is waited at, so it follows the wait.
  barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
          image_barrier(source.image, VK_ACCESS_SHADER_WRITE_BIT, VK_ACCESS_TRANSFER_READ_BIT,
                        VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL));
  barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
          image_barrier(target, 0, VK_ACCESS_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                        VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL));
  // Same size, nearest: every texel is converted on its own, UNORM to UNORM keeps its bytes.
  VkImageBlit region{};
  region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.dstSubresource = region.srcSubresource;
  region.srcOffsets[1] = {int32_t(extent.width), int32_t(extent.height), 1};
  region.dstOffsets[1] = region.srcOffsets[1];
  vkCmdBlitImage(cmd, source.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target,
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region, VK_FILTER_NEAREST);
  // Back to GENERAL, ordered before the next frame's compute passes write it again.
  barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
          image_barrier(source.image, VK_ACCESS_TRANSFER_READ_BIT,
                        VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_SHADER_READ_BIT,
                        VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL));
}

void record_readback(const Context& ctx, Presenter& p, VkCommandBuffer cmd, VkImage target,
                     VkExtent2D extent) {
  const VkDeviceSize bytes = VkDeviceSize(extent.width) * extent.height * 4;
  if (p.readback.size < bytes) {
    destroy_buffer(ctx, p.readback);
    p.readback = create_buffer(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryKind::readback);
  }
  barrier(
      cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
      image_barrier(target, VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_TRANSFER_READ_BIT,
                    VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL));
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {extent.width, extent.height, 1};
  vkCmdCopyImageToBuffer(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, p.readback.buffer, 1,
                         &region);
  memory_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                 VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
  barrier(
      cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
      image_barrier(target, VK_ACCESS_TRANSFER_READ_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                    VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL));
}

Image8 read_screenshot(const Presenter& p, VkFormat format, VkExtent2D extent) {
  Image8 image{extent.width, extent.height,
               std::vector<glm::u8vec4>(size_t(extent.width) * extent.height)};
  std::memcpy(image.pixels.data(), p.readback.mapped, image.pixels.size() * 4);
  if (format == VK_FORMAT_B8G8R8A8_UNORM) {
    for (glm::u8vec4& texel : image.pixels) std::swap(texel.r, texel.b);
  }
  return image;
}

}  // namespace

void create_presenter(const Context& ctx, Presenter& p) {
  VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  alloc.commandPool = ctx.command_pool;
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  VK_CHECK(vkAllocateCommandBuffers(ctx.device, &alloc, &p.cmd));
  VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VK_CHECK(vkCreateFence(ctx.device, &fence_info, nullptr, &p.done));
  VkSemaphoreCreateInfo sem_info{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  VK_CHECK(vkCreateSemaphore(ctx.device, &sem_info, nullptr, &p.acquired));
}

void destroy_presenter(const Context& ctx, Presenter& p) {
  destroy_buffer(ctx, p.readback);
  if (p.acquired) vkDestroySemaphore(ctx.device, p.acquired, nullptr);
  if (p.done) vkDestroyFence(ctx.device, p.done, nullptr);
  if (p.cmd) vkFreeCommandBuffers(ctx.device, ctx.command_pool, 1, &p.cmd);
  p = Presenter{};
}

PresentResult present_frame(const Context& ctx, Presenter& p, const Swapchain& chain,
                            const StorageImage& source, const OverlayRecorder& overlay,
                            Image8* screenshot) {
  TESSERA_CHECK(source.width == chain.extent.width && source.height == chain.extent.height);
  uint32_t index = 0;
  VkResult acquired = vkAcquireNextImageKHR(ctx.device, chain.swapchain, UINT64_MAX, p.acquired,
                                            VK_NULL_HANDLE, &index);
  if (acquired == VK_ERROR_OUT_OF_DATE_KHR) return PresentResult::out_of_date;
  if (acquired != VK_SUBOPTIMAL_KHR) vk_check(acquired, "vkAcquireNextImageKHR");

  VkImage target = chain.images[index];
  VK_CHECK(vkResetCommandBuffer(p.cmd, 0));
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VK_CHECK(vkBeginCommandBuffer(p.cmd, &begin));
  record_blit(p.cmd, source, target, chain.extent);
  if (screenshot) record_readback(ctx, p, p.cmd, target, chain.extent);
  if (overlay) {
    barrier(p.cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
            image_barrier(
                target, VK_ACCESS_TRANSFER_WRITE_BIT,
                VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL));
    overlay(p.cmd, index);
  } else {
    // Presentation needs no access mask: the semaphore signal makes the writes available.
    barrier(p.cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT,
            image_barrier(target, VK_ACCESS_TRANSFER_WRITE_BIT, 0,
                          VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR));
  }
  VK_CHECK(vkEndCommandBuffer(p.cmd));

  const VkPipelineStageFlags wait_stage = VK_PIPELINE_STAGE_TRANSFER_BIT;
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.waitSemaphoreCount = 1;
  submit.pWaitSemaphores = &p.acquired;
  submit.pWaitDstStageMask = &wait_stage;
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &p.cmd;
  submit.signalSemaphoreCount = 1;
  submit.pSignalSemaphores = &chain.rendered[index];
  VK_CHECK(vkResetFences(ctx.device, 1, &p.done));
  VK_CHECK(vkQueueSubmit(ctx.queue, 1, &submit, p.done));

  VkPresentInfoKHR present{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  present.waitSemaphoreCount = 1;
  present.pWaitSemaphores = &chain.rendered[index];
  present.swapchainCount = 1;
  present.pSwapchains = &chain.swapchain;
  present.pImageIndices = &index;
  const VkResult presented = vkQueuePresentKHR(ctx.queue, &present);
  VK_CHECK(vkWaitForFences(ctx.device, 1, &p.done, VK_TRUE, UINT64_MAX));
  if (screenshot) *screenshot = read_screenshot(p, chain.format, chain.extent);
  if (presented == VK_ERROR_OUT_OF_DATE_KHR) return PresentResult::out_of_date;
  if (presented == VK_SUBOPTIMAL_KHR || acquired == VK_SUBOPTIMAL_KHR) {
    return PresentResult::presented_suboptimal;
  }
  vk_check(presented, "vkQueuePresentKHR");
  return PresentResult::presented;
}

}  // namespace tessera
