#include "compute/pipelines.h"

#include <cstddef>
#include <string>
#include <vector>

#include "compute/vk_check.h"
#include "core/check.h"
#include "shaders/shader_registry.h"
#include "shaders/shared/gpu_types.h"

namespace tessera {
namespace {}  // namespace

VkDescriptorType binding_type(uint32_t binding) {
  if (binding == TS_BINDING_FRAME) return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  if (binding == TS_BINDING_HDR_IMAGE || binding == TS_BINDING_LDR_IMAGE) {
    return VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
  }
  if (binding == TS_BINDING_ENV_MAP || binding == TS_BINDING_ENV_SPECULAR) {
    return VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  }
  return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
}

VkShaderModule create_shader_module(const Context& ctx, std::string_view name) {
  std::span<const uint32_t> code = find_shader(name);
  TESSERA_CHECK(!code.empty());
  VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  info.codeSize = code.size_bytes();
  info.pCode = code.data();
  VkShaderModule module = VK_NULL_HANDLE;
  VK_CHECK(vkCreateShaderModule(ctx.device, &info, nullptr, &module));
  return module;
}

namespace {

// Values of the specialization constants (TS_SPEC_*); a shader ignores those it does not declare.
struct Specialization {
  VkBool32 debug_coverage;
  uint32_t brdf;
  VkBool32 energy_compensation;
  VkBool32 lights_specialized = VK_FALSE;
  uint32_t texture_maps = TS_MAP_ALL;
  uint32_t ibl = TS_IBL_RUNTIME;
  std::array<uint32_t, TS_LIGHT_KIND_COUNT> light_counts{};  // by TS_LIGHT_* kind
};

VkPipeline create_compute_pipeline(const Context& ctx, VkPipelineLayout layout,
                                   std::string_view shader, Specialization values) {
  VkShaderModule module = create_shader_module(ctx, shader);

  std::vector<VkSpecializationMapEntry> entries = {
      {TS_SPEC_DEBUG_COVERAGE, offsetof(Specialization, debug_coverage), sizeof(VkBool32)},
      {TS_SPEC_BRDF, offsetof(Specialization, brdf), sizeof(uint32_t)},
      {TS_SPEC_ENERGY_COMPENSATION, offsetof(Specialization, energy_compensation),
       sizeof(VkBool32)},
      {TS_SPEC_LIGHTS_SPECIALIZED, offsetof(Specialization, lights_specialized), sizeof(VkBool32)},
      {TS_SPEC_TEXTURE_MAPS, offsetof(Specialization, texture_maps), sizeof(uint32_t)},
      {TS_SPEC_IBL, offsetof(Specialization, ibl), sizeof(uint32_t)}};
  for (uint32_t kind = 0; kind < TS_LIGHT_KIND_COUNT; ++kind) {
    entries.push_back({TS_SPEC_LIGHT_COUNT_BASE + kind,
                       uint32_t(offsetof(Specialization, light_counts) + kind * sizeof(uint32_t)),
                       sizeof(uint32_t)});
  }
  // Every member of Specialization (4 bytes each) has its entry: a member without one would be
  // silently ignored by the driver.
  TESSERA_CHECK(entries.size() * 4 == sizeof(Specialization));
  VkSpecializationInfo spec{uint32_t(entries.size()), entries.data(), sizeof(values), &values};

  VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  info.stage.module = module;
  info.stage.pName = "main";
  info.stage.pSpecializationInfo = &spec;
  info.layout = layout;
  VkPipeline pipeline = VK_NULL_HANDLE;
  VkResult result =
      vkCreateComputePipelines(ctx.device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline);
  vkDestroyShaderModule(ctx.device, module, nullptr);
  vk_check(result, ("vkCreateComputePipelines(" + std::string(shader) + ")").c_str());
  return pipeline;
}

}  // namespace

VkPipeline create_shade_pipeline(const Context& ctx, const Pipelines& pipelines,
                                 const ShadeVariant& v) {
  const Specialization values{.debug_coverage = VK_FALSE,
                              .brdf = v.brdf,
                              .energy_compensation = v.energy_compensation ? VK_TRUE : VK_FALSE,
                              .lights_specialized = VK_TRUE,
                              .texture_maps = v.texture_maps,
                              .ibl = v.ibl ? TS_IBL_ON : TS_IBL_OFF,
                              .light_counts = v.light_counts};
  return create_compute_pipeline(ctx, pipelines.layout, "shade", values);
}

Pipelines create_pipelines(const Context& ctx) {
  Pipelines p;
  std::vector<VkDescriptorSetLayoutBinding> bindings;
  for (uint32_t b = 0; b < TS_BINDING_COUNT; ++b) {
    bindings.push_back({b, binding_type(b), 1, kShaderStages, nullptr});
  }
  VkDescriptorSetLayoutCreateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  set_info.bindingCount = uint32_t(bindings.size());
  set_info.pBindings = bindings.data();
  VK_CHECK(vkCreateDescriptorSetLayout(ctx.device, &set_info, nullptr, &p.set_layout));

  VkPushConstantRange push{kShaderStages, 0, sizeof(gpu::GpuBatch)};
  VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layout_info.setLayoutCount = 1;
  layout_info.pSetLayouts = &p.set_layout;
  layout_info.pushConstantRangeCount = 1;
  layout_info.pPushConstantRanges = &push;
  VK_CHECK(vkCreatePipelineLayout(ctx.device, &layout_info, nullptr, &p.layout));

  struct Variant {
    Pipeline id;
    const char* shader;
    Specialization values;
  };
  const Variant variants[] = {
      {Pipeline::setup, "setup", {VK_FALSE, 0, VK_FALSE}},
      {Pipeline::clip, "clip", {VK_FALSE, 0, VK_FALSE}},
      {Pipeline::bin_count, "count", {VK_FALSE, 0, VK_FALSE}},
      {Pipeline::scan, "scan", {VK_FALSE, 0, VK_FALSE}},
      {Pipeline::fill, "fill", {VK_FALSE, 0, VK_FALSE}},
      {Pipeline::raster_small, "raster_small", {VK_FALSE, 0, VK_FALSE}},
      {Pipeline::raster_tiles, "raster_tiles", {VK_FALSE, 0, VK_FALSE}},
      {Pipeline::raster_small_coverage, "raster_small", {VK_TRUE, 0, VK_FALSE}},
      {Pipeline::raster_tiles_coverage, "raster_tiles", {VK_TRUE, 0, VK_FALSE}},
      {Pipeline::shade_classic, "shade", {VK_FALSE, TS_BRDF_CLASSIC, VK_FALSE}},
      {Pipeline::shade_filament, "shade", {VK_FALSE, TS_BRDF_FILAMENT, VK_FALSE}},
      {Pipeline::shade_blinn_phong, "shade", {VK_FALSE, TS_BRDF_BLINN_PHONG, VK_FALSE}},
      {Pipeline::shade_classic_compensated, "shade", {VK_FALSE, TS_BRDF_CLASSIC, VK_TRUE}},
      {Pipeline::shade_filament_compensated, "shade", {VK_FALSE, TS_BRDF_FILAMENT, VK_TRUE}},
      {Pipeline::dfg_classic, "dfg", {VK_FALSE, TS_BRDF_CLASSIC, VK_FALSE}},
      {Pipeline::dfg_filament, "dfg", {VK_FALSE, TS_BRDF_FILAMENT, VK_FALSE}},
      {Pipeline::env_irradiance, "env_irradiance", {VK_FALSE, 0, VK_FALSE}},
      {Pipeline::env_prefilter, "env_prefilter", {VK_FALSE, 0, VK_FALSE}},
      {Pipeline::resolve, "resolve", {VK_FALSE, 0, VK_FALSE}},
  };

  for (const Variant& v : variants) {
    p.pipelines[size_t(v.id)] = create_compute_pipeline(ctx, p.layout, v.shader, v.values);
  }
  return p;
}

void destroy_pipelines(const Context& ctx, Pipelines& p) {
  for (VkPipeline& pipeline : p.pipelines) {
    if (pipeline) vkDestroyPipeline(ctx.device, pipeline, nullptr);
  }
  if (p.layout) vkDestroyPipelineLayout(ctx.device, p.layout, nullptr);
  if (p.set_layout) vkDestroyDescriptorSetLayout(ctx.device, p.set_layout, nullptr);
  p = Pipelines{};
}

}  // namespace tessera
