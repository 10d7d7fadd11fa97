#pragma once
// The descriptor set layout shared by every pass, and the compute pipelines, created once.

#include <array>
#include <string_view>

#include <vulkan/vulkan.h>

#include "compute/context.h"
#include "shaders/shared/constants.h"

namespace tessera {

enum class Pipeline {
  setup,
  clip,
  bin_count,
  scan,
  fill,
  raster_small,
  raster_tiles,
  raster_small_coverage,      // raster_small with DEBUG_COVERAGE on
  raster_tiles_coverage,      // raster_tiles with DEBUG_COVERAGE on
  shade_classic,              // shade with BRDF variant TS_BRDF_CLASSIC,
  shade_filament,             // TS_BRDF_FILAMENT,
  shade_blinn_phong,          // TS_BRDF_BLINN_PHONG (specialization constant TS_SPEC_BRDF)
  shade_classic_compensated,  // with TS_SPEC_ENERGY_COMPENSATION on
  shade_filament_compensated,
  dfg_classic,  // the DFG tables, per visibility term
  dfg_filament,
  env_irradiance,  // the environment's irradiance coefficients
  env_prefilter,   // one level of the prefiltered specular cube
  resolve,
  count
};

/// Stages of the shared descriptor set and push constants: the compute passes, and the
/// graphics baseline's vertex and fragment shaders.
constexpr VkShaderStageFlags kShaderStages =
    VK_SHADER_STAGE_COMPUTE_BIT | VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;

struct Pipelines {
  VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  std::array<VkPipeline, size_t(Pipeline::count)> pipelines{};
  VkPipeline operator[](Pipeline p) const { return pipelines[size_t(p)]; }
};

/// Descriptor type of binding `binding` (TS_BINDING_*) of the shared set.
VkDescriptorType binding_type(uint32_t binding);

/// A shader module from the embedded SPIR-V of `name` (shaders/shader_registry.h). The caller
/// destroys it once its pipelines are built.
VkShaderModule create_shader_module(const Context& ctx, std::string_view name);

/// A shading pipeline specialized to a scene: BRDF variant, energy compensation, the number
/// of lights of each kind (lights sorted by kind), the texture maps its
/// materials use (TS_MAP_* bits) and whether an environment lights it.
struct ShadeVariant {
  uint32_t brdf;
  bool energy_compensation;
  std::array<uint32_t, TS_LIGHT_KIND_COUNT> light_counts;  // by TS_LIGHT_* kind
  uint32_t texture_maps;
  bool ibl;
  auto operator<=>(const ShadeVariant&) const = default;
};

/// Builds the shading pipeline for `variant` with the layout of `pipelines`.
VkPipeline create_shade_pipeline(const Context& ctx, const Pipelines& pipelines,
                                 const ShadeVariant& variant);

/// Creates the layouts and every pipeline from the embedded SPIR-V.
Pipelines create_pipelines(const Context& ctx);
void destroy_pipelines(const Context& ctx, Pipelines& pipelines);

}  // namespace tessera
