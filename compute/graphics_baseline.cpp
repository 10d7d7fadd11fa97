#include "compute/graphics_baseline.h"

#include <cstring>
#include <string>

#include "compute/gpu_memory.h"
#include "compute/vk_check.h"
#include "core/check.h"
#include "shaders/shader_registry.h"

namespace tessera {
namespace {

constexpr VkFormat kIdFormat = VK_FORMAT_R32_UINT;
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

struct Attachment {
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
};

Attachment create_attachment(const Context& ctx, uint32_t w, uint32_t h, VkFormat format,
                             VkImageUsageFlags usage, VkImageAspectFlags aspect) {
  Attachment a;
  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = format;
  info.extent = {w, h, 1};
  info.mipLevels = 1;
  info.arrayLayers = 1;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = usage;
  VK_CHECK(vkCreateImage(ctx.device, &info, nullptr, &a.image));
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(ctx.device, a.image, &req);
  VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  alloc.allocationSize = req.size;
  alloc.memoryTypeIndex = UINT32_MAX;
  for (uint32_t i = 0; i < ctx.memory_properties.memoryTypeCount; ++i) {
    if ((req.memoryTypeBits & (1u << i)) && (ctx.memory_properties.memoryTypes[i].propertyFlags &
                                             VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT)) {
      alloc.memoryTypeIndex = i;
      break;
    }
  }
  if (alloc.memoryTypeIndex == UINT32_MAX) throw Error("no device-local memory for an attachment");
  VK_CHECK(vkAllocateMemory(ctx.device, &alloc, nullptr, &a.memory));
  VK_CHECK(vkBindImageMemory(ctx.device, a.image, a.memory, 0));
  VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  view.image = a.image;
  view.viewType = VK_IMAGE_VIEW_TYPE_2D;
  view.format = format;
  view.subresourceRange = {aspect, 0, 1, 0, 1};
  VK_CHECK(vkCreateImageView(ctx.device, &view, nullptr, &a.view));
  return a;
}

void destroy_attachment(const Context& ctx, Attachment& a) {
  vkDestroyImageView(ctx.device, a.view, nullptr);
  vkDestroyImage(ctx.device, a.image, nullptr);
  vkFreeMemory(ctx.device, a.memory, nullptr);
}

VkShaderModule shader_module(const Context& ctx, const char* name) {
  std::span<const uint32_t> code = find_shader(name);
  TESSERA_CHECK(!code.empty());
  VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  info.codeSize = code.size_bytes();
  info.pCode = code.data();
  VkShaderModule m = VK_NULL_HANDLE;
  VK_CHECK(vkCreateShaderModule(ctx.device, &info, nullptr, &m));
  return m;
}

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

VkPipeline create_pipeline(const Context& ctx, VkRenderPass pass, VkPipelineLayout layout,
                           uint32_t w, uint32_t h) {
  VkShaderModule vert = shader_module(ctx, "baseline_ids_vert");
  VkShaderModule frag = shader_module(ctx, "baseline_ids_frag");
  VkPipelineShaderStageCreateInfo stages[2] = {};
  stages[0].sType = stages[1].sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  stages[0].module = vert;
  stages[0].pName = "main";
  stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
  stages[1].module = frag;
  stages[1].pName = "main";
  VkVertexInputBindingDescription binding{0, sizeof(glm::vec4), VK_VERTEX_INPUT_RATE_VERTEX};
  VkVertexInputAttributeDescription attribute{0, 0, VK_FORMAT_R32G32B32A32_SFLOAT, 0};
  VkPipelineVertexInputStateCreateInfo input{
      VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  input.vertexBindingDescriptionCount = 1;
  input.pVertexBindingDescriptions = &binding;
  input.vertexAttributeDescriptionCount = 1;
  input.pVertexAttributeDescriptions = &attribute;
  VkPipelineInputAssemblyStateCreateInfo assembly{
      VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkViewport viewport{0, 0, float(w), float(h), 0, 1};
  VkRect2D scissor{{0, 0}, {w, h}};
  VkPipelineViewportStateCreateInfo vp{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  vp.viewportCount = 1;
  vp.pViewports = &viewport;
  vp.scissorCount = 1;
  vp.pScissors = &scissor;
  VkPipelineRasterizationStateCreateInfo raster{
      VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = VK_CULL_MODE_NONE;
  raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  raster.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo ds{
      VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  ds.depthTestEnable = VK_TRUE;
  ds.depthWriteEnable = VK_TRUE;
  ds.depthCompareOp = VK_COMPARE_OP_LESS;
  VkPipelineColorBlendAttachmentState blend{};
  blend.colorWriteMask = VK_COLOR_COMPONENT_R_BIT;
  VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  cb.attachmentCount = 1;
  cb.pAttachments = &blend;
  VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  info.stageCount = 2;
  info.pStages = stages;
  info.pVertexInputState = &input;
  info.pInputAssemblyState = &assembly;
  info.pViewportState = &vp;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &ms;
  info.pDepthStencilState = &ds;
  info.pColorBlendState = &cb;
  info.layout = layout;
  info.renderPass = pass;
  VkPipeline pipeline = VK_NULL_HANDLE;
  VkResult result =
      vkCreateGraphicsPipelines(ctx.device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline);
  vkDestroyShaderModule(ctx.device, vert, nullptr);
  vkDestroyShaderModule(ctx.device, frag, nullptr);
  vk_check(result, "vkCreateGraphicsPipelines(baseline_ids)");
  return pipeline;
}

}  // namespace

std::vector<uint32_t> hardware_triangle_ids(const Context& ctx,
                                            const std::vector<glm::vec4>& clip_positions,
                                            uint32_t width, uint32_t height) {
  TESSERA_CHECK(clip_positions.size() % 3 == 0);
  TESSERA_CHECK(width > 0 && height > 0);
  uint32_t families = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(ctx.physical_device, &families, nullptr);
  std::vector<VkQueueFamilyProperties> props(families);
  vkGetPhysicalDeviceQueueFamilyProperties(ctx.physical_device, &families, props.data());
  if (!(props[ctx.queue_family].queueFlags & VK_QUEUE_GRAPHICS_BIT)) {
    throw Error(std::string("device '") + ctx.properties.deviceName +
                "' has no graphics queue for the baseline");
  }

  Attachment ids =
      create_attachment(ctx, width, height, kIdFormat,
                        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                        VK_IMAGE_ASPECT_COLOR_BIT);
  Attachment depth =
      create_attachment(ctx, width, height, kDepthFormat,
                        VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT);
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
  VkPipeline pipeline = create_pipeline(ctx, pass, layout, width, height);

  const VkDeviceSize vertex_bytes =
      std::max<VkDeviceSize>(clip_positions.size() * sizeof(glm::vec4), 16);
  Buffer vertices =
      create_buffer(ctx, vertex_bytes, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, MemoryKind::upload);
  if (!clip_positions.empty())
    std::memcpy(vertices.mapped, clip_positions.data(), clip_positions.size() * 16);
  Buffer readback = create_buffer(ctx, VkDeviceSize(width) * height * 4,
                                  VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryKind::readback);

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
  destroy_attachment(ctx, depth);
  destroy_attachment(ctx, ids);
  return out;
}

}  // namespace tessera
