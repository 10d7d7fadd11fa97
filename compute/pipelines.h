#pragma once
// The descriptor set layout shared by every pass, and the compute pipelines of the pass and
// pipeline tables (compute/passes.h), created once.

#include <array>
#include <span>
#include <string_view>
#include <vector>

#include <vulkan/vulkan.h>

#include "compute/context.h"
#include "compute/passes.h"

namespace tessera {

/// Stages of the shared descriptor set and push constants: the compute passes, and the vertex
/// and fragment stages a graphics pipeline drawing with the same set uses (the hardware
/// baseline of compute/baselines/).
constexpr VkShaderStageFlags kShaderStages =
    VK_SHADER_STAGE_COMPUTE_BIT | VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;

struct Pipelines {
  VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  std::array<VkPipeline, kPassCount> passes{};    // per pass that dispatches (all but
                                                  // Variants::shading)
  std::array<VkPipeline, kPassCount> coverage{};  // TS_SPEC_DEBUG_COVERAGE on (::debug_coverage)
  std::array<VkPipeline, kPassCount> lod{};       // TS_SPEC_LOD on (Variants::lod)
  std::array<VkPipeline, size_t(Pipeline::count)> pipelines{};  // kPipelines
  VkPipeline operator[](Pipeline p) const { return pipelines[size_t(p)]; }
  VkPipeline operator[](Pass p) const { return passes[size_t(p)]; }
};

/// A shader module from SPIR-V words. The caller destroys it once its pipelines are built.
VkShaderModule create_shader_module(const Context& ctx, std::span<const uint32_t> code);

/// A shader module from the embedded SPIR-V of `name` (shaders/shader_registry.h).
VkShaderModule create_shader_module(const Context& ctx, std::string_view name);

/// A shading pipeline specialized to a scene: BRDF variant, energy compensation, the number
/// of lights of each kind (lights sorted by kind), the texture maps its
/// materials use (TS_MAP_* bits), whether an environment lights it, and the maps that read uv
/// set 1 (TS_MAP_* bits; 0 leaves out the second set's code and reads).
struct ShadeVariant {
  uint32_t brdf;
  bool energy_compensation;
  std::array<uint32_t, TS_LIGHT_KIND_COUNT> light_counts;  // by TS_LIGHT_* kind
  uint32_t texture_maps;
  bool ibl;
  uint32_t uv1_maps;
  uint32_t samples = 1;  // per pixel
  uint32_t aa_coverage = TS_AA_COVERAGE_COUNT;  // FrameSettings::aa_coverage, with samples > 1
  auto operator<=>(const ShadeVariant&) const = default;
};

/// The specialization constants of `variant`'s shading pipeline (shared with the graphics
/// baseline's fragment shader, which includes the same lighting code).
Specialization shade_specialization(const ShadeVariant& variant);

/// The map entries of every Specialization member to its constant id (TS_SPEC_*), for
/// VkSpecializationInfo with a Specialization as data.
std::vector<VkSpecializationMapEntry> specialization_entries();

/// A compute pipeline of the embedded shader `shader` with the layout `layout`, specialized to
/// `values`. Throws Error (through vk_check) if the driver cannot build it.
VkPipeline create_compute_pipeline(const Context& ctx, VkPipelineLayout layout,
                                   std::string_view shader, Specialization values);

/// Builds the shading pipeline for `variant` with the layout of `pipelines`.
VkPipeline create_shade_pipeline(const Context& ctx, const Pipelines& pipelines,
                                 const ShadeVariant& variant);

/// Creates the layouts and every pipeline of kPasses and kPipelines from the embedded SPIR-V,
/// the passes specialized to tiles of `tile_size` pixels per side (validate_tile_size) and to
/// hierarchical depth rejection on or off (`depth_rejection`, RendererOptions), except the
/// generic shading pipelines of kPipelines (shader "shade"), left null for the renderer to
/// build on first use.
Pipelines create_pipelines(const Context& ctx, uint32_t tile_size, bool depth_rejection);
void destroy_pipelines(const Context& ctx, Pipelines& pipelines);

}  // namespace tessera
