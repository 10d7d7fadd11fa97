#include "compute/baselines/graphics_baseline.h"

#include <cstring>
#include <string>

#include "compute/baselines/graphics_util.h"
#include "compute/gpu_memory.h"
#include "compute/timestamps.h"
#include "compute/vk_check.h"
#include "core/check.h"

namespace tessera {
namespace {

constexpr VkFormat kIdFormat = VK_FORMAT_R32_UINT;
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

VkRenderPass create_render_pass(const Context& ctx) {
  VkAttachmentDescription attachments[2] = {};
  attachments[0].format = kIdFormat;
  attachments[0].samples = VK_SAMPLE_COUNT_1_BIT;
  attachments[0].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  attachments[0].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  attachments[0].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  attachments[0].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  attachments[0].initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  attachments[0].finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  attachments[1] = attachments[0];
  attachments[1].format = kDepthFormat;
  attachments[1].storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  attachments[1].finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
  VkAttachmentReference color{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkAttachmentReference depth{1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &color;
  subpass.pDepthStencilAttachment = &depth;
  // The copy of the id image after the pass waits for its writes.
  VkSubpassDependency after{0,
                            VK_SUBPASS_EXTERNAL,
                            VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                            VK_PIPELINE_STAGE_TRANSFER_BIT,
                            VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                            VK_ACCESS_TRANSFER_READ_BIT,
                            0};
  VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  info.attachmentCount = 2;
  info.pAttachments = attachments;
  info.subpassCount = 1;
  info.pSubpasses = &subpass;
  info.dependencyCount = 1;
  info.pDependencies = &after;
  VkRenderPass pass = VK_NULL_HANDLE;
  VK_CHECK(vkCreateRenderPass(ctx.device, &info, nullptr, &pass));
  return pass;
}

}  // namespace

std::vector<uint32_t> hardware_triangle_ids(const Context& ctx,
                                            const std::vector<glm::vec4>& clip_positions,
                                            uint32_t width, uint32_t height) {
  TESSERA_CHECK(clip_positions.size() % 3 == 0);
  TESSERA_CHECK(width > 0 && height > 0);
  require_graphics_queue(ctx);

  Attachment ids =
      create_image(ctx, width, height, kIdFormat,
                   VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                   VK_IMAGE_ASPECT_COLOR_BIT);
  Attachment depth =
      create_image(ctx, width, height, kDepthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                   VK_IMAGE_ASPECT_DEPTH_BIT);
  VkRenderPass pass = create_render_pass(ctx);
  VkImageView views[2] = {ids.view, depth.view};
  VkFramebufferCreateInfo fb_info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
  fb_info.renderPass = pass;
  fb_info.attachmentCount = 2;
  fb_info.pAttachments = views;
  fb_info.width = width;
  fb_info.height = height;
  fb_info.layers = 1;
  VkFramebuffer framebuffer = VK_NULL_HANDLE;
  VK_CHECK(vkCreateFramebuffer(ctx.device, &fb_info, nullptr, &framebuffer));
  VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VK_CHECK(vkCreatePipelineLayout(ctx.device, &layout_info, nullptr, &layout));
  const GraphicsPipelineDesc desc{
      "baseline_ids_vert", "baseline_ids_frag", true,
      VK_CULL_MODE_NONE,   VK_COMPARE_OP_LESS,  VK_COLOR_COMPONENT_R_BIT};
  VkPipeline pipeline = create_graphics_pipeline(ctx, pass, layout, desc);

  const VkDeviceSize vertex_bytes =
      std::max<VkDeviceSize>(clip_positions.size() * sizeof(glm::vec4), 16);
  Buffer vertices =
      create_buffer(ctx, vertex_bytes, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, MemoryKind::upload);
  if (!clip_positions.empty())
    std::memcpy(vertices.mapped, clip_positions.data(), clip_positions.size() * 16);
  Buffer readback = create_buffer(ctx, VkDeviceSize(width) * height * 4,
                                  VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryKind::readback);

  note_render_pass(ctx);
  submit_and_wait(ctx, [&](VkCommandBuffer cmd) {
    memory_barrier(cmd, VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_WRITE_BIT,
                   VK_PIPELINE_STAGE_VERTEX_INPUT_BIT, VK_ACCESS_VERTEX_ATTRIBUTE_READ_BIT);
    VkClearValue clears[2];
    clears[0].color.uint32[0] = 0xFFFFFFFFu;
    clears[1].depthStencil = {1.0f, 0};
    VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    begin.renderPass = pass;
    begin.framebuffer = framebuffer;
    begin.renderArea = {{0, 0}, {width, height}};
    begin.clearValueCount = 2;
    begin.pClearValues = clears;
    vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
    const VkViewport viewport{0, 0, float(width), float(height), 0, 1};
    const VkRect2D scissor{{0, 0}, {width, height}};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &vertices.buffer, &offset);
    vkCmdDraw(cmd, uint32_t(clip_positions.size()), 1, 0, 0);
    vkCmdEndRenderPass(cmd);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {width, height, 1};
    vkCmdCopyImageToBuffer(cmd, ids.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback.buffer, 1,
                           &region);
    memory_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                   VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
  });
  std::vector<uint32_t> out(size_t(width) * height);
  std::memcpy(out.data(), readback.mapped, out.size() * 4);

  destroy_buffer(ctx, readback);
  destroy_buffer(ctx, vertices);
  vkDestroyPipeline(ctx.device, pipeline, nullptr);
  vkDestroyPipelineLayout(ctx.device, layout, nullptr);
  vkDestroyFramebuffer(ctx.device, framebuffer, nullptr);
  vkDestroyRenderPass(ctx.device, pass, nullptr);
  destroy_image(ctx, depth);
  destroy_image(ctx, ids);
  return out;
}

}  // namespace tessera
