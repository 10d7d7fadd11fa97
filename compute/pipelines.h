#pragma once
// The descriptor set layout shared by every pass, and the compute pipelines of the pass and
// pipeline tables (compute/passes.h), created once per context.

#include <array>
#include <map>
#include <mutex>
#include <span>
#include <string>
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

/// The compute pipelines a context has built, by shader and specialization, and the layouts all
/// of them use. Building a pipeline costs lavapipe 10 ms to 1 s of CPU time (the shading pass
/// the most), often more than rendering a small frame, so every renderer of a context (a tool
/// or test rendering with several sets of options, one renderer after another) builds each
/// one once. Owned by Context::pipeline_cache and destroyed with the context; thread-safe.
struct PipelineCache {
  std::mutex mutex;
  VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;  // built on first use, as `layout`
  VkPipelineLayout layout = VK_NULL_HANDLE;
  std::map<std::string, VkPipeline> compute;  // by shader name, '\0', Specialization's bytes
};

/// Destroys the pipelines and layouts of ctx.pipeline_cache. No renderer of `ctx` may be left,
/// and the device must be idle (Context's destructor).
void destroy_pipeline_cache(Context& ctx);

/// A renderer's view of its context's pipelines (PipelineCache): every handle belongs to the
/// cache. The pipelines of kPasses and kPipelines are built on first use, by operator[]: a
/// process pays lavapipe's translation (10 to 40 ms a pipeline) only for the passes it records;
/// a frame of the default scene records half of them (docs/architecture.md, "The frame").
struct Pipelines {
  const Context* ctx = nullptr;
  // pass_specialization's arguments, for the passes' pipelines.
  uint32_t tile_size = 0;
  bool depth_rejection = false;
  bool shade_tiles = false;
  VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  // Null until first used (operator[] for these two; pass_variant_pipeline, renderer.cpp, for
  // the variants; shade_pipeline for the generic shading pipelines of kPipelines). Mutable:
  // building one on first use changes nothing a caller can see.
  mutable std::array<VkPipeline, kPassCount> passes{};  // per pass that dispatches (all but
                                                        // Variants::shading and ::raster_shade)
  std::array<VkPipeline, kPassCount> coverage{};  // TS_SPEC_DEBUG_COVERAGE on (::debug_coverage)
  std::array<VkPipeline, kPassCount> lod{};       // TS_SPEC_LOD on (Variants::lod)
  VkPipeline setup_object_clip_inline = VK_NULL_HANDLE;  // TS_SPEC_OBJECT_CLIP_INLINE on
  VkPipeline setup_raster_only = VK_NULL_HANDLE;         // that and TS_SPEC_RASTER_ONLY on
  mutable std::array<VkPipeline, size_t(Pipeline::count)> pipelines{};  // kPipelines
  /// kPipelines' row `p` as the table specializes it (not the generic shading pipelines, which
  /// shade_pipeline specializes to the tile size), built now if this is its first use.
  VkPipeline operator[](Pipeline p) const;
  /// Pass `p`'s pipeline (pass_specialization), built now if this is its first use. Not for
  /// Variants::shading, ::silhouette and ::raster_shade, whose pipelines the renderer chooses.
  VkPipeline operator[](Pass p) const;
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
  uint32_t samples = 1;                         // per pixel
  uint32_t aa_coverage = TS_AA_COVERAGE_COUNT;  // FrameSettings::aa_coverage, with samples > 1
  uint32_t shade_tiles = TS_SHADE_TILES_OFF;    // which dispatch (RendererOptions::shade_tiles)
  uint32_t tile_size = TS_TILE_SIZE;            // RendererOptions::tile_size, for shade_tiles
  // The pass that rasterizes and shades small frames (raster_shade.comp) rather than the
  // shading pass, with or without depth rejection (RendererOptions::depth_rejection).
  bool rasterizes = false;
  bool depth_rejection = true;
  auto operator<=>(const ShadeVariant&) const = default;
};

/// The specialization constants of `variant`'s shading pipeline (shared with the graphics
/// baseline's fragment shader, which includes the same lighting code).
Specialization shade_specialization(const ShadeVariant& variant);

/// The embedded module a pipeline of `shader` specialized to `values` is built from
/// (shaders/shader_registry.h): the shading pass at several samples per pixel from
/// shade_samples.comp, and a shader with a module built without texture-map code
/// ("<name>_untextured", shaders/CMakeLists.txt) from that one when `values` samples no map.
/// Modules without a variant are their shader's own.
std::string shader_module(std::string_view shader, const Specialization& values);

/// True if a pipeline specialized to `values` samples a texture map (a TS_MAP_* map bit of
/// Specialization::texture_maps; TS_MAP_WRAP_MODES alone samples none).
bool samples_texture_maps(const Specialization& values);

/// The map entries of every Specialization member to its constant id (TS_SPEC_*), for
/// VkSpecializationInfo with a Specialization as data.
std::vector<VkSpecializationMapEntry> specialization_entries();

/// The compute pipeline of the embedded shader `shader` with the context's layout
/// (PipelineCache), specialized to `values`: built on first use and kept by the context, which
/// destroys it (callers must not). Throws Error (through vk_check) if the driver cannot build it.
VkPipeline create_compute_pipeline(const Context& ctx, std::string_view shader,
                                   Specialization values);

/// Whether the context has built the pipeline create_compute_pipeline(ctx, shader, values)
/// returns (else that call builds it: up to seconds on a CPU device).
bool has_compute_pipeline(const Context& ctx, std::string_view shader, Specialization values);

/// The shading pipeline for `variant` (create_compute_pipeline).
VkPipeline create_shade_pipeline(const Context& ctx, const ShadeVariant& variant);

/// The specialization of pass `row` (a kPasses row) to tiles of `tile_size` pixels per side
/// (validate_tile_size), hierarchical depth rejection on or off (`depth_rejection`,
/// RendererOptions) and marking drawn tiles or not (`shade_tiles`); its variants (debug
/// coverage, level of detail, setup's) set their constants on top.
Specialization pass_specialization(const PassInfo& row, uint32_t tile_size, bool depth_rejection,
                                   bool shade_tiles);

/// The layouts, and a Pipelines whose pipelines are built on first use (Pipelines::operator[]),
/// from the embedded SPIR-V unless the context has them (create_compute_pipeline).
Pipelines create_pipelines(const Context& ctx, uint32_t tile_size, bool depth_rejection,
                           bool shade_tiles);
/// Forgets `pipelines`; their handles stay with the context.
void destroy_pipelines(const Context& ctx, Pipelines& pipelines);

}  // namespace tessera
