#pragma once
// The one description of the renderer's frame: which passes run, in which order, with which
// shader, how each is dispatched and timed (kPasses), the pipelines outside that sequence
// (kPipelines), and what every binding of the shared descriptor set holds (kBindings).
// compute/pipelines.cpp builds the pipelines from these tables and compute/renderer.cpp
// records the frame, allocates, clears, binds and destroys the buffers from them, so a new
// pass with one buffer is: its .comp file (found by shaders/CMakeLists.txt), its binding in
// shaders/shared/gpu_types.h, and a row in kPasses and in kBindings here.

#include <array>
#include <cstddef>
#include <cstdint>

#include <vulkan/vulkan.h>

#include "shaders/shared/gpu_types.h"

namespace tessera {

/// The passes of a frame, in recording order, as FrameStats::pass_ms reports them.
enum class Pass {
  environment,  // the environment's irradiance and prefiltered cube, on the first frame after
                // set_scene changed it (also the DFG tables when first needed, and the
                // background's colours when what they depend on changed: background.comp)
  clear,
  object_clip,  // each object's clip-space transform (view_proj * model)
  lod,          // level of detail (FrameSettings::lod automatic only): each object's level,
  lod_scan,     // the triangle total and each batch's setup dispatch,
  lod_offsets,  // and each object's first triangle-instance id
  setup,
  clip,
  bin_count,
  scan,
  fill,
  raster_small,  // on GPUs recorded first: its threads' long walks start before the per-tile
  raster_tiles,  // pass's thousands of workgroups take the GPU (renderer.cpp's barrier_after)
  raster_shade,  // small frames (RendererOptions::raster_shade): both rasterizers and shading in
                 // one pass, in place of fill, raster_small, raster_tiles, list_tiles and shade
  list_tiles,    // shading by tiles (RendererOptions::shade_tiles): the drawn tiles and the others
  shade,
  outline,  // silhouette coverage (several samples): the outline pixels' exact coverage
  resolve,
  count
};
constexpr size_t kPassCount = size_t(Pass::count);

/// Values of the specialization constants (TS_SPEC_*); a shader ignores those it does not
/// declare. Every member is 4 bytes (pipelines.cpp maps each to its constant id).
struct Specialization {
  VkBool32 debug_coverage = VK_FALSE;
  uint32_t brdf = 0;
  VkBool32 energy_compensation = VK_FALSE;
  VkBool32 lights_specialized = VK_FALSE;
  uint32_t texture_maps = TS_MAP_ALL;
  uint32_t ibl = TS_IBL_RUNTIME;
  uint32_t uv1_maps = TS_MAP_ALL;
  uint32_t samples = 1;  // per pixel (FrameSettings::samples); others are built on first use
  VkBool32 output_bgra = VK_FALSE;
  VkBool32 lod = VK_FALSE;
  uint32_t tile_size = TS_TILE_SIZE;            // RendererOptions::tile_size
  VkBool32 depth_rejection = VK_TRUE;           // RendererOptions::depth_rejection
  uint32_t aa_coverage = TS_AA_COVERAGE_COUNT;  // FrameSettings::aa_coverage (shading, samples > 1)
  uint32_t silhouette_steps = 0;              // FrameSettings::silhouette_steps (the outline pass)
  uint32_t shade_tiles = TS_SHADE_TILES_OFF;  // RendererOptions::shade_tiles (TS_SHADE_TILES_*)
  VkBool32 object_clip_inline = VK_FALSE;     // setup, in frames without the object_clip pass
  VkBool32 raster_only = VK_FALSE;  // setup, in frames that rasterize and shade in one pass
  // Set by create_compute_pipeline from Context::polygons_in_registers, for every pipeline.
  VkBool32 polygons_in_registers = VK_FALSE;
  std::array<uint32_t, TS_LIGHT_KIND_COUNT> light_counts{};  // by TS_LIGHT_* kind
};

/// When a pass is recorded.
enum class Stage {
  precompute,  // record_precomputation: timed only on frames that computed something
  clear,       // the buffers of kBindings with Clear::per_frame are filled (and those with
               // Clear::on_creation after they were created); by the host where it maps them
  objects,     // once per frame before the batches, when the scene has triangles
  lod,         // once per frame before the batches, only under FrameSettings::lod automatic
  batch,       // once per batch of triangles (these rows are contiguous), with the GpuBatch
               // push constant set
  frame,       // once per frame, after the batches
};

/// How a pass of Stage::batch or Stage::frame is dispatched.
enum class Dispatch {
  none,                // Stage::precompute and Stage::clear record no dispatch of their own
  fixed,               // `groups` workgroups
  per_batch_triangle,  // one thread per triangle of the batch, `group_size` per workgroup
  per_object,          // one thread per object, `group_size` per workgroup
  per_pixel,           // `group_size` x `group_size` pixels per workgroup
  per_tile,            // one thread per screen tile (RendererOptions::tile_size), `group_size`
                       // per workgroup
  indirect,            // VkDispatchIndirectCommand at `counter_offset` of the batch's GpuCounters
  tile_workgroups,     // a workgroup per screen tile (RendererOptions::tile_size)
};

/// Which pipeline a pass binds.
enum class Variants {
  plain,           // the one built from `shader` and `spec`
  debug_coverage,  // that, or with TS_SPEC_DEBUG_COVERAGE on under RendererOptions::debug_coverage
  shading,       // chosen per frame by the scene and FrameSettings (renderer.cpp's shade_pipeline)
  lod,           // that, or under FrameSettings::lod automatic with TS_SPEC_LOD on and dispatched
                 // indirectly from the GpuCounters field at `counter_offset` (which lod_scan wrote)
  silhouette,    // only at several samples per pixel under AaCoverage::silhouette, built then
  raster_shade,  // specialized to the scene as the shading pass is (renderer.cpp's
                 // raster_shade_pipeline), built on first use
};

struct PassInfo {
  Pass pass;
  const char* name;    // in FrameStats, `tessera render` and `tessera bench` columns
  const char* shader;  // embedded name (shaders/<shader>.comp); null for Dispatch::none
  Stage stage;
  Dispatch dispatch;
  uint32_t groups = 0;      // Dispatch::fixed
  uint32_t group_size = 0;  // Dispatch::per_batch_triangle, ::per_object, ::per_pixel, ::per_tile
  uint32_t counter_offset = 0;  // Dispatch::indirect and Variants::lod: byte offset in GpuCounters
  Variants variants = Variants::plain;
  Specialization spec{};
};

constexpr PassInfo kPasses[] = {
    {Pass::environment, "environment", nullptr, Stage::precompute, Dispatch::none},
    {Pass::clear, "clear", nullptr, Stage::clear, Dispatch::none},
    {Pass::object_clip, "object_clip", "object_clip", Stage::objects, Dispatch::per_object, 0,
     TS_GROUP_SIZE},
    {Pass::lod, "lod", "lod", Stage::lod, Dispatch::per_object, 0, TS_LOD_GROUP_SIZE},
    {Pass::lod_scan, "lod_scan", "lod_scan", Stage::lod, Dispatch::fixed, 1},
    {Pass::lod_offsets, "lod_offsets", "lod_offsets", Stage::lod, Dispatch::per_object, 0,
     TS_LOD_GROUP_SIZE},
    {Pass::setup, "setup", "setup", Stage::batch, Dispatch::per_batch_triangle, 0,
     TS_SETUP_GROUP_SIZE, offsetof(gpu::GpuCounters, setup_dispatch), Variants::lod},
    {Pass::clip, "clip", "clip", Stage::batch, Dispatch::indirect, 0, 0,
     offsetof(gpu::GpuCounters, clip_dispatch)},
    {Pass::bin_count, "count", "count", Stage::batch, Dispatch::indirect, 0, 0,
     offsetof(gpu::GpuCounters, big_dispatch)},
    {Pass::scan, "scan", "scan", Stage::batch, Dispatch::per_tile, 0, TS_SCAN_GROUP_SIZE},
    {Pass::fill, "fill", "fill", Stage::batch, Dispatch::indirect, 0, 0,
     offsetof(gpu::GpuCounters, big_dispatch)},
    {Pass::raster_small, "raster_small", "raster_small", Stage::batch, Dispatch::indirect, 0, 0,
     offsetof(gpu::GpuCounters, small_dispatch), Variants::debug_coverage},
    {Pass::raster_tiles, "raster_tiles", "raster_tiles", Stage::batch, Dispatch::indirect, 0, 0,
     offsetof(gpu::GpuCounters, tiles_dispatch), Variants::debug_coverage},
    {Pass::raster_shade, "raster_shade", "raster_shade", Stage::frame, Dispatch::tile_workgroups, 0,
     0, 0, Variants::raster_shade},
    {Pass::list_tiles, "list_tiles", "list_tiles", Stage::frame, Dispatch::per_tile, 0,
     TS_GROUP_SIZE},
    {Pass::shade, "shade", "shade", Stage::frame, Dispatch::per_pixel, 0, 8, 0, Variants::shading},
    {Pass::outline, "outline", "outline", Stage::frame, Dispatch::indirect, 0, 0,
     offsetof(gpu::GpuCounters, outline_dispatch), Variants::silhouette},
    {Pass::resolve, "resolve", "resolve", Stage::frame, Dispatch::per_pixel, 0, 8},
};

constexpr bool pass_row_is_filled(const PassInfo& p) {
  if (p.name == nullptr || p.name[0] == '\0') return false;
  const bool dispatches = p.dispatch != Dispatch::none;
  if (dispatches != (p.stage == Stage::batch || p.stage == Stage::frame || p.stage == Stage::lod ||
                     p.stage == Stage::objects))
    return false;
  if (p.variants == Variants::lod &&
      (p.counter_offset % 4 != 0 ||
       p.counter_offset + 3 * sizeof(uint32_t) > sizeof(gpu::GpuCounters)))
    return false;
  if (dispatches != (p.shader != nullptr)) return false;
  switch (p.dispatch) {
    case Dispatch::fixed:
      return p.groups > 0;
    case Dispatch::per_batch_triangle:
    case Dispatch::per_object:
    case Dispatch::per_pixel:
    case Dispatch::per_tile:
      return p.group_size > 0;
    case Dispatch::indirect:  // a whole VkDispatchIndirectCommand inside GpuCounters
      return p.counter_offset % 4 == 0 &&
             p.counter_offset + 3 * sizeof(uint32_t) <= sizeof(gpu::GpuCounters);
    case Dispatch::none:
    case Dispatch::tile_workgroups:
      return true;
  }
  return false;
}

constexpr bool pass_table_is_complete() {
  bool batch_ended = false;
  for (size_t i = 0; i < std::size(kPasses); ++i) {
    const PassInfo& p = kPasses[i];
    if (size_t(p.pass) != i || !pass_row_is_filled(p)) return false;
    if (i > 0 && kPasses[i - 1].stage == Stage::batch && p.stage != Stage::batch)
      batch_ended = true;
    if (batch_ended && p.stage == Stage::batch) return false;  // batch rows must be contiguous
  }
  return std::size(kPasses) == kPassCount;
}
static_assert(pass_table_is_complete(),
              "kPasses: one row per Pass, in order, each filled for its dispatch kind, with the "
              "Stage::batch rows contiguous");

/// The name a pass is reported under.
constexpr const char* pass_name(Pass pass) {
  return kPasses[size_t(pass)].name;
}

/// Timestamps a frame of `batches` batches writes at most: one before the first pass and one
/// after each pass it records (the Stage::lod passes only under level of detail).
constexpr uint32_t timestamps_needed(uint32_t batches) {
  uint32_t per_frame = 1, per_batch = 0;
  for (const PassInfo& p : kPasses) (p.stage == Stage::batch ? per_batch : per_frame)++;
  return per_frame + per_batch * batches;
}

/// Pipelines outside the frame's pass sequence: the generic shading variants (used when the
/// shading pass is not specialized to the scene) and the precomputation passes.
enum class Pipeline {
  shade_classic,
  shade_filament,
  shade_blinn_phong,
  shade_classic_compensated,
  shade_filament_compensated,
  dfg_classic,  // the DFG tables, per visibility term
  dfg_filament,
  env_irradiance,  // the environment's irradiance coefficients
  env_prefilter,   // one level of the prefiltered specular cube
  resolve_bgra,    // the resolve pass storing B, G, R, A bytes, for B8G8R8A8 swapchain images
  hdr_rounding,    // how the device rounds stores to the RGBA16F image (probe_hdr_rounding)
  background,      // the background's stored and display colours (GpuBackground)
  count
};

struct PipelineInfo {
  Pipeline id;
  const char* shader;
  Specialization spec;
};

constexpr PipelineInfo kPipelines[] = {
    {Pipeline::shade_classic, "shade", {.brdf = TS_BRDF_CLASSIC}},
    {Pipeline::shade_filament, "shade", {.brdf = TS_BRDF_FILAMENT}},
    {Pipeline::shade_blinn_phong, "shade", {.brdf = TS_BRDF_BLINN_PHONG}},
    {Pipeline::shade_classic_compensated,
     "shade",
     {.brdf = TS_BRDF_CLASSIC, .energy_compensation = VK_TRUE}},
    {Pipeline::shade_filament_compensated,
     "shade",
     {.brdf = TS_BRDF_FILAMENT, .energy_compensation = VK_TRUE}},
    {Pipeline::dfg_classic, "dfg", {.brdf = TS_BRDF_CLASSIC}},
    {Pipeline::dfg_filament, "dfg", {.brdf = TS_BRDF_FILAMENT}},
    {Pipeline::env_irradiance, "env_irradiance", {}},
    {Pipeline::env_prefilter, "env_prefilter", {}},
    {Pipeline::resolve_bgra, "resolve", {.output_bgra = VK_TRUE}},
    {Pipeline::hdr_rounding, "hdr_rounding", {}},
    {Pipeline::background, "background", {}},
};

constexpr bool pipeline_table_is_complete() {
  for (size_t i = 0; i < std::size(kPipelines); ++i) {
    if (size_t(kPipelines[i].id) != i || kPipelines[i].shader == nullptr) return false;
  }
  return std::size(kPipelines) == size_t(Pipeline::count);
}
static_assert(pipeline_table_is_complete(), "kPipelines: one row per Pipeline, in order");

/// What a binding of the shared descriptor set holds, and who makes it.
enum class Source {
  frame_constants,  // the GpuFrame uniform buffer, written before each frame
  scene,            // an array of the scene, uploaded by Renderer::set_scene
  environment,      // a buffer or sampled image of EnvironmentGpu (environment_gpu.h)
  output_image,     // the HDR (RGBA16F or RGBA32F; stored, or sampled by the resolve pass) or
                    // display (RGBA8) image, sized by the frame
  sized,            // a buffer the renderer allocates by `size` below
};

/// What the size of a Source::sized buffer is a multiple of.
enum class Scale {
  fixed,                 // `bytes` in all
  pixels,                // per pixel of the frame
  samples,               // per sample of the frame: pixels times FrameSettings::samples
  pixels_if_coverage,    // per pixel under RendererOptions::debug_coverage, else 4 bytes
  tiles,                 // per screen tile (plus `extra` elements)
  raster_capacity,       // per raster triangle the scratch buffers hold (grows on overflow)
  objects,               // per object of the scene
  lod_groups,            // per TS_LOD_GROUP_SIZE objects of the scene
  objects_if_lod_draws,  // per object once the hardware baseline drew with level of detail,
                         // else 4 bytes
  tile_entry_capacity,   // per tile-list entry (grows on overflow)
  batches,               // per batch of the frame (GpuCounters slots)
  pixels_if_outlines,    // per pixel once a frame used silhouette coverage, else 4 bytes
};

/// When a Source::sized buffer is filled with `clear_value`: never, at the start of every
/// frame, or only when it is (re)created, for buffers the passes themselves leave cleared.
enum class Clear { never, per_frame, on_creation };

struct BindingInfo {
  uint32_t binding;  // TS_BINDING_*
  VkDescriptorType type;
  Source source;
  Scale scale = Scale::fixed;
  uint64_t bytes = 0;  // per element of `scale` (in all for Scale::fixed)
  uint32_t extra = 0;  // elements beyond the scale's count
  Clear clear = Clear::never;
  uint32_t clear_value = 0;
  VkBufferUsageFlags extra_usage = 0;  // besides the storage usage every buffer has
  // In device-local memory the host maps where the device has such memory
  // (MemoryKind::device_mapped): a per-frame clear is then the host's, which spares the frame a
  // fill and the barrier after it (about 5 us on the H200).
  bool host_mapped = false;
};

constexpr VkDescriptorType kStorageBuffer = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;

constexpr BindingInfo kBindings[] = {
    {TS_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, Source::frame_constants},
    {TS_BINDING_VERTICES, kStorageBuffer, Source::scene},
    {TS_BINDING_INDICES, kStorageBuffer, Source::scene},
    {TS_BINDING_OBJECTS, kStorageBuffer, Source::scene},
    {TS_BINDING_MATERIALS, kStorageBuffer, Source::scene},
    {TS_BINDING_LIGHTS, kStorageBuffer, Source::scene},
    {TS_BINDING_RASTER_TRIS, kStorageBuffer, Source::sized, Scale::raster_capacity,
     sizeof(gpu::GpuRasterTri)},
    {TS_BINDING_SMALL_LIST, kStorageBuffer, Source::sized, Scale::raster_capacity, 4},
    // (raster triangle, tile block) bin entries
    {TS_BINDING_BIG_LIST, kStorageBuffer, Source::sized, Scale::raster_capacity, 8},
    // Zeroed by raster_tiles as it reads each tile's count, ready for the next batch.
    {TS_BINDING_TILE_COUNTS, kStorageBuffer, Source::sized, Scale::tiles, 4, 0, Clear::on_creation},
    {TS_BINDING_TILE_OFFSETS, kStorageBuffer, Source::sized, Scale::tiles, 4, 1},
    {TS_BINDING_TILE_CURSORS, kStorageBuffer, Source::sized, Scale::tiles, 4},
    {TS_BINDING_TILE_ENTRIES, kStorageBuffer, Source::sized, Scale::tile_entry_capacity, 4},
    {TS_BINDING_COUNTERS, kStorageBuffer, Source::sized, Scale::batches, sizeof(gpu::GpuCounters),
     0, Clear::per_frame, 0, VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT, true},
    // Each pixel's samples together (shaders/samples.glsl).
    {TS_BINDING_VISIBILITY, kStorageBuffer, Source::sized, Scale::samples, 8, 0, Clear::per_frame,
     0xFFFFFFFFu},  // TS_VIS_EMPTY
    {TS_BINDING_COVERAGE, kStorageBuffer, Source::sized, Scale::pixels_if_coverage, 4, 0,
     Clear::per_frame},
    {TS_BINDING_HDR_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, Source::output_image},
    {TS_BINDING_LDR_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, Source::output_image},
    {TS_BINDING_CLIP_LIST, kStorageBuffer, Source::sized, Scale::raster_capacity, 4},
    // Two tables, then a row of cosine-weighted means per variant (shaders/dfg.comp); then the
    // background's colours (GpuBackground, shaders/background.comp).
    {TS_BINDING_DFG, kStorageBuffer, Source::sized, Scale::fixed,
     TS_BACKGROUND_OFFSET + sizeof(gpu::GpuBackground)},
    {TS_BINDING_TEXTURES, kStorageBuffer, Source::scene},
    {TS_BINDING_ENV_MAP, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, Source::environment},
    {TS_BINDING_ENV_SPECULAR, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, Source::environment},
    {TS_BINDING_ENV_LEVELS, kStorageBuffer, Source::environment},
    {TS_BINDING_ENV_IRRADIANCE, kStorageBuffer, Source::environment},
    {TS_BINDING_UV1, kStorageBuffer, Source::scene},
    // Level of detail: every mesh's chain, uploaded by the first frame that asks for it.
    {TS_BINDING_LOD_LEVELS, kStorageBuffer, Source::scene},
    {TS_BINDING_LOD_MESHES, kStorageBuffer, Source::scene},
    {TS_BINDING_LOD_SUMS, kStorageBuffer, Source::sized, Scale::lod_groups, 4},
    {TS_BINDING_LOD_DRAWS, kStorageBuffer, Source::sized, Scale::objects_if_lod_draws,
     sizeof(VkDrawIndexedIndirectCommand), 0, Clear::never, 0, VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT},
    {TS_BINDING_HDR_TEXTURE, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, Source::output_image},
    // Only lowered within a frame (every bound stays valid for the later batches); the shading
    // pass resets each tile's bound for the next frame (shade_tiles.glsl's reset_tile_bound).
    {TS_BINDING_TILE_FAR, kStorageBuffer, Source::sized, Scale::tiles, 4, 0, Clear::on_creation,
     0xFFFFFFFFu},
    {TS_BINDING_OBJECT_CLIP, kStorageBuffer, Source::sized, Scale::objects, sizeof(glm::mat4)},
    {TS_BINDING_ADJACENCY, kStorageBuffer, Source::scene},
    // As many entries as pixels: every pixel may be an outline pixel (10^6 spheres of a pixel).
    {TS_BINDING_OUTLINE, kStorageBuffer, Source::sized, Scale::pixels_if_outlines,
     sizeof(gpu::GpuOutlinePixel)},
    // Zeroed by list_tiles as it reads each tile's mark, ready for the next frame.
    {TS_BINDING_TILE_DRAWN, kStorageBuffer, Source::sized, Scale::tiles, 4, 0, Clear::on_creation},
    {TS_BINDING_SHADE_TILES, kStorageBuffer, Source::sized, Scale::tiles, 4},
};

constexpr bool binding_table_is_complete() {
  for (size_t i = 0; i < std::size(kBindings); ++i) {
    const BindingInfo& b = kBindings[i];
    if (b.binding != i) return false;
    const bool buffer =
        b.type == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER || b.type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    if (b.source == Source::sized && (!buffer || b.bytes == 0)) return false;
    if (b.source != Source::sized && (b.bytes != 0 || b.clear != Clear::never || b.host_mapped))
      return false;
    if (b.source == Source::output_image && b.type != VK_DESCRIPTOR_TYPE_STORAGE_IMAGE &&
        b.binding != TS_BINDING_HDR_TEXTURE)
      return false;
  }
  return std::size(kBindings) == TS_BINDING_COUNT;
}
static_assert(binding_table_is_complete(),
              "kBindings: one row per TS_BINDING_*, in order; a sized buffer has a size, and "
              "only sized buffers are cleared");

/// Descriptor type of binding `binding` (TS_BINDING_*) of the shared set.
constexpr VkDescriptorType binding_type(uint32_t binding) {
  return kBindings[binding].type;
}

/// Bindings of the shared set of descriptor type `type`.
constexpr uint32_t bindings_of_type(VkDescriptorType type) {
  uint32_t n = 0;
  for (const BindingInfo& b : kBindings) n += b.type == type ? 1 : 0;
  return n;
}

}  // namespace tessera
