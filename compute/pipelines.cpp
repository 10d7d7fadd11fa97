#include "compute/pipelines.h"

#include <cstddef>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "compute/vk_check.h"
#include "core/check.h"
#include "shaders/shader_registry.h"
#include "shaders/shared/gpu_types.h"

namespace tessera {

VkShaderModule create_shader_module(const Context& ctx, std::span<const uint32_t> code) {
  TESSERA_CHECK(!code.empty());
  VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  info.codeSize = code.size_bytes();
  info.pCode = code.data();
  VkShaderModule module = VK_NULL_HANDLE;
  VK_CHECK(vkCreateShaderModule(ctx.device, &info, nullptr, &module));
  return module;
}

VkShaderModule create_shader_module(const Context& ctx, std::string_view name) {
  return create_shader_module(ctx, find_shader(name));
}

std::vector<VkSpecializationMapEntry> specialization_entries() {
  std::vector<VkSpecializationMapEntry> entries = {
      {TS_SPEC_DEBUG_COVERAGE, offsetof(Specialization, debug_coverage), sizeof(VkBool32)},
      {TS_SPEC_BRDF, offsetof(Specialization, brdf), sizeof(uint32_t)},
      {TS_SPEC_ENERGY_COMPENSATION, offsetof(Specialization, energy_compensation),
       sizeof(VkBool32)},
      {TS_SPEC_LIGHTS_SPECIALIZED, offsetof(Specialization, lights_specialized), sizeof(VkBool32)},
      {TS_SPEC_TEXTURE_MAPS, offsetof(Specialization, texture_maps), sizeof(uint32_t)},
      {TS_SPEC_IBL, offsetof(Specialization, ibl), sizeof(uint32_t)},
      {TS_SPEC_UV1_MAPS, offsetof(Specialization, uv1_maps), sizeof(uint32_t)},
      {TS_SPEC_SAMPLES, offsetof(Specialization, samples), sizeof(uint32_t)},
      {TS_SPEC_OUTPUT_BGRA, offsetof(Specialization, output_bgra), sizeof(VkBool32)},
      {TS_SPEC_LOD, offsetof(Specialization, lod), sizeof(VkBool32)},
      {TS_SPEC_TILE_SIZE, offsetof(Specialization, tile_size), sizeof(uint32_t)},
      {TS_SPEC_DEPTH_REJECTION, offsetof(Specialization, depth_rejection), sizeof(VkBool32)},
      {TS_SPEC_AA_COVERAGE, offsetof(Specialization, aa_coverage), sizeof(uint32_t)},
      {TS_SPEC_SILHOUETTE_STEPS, offsetof(Specialization, silhouette_steps), sizeof(uint32_t)},
      {TS_SPEC_SHADE_TILES, offsetof(Specialization, shade_tiles), sizeof(uint32_t)},
      {TS_SPEC_OBJECT_CLIP_INLINE, offsetof(Specialization, object_clip_inline), sizeof(VkBool32)},
      {TS_SPEC_RASTER_ONLY, offsetof(Specialization, raster_only), sizeof(VkBool32)},
      {TS_SPEC_POLYGONS_IN_REGISTERS, offsetof(Specialization, polygons_in_registers),
       sizeof(VkBool32)}};
  for (uint32_t kind = 0; kind < TS_LIGHT_KIND_COUNT; ++kind) {
    entries.push_back({TS_SPEC_LIGHT_COUNT_BASE + kind,
                       uint32_t(offsetof(Specialization, light_counts) + kind * sizeof(uint32_t)),
                       sizeof(uint32_t)});
  }
  // Every member of Specialization (4 bytes each) has its entry: a member without one would be
  // silently ignored by the driver. The ids are the members' indices, so none is used twice
  // (two branches adding a constant each may otherwise both take the next free id) and the
  // light counts stay last.
  TESSERA_CHECK(entries.size() * 4 == sizeof(Specialization));
  for (uint32_t i = 0; i < entries.size(); ++i)
    TESSERA_CHECK(entries[i].constantID == i && entries[i].offset == 4 * i);
  return entries;
}

Specialization shade_specialization(const ShadeVariant& v) {
  return {.debug_coverage = VK_FALSE,
          .brdf = v.brdf,
          .energy_compensation = v.energy_compensation ? VK_TRUE : VK_FALSE,
          .lights_specialized = VK_TRUE,
          .texture_maps = v.texture_maps,
          .ibl = v.ibl ? TS_IBL_ON : TS_IBL_OFF,
          .uv1_maps = v.uv1_maps,
          .samples = v.samples,
          .tile_size = v.tile_size,
          .depth_rejection = v.depth_rejection ? VK_TRUE : VK_FALSE,
          .aa_coverage = v.aa_coverage,
          .shade_tiles = v.shade_tiles,
          .light_counts = v.light_counts};
}

bool samples_texture_maps(const Specialization& values) {
  return (values.texture_maps & ~TS_MAP_WRAP_MODES) != 0u;
}

// A driver translates a module whole before specialization folds away what a variant does not
// run: lavapipe spent about 0.35 of a one-sample shading pipeline's 1.3 CPU seconds on the
// multi-sample path when both were one module (shade.comp), and a one-sample pipeline of a
// scene without maps built in about 80 ms from a module without texture code against 500 with
// it (docs/development.md, "Measured CI time").
std::string shader_module(std::string_view shader, const Specialization& values) {
  std::string name(shader == "shade" && values.samples > 1 ? "shade_samples" : shader);
  if (!samples_texture_maps(values) && !find_shader(name + "_untextured").empty()) {
    name += "_untextured";
  }
  return name;
}

namespace {

// The context's layouts, created on first use. The cache's mutex must be held.
VkPipelineLayout cached_layout(const Context& ctx, PipelineCache& cache) {
  if (cache.layout) return cache.layout;
  std::vector<VkDescriptorSetLayoutBinding> bindings;
  for (uint32_t b = 0; b < TS_BINDING_COUNT; ++b) {
    bindings.push_back({b, binding_type(b), 1, kShaderStages, nullptr});
  }
  VkDescriptorSetLayoutCreateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  set_info.bindingCount = uint32_t(bindings.size());
  set_info.pBindings = bindings.data();
  VK_CHECK(vkCreateDescriptorSetLayout(ctx.device, &set_info, nullptr, &cache.set_layout));

  VkPushConstantRange push{kShaderStages, 0, sizeof(gpu::GpuBatch)};
  VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layout_info.setLayoutCount = 1;
  layout_info.pSetLayouts = &cache.set_layout;
  layout_info.pushConstantRangeCount = 1;
  layout_info.pPushConstantRanges = &push;
  VK_CHECK(vkCreatePipelineLayout(ctx.device, &layout_info, nullptr, &cache.layout));
  return cache.layout;
}

// Vulkan's two calls for an array: its length, then that many elements, each first set to
// `blank` (for its sType). `call(count, elements)` returns the VkResult.
template <typename T, typename Call>
std::vector<T> enumerate(Call call, T blank) {
  uint32_t n = 0;
  VK_CHECK(call(&n, nullptr));
  std::vector<T> out(n, blank);
  VK_CHECK(call(&n, out.data()));
  out.resize(n);
  return out;
}

// Prints the driver's statistics of `pipeline`'s code (VK_KHR_pipeline_executable_properties:
// on NVIDIA registers, spills, shared memory ...) to stderr, one line per executable, with the
// specialization constants that distinguish the variants of one shader.
void print_pipeline_statistics(const Context& ctx, VkPipeline pipeline, std::string_view shader,
                               const Specialization& values) {
  const auto properties = reinterpret_cast<PFN_vkGetPipelineExecutablePropertiesKHR>(
      vkGetInstanceProcAddr(ctx.instance, "vkGetPipelineExecutablePropertiesKHR"));
  const auto statistics = reinterpret_cast<PFN_vkGetPipelineExecutableStatisticsKHR>(
      vkGetInstanceProcAddr(ctx.instance, "vkGetPipelineExecutableStatisticsKHR"));
  if (!properties || !statistics) return;
  VkPipelineInfoKHR info{VK_STRUCTURE_TYPE_PIPELINE_INFO_KHR};
  info.pipeline = pipeline;
  const auto executables = enumerate(
      [&](uint32_t* n, VkPipelineExecutablePropertiesKHR* out) {
        return properties(ctx.device, &info, n, out);
      },
      VkPipelineExecutablePropertiesKHR{VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_PROPERTIES_KHR});
  for (uint32_t e = 0; e < executables.size(); ++e) {
    VkPipelineExecutableInfoKHR which{VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_INFO_KHR};
    which.pipeline = pipeline;
    which.executableIndex = e;
    const auto stats = enumerate(
        [&](uint32_t* n, VkPipelineExecutableStatisticKHR* out) {
          return statistics(ctx.device, &which, n, out);
        },
        VkPipelineExecutableStatisticKHR{VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_STATISTIC_KHR});
    std::string line = "pipeline statistics: " + std::string(shader) + " (samples " +
                       std::to_string(values.samples) + ", aa_coverage " +
                       std::to_string(values.aa_coverage) + ", " + executables[e].name + "):";
    for (const VkPipelineExecutableStatisticKHR& s : stats) {
      line += std::string(" ") + s.name + " ";
      switch (s.format) {
        case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_BOOL32_KHR:
          line += s.value.b32 ? "true" : "false";
          break;
        case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_INT64_KHR:
          line += std::to_string(s.value.i64);
          break;
        case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_UINT64_KHR:
          line += std::to_string(s.value.u64);
          break;
        default:
          line += std::to_string(s.value.f64);
          break;
      }
      line += ";";
    }
    std::fprintf(stderr, "%s\n", line.c_str());
  }
}

VkPipeline build_compute_pipeline(const Context& ctx, VkPipelineLayout layout,
                                  std::string_view shader, Specialization values) {
  VkShaderModule module = create_shader_module(ctx, shader_module(shader, values));
  const std::vector<VkSpecializationMapEntry> entries = specialization_entries();
  VkSpecializationInfo spec{uint32_t(entries.size()), entries.data(), sizeof(values), &values};

  VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  info.stage.module = module;
  info.stage.pName = "main";
  info.stage.pSpecializationInfo = &spec;
  info.layout = layout;
  if (ctx.pipeline_statistics) info.flags |= VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR;
  VkPipeline pipeline = VK_NULL_HANDLE;
  VkResult result =
      vkCreateComputePipelines(ctx.device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline);
  vkDestroyShaderModule(ctx.device, module, nullptr);
  vk_check(result, ("vkCreateComputePipelines(" + std::string(shader) + ")").c_str());
  if (ctx.pipeline_statistics) print_pipeline_statistics(ctx, pipeline, shader, values);
  return pipeline;
}

// PipelineCache::compute's key. Specialization is 4-byte members only (specialization_entries
// checks it): no padding, so its bytes name the constants.
std::string pipeline_key(std::string_view shader, const Specialization& values) {
  std::string key(shader);
  key.push_back('\0');
  key.append(reinterpret_cast<const char*>(&values), sizeof(values));
  return key;
}

}  // namespace

bool has_compute_pipeline(const Context& ctx, std::string_view shader, Specialization values) {
  TESSERA_CHECK(ctx.pipeline_cache);
  values.polygons_in_registers = ctx.polygons_in_registers ? VK_TRUE : VK_FALSE;
  PipelineCache& cache = *ctx.pipeline_cache;
  const std::string key = pipeline_key(shader, values);
  std::lock_guard lock(cache.mutex);
  const auto it = cache.compute.find(key);
  return it != cache.compute.end() && it->second != VK_NULL_HANDLE;
}

VkPipeline create_compute_pipeline(const Context& ctx, std::string_view shader,
                                   Specialization values) {
  TESSERA_CHECK(ctx.pipeline_cache);
  values.polygons_in_registers = ctx.polygons_in_registers ? VK_TRUE : VK_FALSE;
  PipelineCache& cache = *ctx.pipeline_cache;
  const std::string key = pipeline_key(shader, values);
  std::lock_guard lock(cache.mutex);
  VkPipeline& pipeline = cache.compute[key];
  if (!pipeline) pipeline = build_compute_pipeline(ctx, cached_layout(ctx, cache), shader, values);
  return pipeline;
}

VkPipeline create_shade_pipeline(const Context& ctx, const ShadeVariant& v) {
  return create_compute_pipeline(ctx, v.rasterizes ? "raster_shade" : "shade",
                                 shade_specialization(v));
}

void destroy_pipeline_cache(Context& ctx) {
  PipelineCache& cache = *ctx.pipeline_cache;
  std::lock_guard lock(cache.mutex);
  for (const auto& [key, pipeline] : cache.compute) {
    if (pipeline) vkDestroyPipeline(ctx.device, pipeline, nullptr);
  }
  cache.compute.clear();
  if (cache.layout) vkDestroyPipelineLayout(ctx.device, cache.layout, nullptr);
  if (cache.set_layout) vkDestroyDescriptorSetLayout(ctx.device, cache.set_layout, nullptr);
  cache.layout = VK_NULL_HANDLE;
  cache.set_layout = VK_NULL_HANDLE;
}

Specialization pass_specialization(const PassInfo& row, uint32_t tile_size, bool depth_rejection,
                                   bool shade_tiles) {
  // Every pass gets the tile size and the rejection and tile-shading switches; only those
  // that bin, rasterize or list by tiles read them.
  Specialization spec = row.spec;
  spec.tile_size = tile_size;
  spec.depth_rejection = depth_rejection ? VK_TRUE : VK_FALSE;
  spec.shade_tiles = shade_tiles ? TS_SHADE_TILES_DRAWN : TS_SHADE_TILES_OFF;
  return spec;
}

Pipelines create_pipelines(const Context& ctx, uint32_t tile_size, bool depth_rejection,
                           bool shade_tiles) {
  TESSERA_CHECK(ctx.pipeline_cache);
  Pipelines p;
  p.ctx = &ctx;
  p.tile_size = tile_size;
  p.depth_rejection = depth_rejection;
  p.shade_tiles = shade_tiles;
  std::lock_guard lock(ctx.pipeline_cache->mutex);
  p.layout = cached_layout(ctx, *ctx.pipeline_cache);
  p.set_layout = ctx.pipeline_cache->set_layout;
  return p;
}

VkPipeline Pipelines::operator[](Pass pass) const {
  VkPipeline& slot = passes[size_t(pass)];
  if (slot) return slot;
  const PassInfo& row = kPasses[size_t(pass)];
  TESSERA_CHECK(row.pass == pass && row.shader != nullptr &&
                row.variants != Variants::shading && row.variants != Variants::silhouette &&
                row.variants != Variants::raster_shade);
  slot = create_compute_pipeline(*ctx, row.shader,
                                 pass_specialization(row, tile_size, depth_rejection, shade_tiles));
  return slot;
}

VkPipeline Pipelines::operator[](Pipeline id) const {
  VkPipeline& slot = pipelines[size_t(id)];
  if (slot) return slot;
  const PipelineInfo& info = kPipelines[size_t(id)];
  TESSERA_CHECK(std::string_view(info.shader) != "shade");
  slot = create_compute_pipeline(*ctx, info.shader, info.spec);
  return slot;
}

void destroy_pipelines(const Context&, Pipelines& p) {
  p = Pipelines{};
}

}  // namespace tessera
