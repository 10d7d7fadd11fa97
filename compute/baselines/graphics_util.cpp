#include "compute/baselines/graphics_util.h"

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "compute/baselines/baseline_shaders.h"
#include "compute/pipelines.h"
#include "compute/vk_check.h"
#include "core/check.h"
#include "shaders/shared/gpu_types.h"

namespace tessera {

void require_graphics_queue(const Context& ctx) {
  uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(ctx.physical_device, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(ctx.physical_device, &count, families.data());
  if (!(families[ctx.queue_family].queueFlags & VK_QUEUE_GRAPHICS_BIT)) {
    throw Error(std::string("device '") + ctx.properties.deviceName +
                "' has no graphics queue for the baseline");
  }
}

double timestamp_interval_ms(const Context& ctx, uint64_t begin, uint64_t end) {
  const uint64_t mask =
      ctx.timestamp_valid_bits >= 64 ? ~0ull : (1ull << ctx.timestamp_valid_bits) - 1;
  return double(((end & mask) - (begin & mask)) & mask) * ctx.properties.limits.timestampPeriod *
         1e-6;
}

VkPipeline create_graphics_pipeline(const Context& ctx, VkRenderPass pass, VkPipelineLayout layout,
                                    const GraphicsPipelineDesc& desc) {
  VkShaderModule vert = create_shader_module(
      ctx, desc.vertex_code.empty() ? find_baseline_shader(desc.vertex_shader) : desc.vertex_code);
  VkShaderModule frag = create_shader_module(ctx, desc.fragment_code.empty()
                                                      ? find_baseline_shader(desc.fragment_shader)
                                                      : desc.fragment_code);
  VkPipelineShaderStageCreateInfo stages[2] = {};
  stages[0].sType = stages[1].sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  stages[0].module = vert;
  stages[0].pName = "main";
  stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
  stages[1].module = frag;
  stages[1].pName = "main";
  const std::vector<VkSpecializationMapEntry> entries = specialization_entries();
  const VkSpecializationInfo spec{uint32_t(entries.size()), entries.data(), sizeof(desc.shading),
                                  &desc.shading};
  stages[0].pSpecializationInfo = &spec;
  stages[1].pSpecializationInfo = &spec;
  const VkVertexInputBindingDescription binding{0, sizeof(glm::vec4), VK_VERTEX_INPUT_RATE_VERTEX};
  const VkVertexInputAttributeDescription attribute{0, 0, VK_FORMAT_R32G32B32A32_SFLOAT, 0};
  VkPipelineVertexInputStateCreateInfo input{
      VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  if (desc.clip_space_positions) {
    input.vertexBindingDescriptionCount = 1;
    input.pVertexBindingDescriptions = &binding;
    input.vertexAttributeDescriptionCount = 1;
    input.pVertexAttributeDescriptions = &attribute;
  } else {
    input.vertexBindingDescriptionCount = uint32_t(desc.bindings.size());
    input.pVertexBindingDescriptions = desc.bindings.data();
    input.vertexAttributeDescriptionCount = uint32_t(desc.attributes.size());
    input.pVertexAttributeDescriptions = desc.attributes.data();
  }
  VkPipelineInputAssemblyStateCreateInfo assembly{
      VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  viewport.viewportCount = 1;
  viewport.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo raster{
      VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = desc.cull;
  // Vulkan's facing uses the y-down framebuffer's area with a minus sign, so the world's
  // counter-clockwise front faces stay counter-clockwise here; a mirroring transform has
  // reversed them.
  raster.frontFace = desc.mirrored ? VK_FRONT_FACE_CLOCKWISE : VK_FRONT_FACE_COUNTER_CLOCKWISE;
  raster.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo ds{
      VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  ds.depthTestEnable = VK_TRUE;
  ds.depthWriteEnable = VK_TRUE;
  ds.depthCompareOp = desc.depth_compare;
  VkPipelineColorBlendAttachmentState blend{};
  blend.colorWriteMask = desc.color_mask;
  VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  cb.attachmentCount = 1;
  cb.pAttachments = &blend;
  const VkDynamicState dynamic[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dyn{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dyn.dynamicStateCount = 2;
  dyn.pDynamicStates = dynamic;
  VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  info.stageCount = 2;
  info.pStages = stages;
  info.pVertexInputState = &input;
  info.pInputAssemblyState = &assembly;
  info.pViewportState = &viewport;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &ms;
  info.pDepthStencilState = &ds;
  info.pColorBlendState = &cb;
  info.pDynamicState = &dyn;
  info.layout = layout;
  info.renderPass = pass;
  VkPipeline pipeline = VK_NULL_HANDLE;
  VkResult result =
      vkCreateGraphicsPipelines(ctx.device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline);
  vkDestroyShaderModule(ctx.device, vert, nullptr);
  vkDestroyShaderModule(ctx.device, frag, nullptr);
  vk_check(result, (std::string("vkCreateGraphicsPipelines(") + desc.vertex_shader + ")").c_str());
  return pipeline;
}

}  // namespace tessera
