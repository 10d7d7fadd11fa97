#include "compute/present.h"

#include <cstring>

#include "compute/passes.h"
#include "compute/renderer_internal.h"
#include "compute/timestamps.h"
#include "compute/vk_check.h"
#include "core/check.h"

namespace tessera {
namespace {

// An image with the layout, stages and accesses of its last use, so that each use after it
// records one barrier from exactly that.
struct TrackedImage {
  VkImage image;
  VkImageLayout layout;
  VkPipelineStageFlags stage;
  VkAccessFlags access;
};

void use(VkCommandBuffer cmd, TrackedImage& t, VkImageLayout layout, VkPipelineStageFlags stage,
         VkAccessFlags access) {
  VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  b.srcAccessMask = t.access;
  b.dstAccessMask = access;
  b.oldLayout = t.layout;
  b.newLayout = layout;
  b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = t.image;
  b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCmdPipelineBarrier(cmd, t.stage, stage, 0, 0, nullptr, 0, nullptr, 1, &b);
  t = {t.image, layout, stage, access};
}

// Copies the renderer's shared set into image `i`'s set, binding that image's storage view
// where the resolve pass writes; again whenever the renderer has rewritten its set.
void refresh_set(const Context& ctx, Presenter& p, const Swapchain& chain,
                 const RendererInternal::SharedSet& shared, uint32_t i) {
  if (p.set_generations[i] == shared.generation) return;
  std::vector<VkCopyDescriptorSet> copies;
  for (const BindingInfo& b : kBindings) {
    if (b.binding == TS_BINDING_LDR_IMAGE) continue;
    VkCopyDescriptorSet c{VK_STRUCTURE_TYPE_COPY_DESCRIPTOR_SET};
    c.srcSet = shared.set;
    c.srcBinding = b.binding;
    c.dstSet = p.sets[i];
    c.dstBinding = b.binding;
    c.descriptorCount = 1;
    copies.push_back(c);
  }
  const VkDescriptorImageInfo target{VK_NULL_HANDLE, chain.storage_views[i],
                                     VK_IMAGE_LAYOUT_GENERAL};
  VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  w.dstSet = p.sets[i];
  w.dstBinding = TS_BINDING_LDR_IMAGE;
  w.descriptorCount = 1;
  w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
  w.pImageInfo = &target;
  vkUpdateDescriptorSets(ctx.device, 1, &w, uint32_t(copies.size()), copies.data());
  p.set_generations[i] = shared.generation;
}

// The resolve pass into the swapchain image, or into the display image and copied from there.
// `target` comes acquired, in UNDEFINED; it leaves holding the frame.
void record_resolve(const Context& ctx, Presenter& p, const Swapchain& chain, Renderer& renderer,
                    VkCommandBuffer cmd, uint32_t index, TrackedImage& target) {
  // The shading pass (in render()'s submission) wrote the HDR image the resolve pass reads.
  memory_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                 VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
  const bool bgra = is_bgra(chain.format);
  const RendererInternal::SharedSet shared = RendererInternal::shared_set(renderer);
  const bool timed = p.queries != VK_NULL_HANDLE;
  if (timed) vkCmdResetQueryPool(cmd, p.queries, 0, timestamp_pool_size(ctx, 2));
  if (chain.direct) {
    refresh_set(ctx, p, chain, shared, index);
    use(cmd, target, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
        VK_ACCESS_SHADER_WRITE_BIT);
    if (timed) write_timestamp(ctx, cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, p.queries, 0, 2);
    RendererInternal::record_resolve_into(renderer, cmd, p.sets[index], bgra);
    if (timed) write_timestamp(ctx, cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, p.queries, 1, 2);
    return;
  }
  // The display image stays in GENERAL between frames; the last frame's copy read it.
  TrackedImage source{renderer.output_image().image, VK_IMAGE_LAYOUT_GENERAL,
                      VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT};
  use(cmd, source, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
      VK_ACCESS_SHADER_WRITE_BIT);
  if (timed) write_timestamp(ctx, cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, p.queries, 0, 2);
  RendererInternal::record_resolve_into(renderer, cmd, shared.set, bgra);
  if (timed) write_timestamp(ctx, cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, p.queries, 1, 2);
  use(cmd, source, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
      VK_ACCESS_TRANSFER_READ_BIT);
  use(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
      VK_ACCESS_TRANSFER_WRITE_BIT);
  // A byte copy (the formats are size-compatible): the bytes are already in the swapchain's
  // order and encoding, which a blit into an sRGB image would encode again.
  VkImageCopy region{};
  region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.dstSubresource = region.srcSubresource;
  region.extent = {chain.extent.width, chain.extent.height, 1};
  vkCmdCopyImage(cmd, source.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target.image,
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
  // Back to GENERAL, ordered before the next frame's compute passes write it again.
  use(cmd, source, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
      VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_SHADER_READ_BIT);
}

void record_readback(const Context& ctx, Presenter& p, VkCommandBuffer cmd, TrackedImage& target,
                     VkExtent2D extent) {
  const VkDeviceSize bytes = VkDeviceSize(extent.width) * extent.height * 4;
  if (p.readback.size < bytes) {
    destroy_buffer(ctx, p.readback);
    p.readback = create_buffer(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryKind::readback);
  }
  use(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
      VK_ACCESS_TRANSFER_READ_BIT);
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {extent.width, extent.height, 1};
  vkCmdCopyImageToBuffer(cmd, target.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, p.readback.buffer,
                         1, &region);
  memory_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                 VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
}

// The read-back bytes as RGBA8: the image's bytes are the display image's, in its order.
Image8 read_screenshot(const Presenter& p, VkFormat format, VkExtent2D extent) {
  Image8 image{extent.width, extent.height,
               std::vector<glm::u8vec4>(size_t(extent.width) * extent.height)};
  std::memcpy(image.pixels.data(), p.readback.mapped, image.pixels.size() * 4);
  if (is_bgra(format)) {
    for (glm::u8vec4& texel : image.pixels) std::swap(texel.r, texel.b);
  }
  return image;
}

double resolve_ms(const Context& ctx, const Presenter& p) {
  uint64_t ticks[2] = {};
  VK_CHECK(vkGetQueryPoolResults(ctx.device, p.queries, 0, 2, sizeof(ticks), ticks,
                                 sizeof(uint64_t),
                                 VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
  const uint64_t mask =
      ctx.timestamp_valid_bits >= 64 ? ~0ull : (1ull << ctx.timestamp_valid_bits) - 1;
  const uint64_t delta = ((ticks[1] & mask) - (ticks[0] & mask)) & mask;
  return double(delta) * ctx.properties.limits.timestampPeriod * 1e-6;
}

void destroy_sets(const Context& ctx, Presenter& p) {
  if (p.pool) vkDestroyDescriptorPool(ctx.device, p.pool, nullptr);
  p.pool = VK_NULL_HANDLE;
  p.sets.clear();
  p.set_generations.clear();
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
  if (ctx.timestamp_valid_bits > 0) {
    VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    info.queryCount = timestamp_pool_size(ctx, 2);
    VK_CHECK(vkCreateQueryPool(ctx.device, &info, nullptr, &p.queries));
  }
}

void destroy_presenter(const Context& ctx, Presenter& p) {
  destroy_sets(ctx, p);
  destroy_buffer(ctx, p.readback);
  if (p.queries) vkDestroyQueryPool(ctx.device, p.queries, nullptr);
  if (p.acquired) vkDestroySemaphore(ctx.device, p.acquired, nullptr);
  if (p.done) vkDestroyFence(ctx.device, p.done, nullptr);
  if (p.cmd) vkFreeCommandBuffers(ctx.device, ctx.command_pool, 1, &p.cmd);
  p = Presenter{};
}

void prepare_presenter(const Context& ctx, Presenter& p, const Swapchain& chain,
                       const Renderer& renderer) {
  destroy_sets(ctx, p);
  if (!chain.direct) return;
  const uint32_t n = uint32_t(chain.images.size());
  std::vector<VkDescriptorPoolSize> sizes;
  for (const BindingInfo& b : kBindings) sizes.push_back({b.type, n});
  VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pool_info.maxSets = n;
  pool_info.poolSizeCount = uint32_t(sizes.size());
  pool_info.pPoolSizes = sizes.data();
  VK_CHECK(vkCreateDescriptorPool(ctx.device, &pool_info, nullptr, &p.pool));
  const std::vector<VkDescriptorSetLayout> layouts(n,
                                                   RendererInternal::shared_set(renderer).layout);
  VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  alloc.descriptorPool = p.pool;
  alloc.descriptorSetCount = n;
  alloc.pSetLayouts = layouts.data();
  p.sets.resize(n);
  VK_CHECK(vkAllocateDescriptorSets(ctx.device, &alloc, p.sets.data()));
  // No generation the renderer counts: each set is copied before its first use.
  p.set_generations.assign(n, ~0ull);
}

PresentResult present_frame(const Context& ctx, Presenter& p, const Swapchain& chain,
                            Renderer& renderer, const OverlayRecorder& overlay, Image8* screenshot,
                            FrameStats* stats) {
  TESSERA_CHECK(renderer.output_image().width == chain.extent.width &&
                renderer.output_image().height == chain.extent.height);
  TESSERA_CHECK(!chain.direct || p.sets.size() == chain.images.size());
  uint32_t index = 0;
  VkResult acquired = vkAcquireNextImageKHR(ctx.device, chain.swapchain, UINT64_MAX, p.acquired,
                                            VK_NULL_HANDLE, &index);
  if (acquired == VK_ERROR_OUT_OF_DATE_KHR) return PresentResult::out_of_date;
  if (acquired != VK_SUBOPTIMAL_KHR) vk_check(acquired, "vkAcquireNextImageKHR");

  // The first use of the image waits for the acquire semaphore: the direct path's resolve pass
  // writes it, the copy path's transfer does.
  const VkPipelineStageFlags wait_stage =
      chain.direct ? VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT : VK_PIPELINE_STAGE_TRANSFER_BIT;
  // Its old content is not needed; the layout transition follows the semaphore wait because
  // its barrier starts at the waiting stage.
  TrackedImage target{chain.images[index], VK_IMAGE_LAYOUT_UNDEFINED, wait_stage, 0};
  VK_CHECK(vkResetCommandBuffer(p.cmd, 0));
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VK_CHECK(vkBeginCommandBuffer(p.cmd, &begin));
  record_resolve(ctx, p, chain, renderer, p.cmd, index, target);
  if (screenshot) record_readback(ctx, p, p.cmd, target, chain.extent);
  if (overlay) {
    use(p.cmd, target, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
        VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
        VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT);
    overlay(p.cmd, index);
  } else {
    // Presentation needs no access mask: the semaphore signal makes the writes available.
    use(p.cmd, target, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0);
  }
  VK_CHECK(vkEndCommandBuffer(p.cmd));

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
  if (stats && p.queries && stats->has_timestamps) {
    const double ms = resolve_ms(ctx, p);
    stats->pass_ms[size_t(Pass::resolve)] += ms;
    stats->gpu_total_ms += ms;
  }
  if (presented == VK_ERROR_OUT_OF_DATE_KHR) return PresentResult::out_of_date;
  if (presented == VK_SUBOPTIMAL_KHR || acquired == VK_SUBOPTIMAL_KHR) {
    return PresentResult::presented_suboptimal;
  }
  vk_check(presented, "vkQueuePresentKHR");
  return PresentResult::presented;
}

}  // namespace tessera
