#include "compute/baselines/brdf_probe.h"

#include <cstring>

#include "compute/baselines/baseline_shaders.h"
#include "compute/gpu_memory.h"
#include "compute/pipelines.h"
#include "compute/vk_check.h"
#include "core/check.h"
#include "shaders/shared/gpu_types.h"

namespace tessera {

std::vector<glm::vec3> evaluate_brdf_on_gpu(const Context& ctx, Brdf variant,
                                            const std::vector<BrdfSample>& samples) {
  std::vector<glm::vec3> out(samples.size());
  if (samples.empty()) return out;
  std::vector<gpu::GpuBrdfSample> packed;
  for (const BrdfSample& s : samples) {
    packed.push_back({.n = s.n,
                      .metallic = s.material.metallic,
                      .v = s.v,
                      .roughness = s.material.roughness,
                      .l = s.l,
                      .base_color = s.material.base_color});
  }
  const size_t input_bytes = packed.size() * sizeof(gpu::GpuBrdfSample);
  Buffer input =
      create_buffer(ctx, input_bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryKind::upload);
  std::memcpy(input.mapped, packed.data(), input_bytes);
  Buffer output = create_buffer(ctx, samples.size() * sizeof(glm::vec4),
                                VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryKind::readback);

  const VkDescriptorSetLayoutBinding bindings[] = {
      {0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
      {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr}};
  VkDescriptorSetLayoutCreateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  set_info.bindingCount = 2;
  set_info.pBindings = bindings;
  VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
  VK_CHECK(vkCreateDescriptorSetLayout(ctx.device, &set_info, nullptr, &set_layout));
  VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(uint32_t)};
  VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layout_info.setLayoutCount = 1;
  layout_info.pSetLayouts = &set_layout;
  layout_info.pushConstantRangeCount = 1;
  layout_info.pPushConstantRanges = &push;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VK_CHECK(vkCreatePipelineLayout(ctx.device, &layout_info, nullptr, &layout));

  VkShaderModule module = create_shader_module(ctx, find_baseline_shader("brdf_probe"));
  const uint32_t brdf = uint32_t(variant);  // Brdf values are the TS_BRDF_* constants
  const VkSpecializationMapEntry entry{TS_SPEC_BRDF, 0, sizeof(uint32_t)};
  const VkSpecializationInfo spec{1, &entry, sizeof(brdf), &brdf};
  VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  info.stage.module = module;
  info.stage.pName = "main";
  info.stage.pSpecializationInfo = &spec;
  info.layout = layout;
  VkPipeline pipeline = VK_NULL_HANDLE;
  VK_CHECK(vkCreateComputePipelines(ctx.device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline));
  vkDestroyShaderModule(ctx.device, module, nullptr);

  const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2};
  VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pool_info.maxSets = 1;
  pool_info.poolSizeCount = 1;
  pool_info.pPoolSizes = &size;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  VK_CHECK(vkCreateDescriptorPool(ctx.device, &pool_info, nullptr, &pool));
  VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  alloc.descriptorPool = pool;
  alloc.descriptorSetCount = 1;
  alloc.pSetLayouts = &set_layout;
  VkDescriptorSet set = VK_NULL_HANDLE;
  VK_CHECK(vkAllocateDescriptorSets(ctx.device, &alloc, &set));
  const VkDescriptorBufferInfo buffers[] = {{input.buffer, 0, VK_WHOLE_SIZE},
                                            {output.buffer, 0, VK_WHOLE_SIZE}};
  VkWriteDescriptorSet writes[2] = {};
  for (uint32_t i = 0; i < 2; ++i) {
    writes[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    writes[i].dstSet = set;
    writes[i].dstBinding = i;
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[i].pBufferInfo = &buffers[i];
  }
  vkUpdateDescriptorSets(ctx.device, 2, writes, 0, nullptr);

  const uint32_t count = uint32_t(samples.size());
  submit_and_wait(ctx, [&](VkCommandBuffer cmd) {
    memory_barrier(cmd, VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_WRITE_BIT,
                   VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &set, 0, nullptr);
    vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(count), &count);
    vkCmdDispatch(cmd, (count + 63) / 64, 1, 1);
    memory_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                   VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
  });
  const auto* results = static_cast<const glm::vec4*>(output.mapped);
  for (size_t i = 0; i < samples.size(); ++i) out[i] = glm::vec3(results[i]);

  vkDestroyDescriptorPool(ctx.device, pool, nullptr);
  vkDestroyPipeline(ctx.device, pipeline, nullptr);
  vkDestroyPipelineLayout(ctx.device, layout, nullptr);
  vkDestroyDescriptorSetLayout(ctx.device, set_layout, nullptr);
  destroy_buffer(ctx, output);
  destroy_buffer(ctx, input);
  return out;
}

}  // namespace tessera
