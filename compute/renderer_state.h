#pragma once
// The renderer's private state (renderer.cpp). Not part of the public interface: other
// libraries reach the renderer through compute/renderer_internal.h.

#include <algorithm>
#include <array>
#include <map>
#include <optional>
#include <tuple>

#include "compute/environment_gpu.h"
#include "compute/gpu_memory.h"
#include "compute/pipelines.h"
#include "compute/renderer.h"
#include "compute/scene_upload.h"
#include "core/clip_prediction.h"
#include "shaders/shared/gpu_types.h"

namespace tessera {

struct Renderer::State {
  Context& ctx;
  RendererOptions options;
  // Shading by tiles as decided for this device (RendererOptions::shade_tiles, raster_tuning).
  bool shade_tiles = false;
  Pipelines pipelines;
  VkDescriptorPool descriptor_pool = VK_NULL_HANDLE;
  VkDescriptorSet set = VK_NULL_HANDLE;
  bool descriptors_dirty = true;
  // A buffer with Clear::on_creation was (re)created: the next frame's clear fills it.
  bool creation_clears_pending = true;
  uint64_t descriptors_generation = 0;  // counts the rewrites of `set` (copies follow it)

  // The scene as it is on the GPU.
  bool has_scene = false;
  GpuSceneArrays uploaded;
  TextureCache texture_cache;  // mip chains of the uploaded textures, reused by the next scene
  Camera camera;
  glm::vec3 background{0.0f};
  glm::vec3 ambient{0.0f};
  EnvironmentGpu env;

  // Level of detail (FrameSettings::lod).
  std::vector<Mesh> meshes;  // the scene's, for the chains a frame may ask for
  std::vector<LodChain>
      lod_chains;                 // the chains of the last scene that used them, reused by content
  bool lod_uploaded = false;      // `uploaded` and the GPU hold this scene's chains
  bool objects_hold_lod = false;  // the GPU's objects hold levels (the lod passes wrote them)
  uint64_t lod_triangles = 0;     // the last such frame's triangle instances (sizes batches)
  uint32_t frame_batches = 0;     // batches of the frame being recorded
  bool lod_draws = false;         // the hardware baseline drew with level of detail
  bool outlines = false;          // a frame used silhouette coverage (sizes TS_BINDING_OUTLINE)

  // Every buffer of the shared set that the renderer owns (kBindings' Source::scene, ::sized
  // and ::frame_constants), by binding (TS_BINDING_*); the others stay empty.
  std::array<Buffer, TS_BINDING_COUNT> buffers{};
  Buffer& buffer(uint32_t binding) { return buffers[binding]; }
  const Buffer& buffer(uint32_t binding) const { return buffers[binding]; }

  // Sized by the image.
  uint32_t width = 0, height = 0, tiles_x = 0, tiles_y = 0;
  uint32_t samples = 1;  // per pixel (FrameSettings::samples) of the visibility buffer
  HdrFormat hdr_format = HdrFormat::fp16;  // of `hdr` (FrameSettings::hdr_format)
  StorageImage hdr, ldr;
  // What the last frame multiplied the HDR image by (pre-exposure, shaders/bindings.glsl):
  // 2^EV for shaded frames, 1 for debug views. read_hdr divides it back out.
  float hdr_pre_exposure = 1.0f;
  uint64_t images_generation = 0;  // counts the times hdr and ldr were (re)created

  // Scratch, sized by capacities that grow on demand.
  uint32_t raster_capacity = 0, tile_entry_capacity = 0, batch_triangles = 0;
  // Direct tile lists (RendererOptions::tile_lists): slots per tile, 0 for counted lists; and
  // whether TileLists::automatic chose counted lists for this scene (set_scene clears it).
  uint32_t tile_list_stride = 0;
  bool tile_lists_counted = false;
  // The visibility buffer holds only empty keys: the last frame's shading emptied every key it
  // read (FrameSettings::keep_visibility off), so the next frame's clear skips its fill.
  bool visibility_clean = false;
  bool visibility_kept = true;  // the last frame kept its keys (read_visibility may read them)
  // The frame records no clip pass: the CPU found nothing to clip (core/clip_prediction.h).
  bool skip_clip = false;
  // That prediction for the scene and image size (frames without level of detail), made by the
  // first frame after set_scene or a new size.
  std::optional<bool> nothing_to_clip;
  std::vector<MeshBox> mesh_boxes;  // of `meshes`, for that prediction
  // The frame records no object_clip pass: its few triangles form their objects' clip-space
  // transforms themselves (TS_SPEC_OBJECT_CLIP_INLINE; renderer.cpp's forms_object_clip_in_setup).
  bool object_clip_inline = false;
  // This frame dispatches fill, raster_small and raster_tiles directly, sized by the last frame's
  // counts (renderer.cpp's dispatches_directly), and its batch passes' barriers wait for no
  // indirect-command read.
  bool direct_dispatch = false;
  // RendererOptions::raster_shade as the device resolves it, and whether this frame takes it
  // (renderer.cpp's rasterizes_and_shades_in_one_pass).
  bool raster_shade = false;
  bool raster_shade_frame = false;
  // What counters_readback holds: a frame of `batches` batches of `triangles` triangle
  // instances (valid false before the first frame and once the counters buffer is replaced).
  struct LastCounts {
    bool valid = false;
    uint32_t batches = 0;
    uint64_t triangles = 0;
  } last_counts;
  // The per-triangle rasterizer is recorded before the per-tile one (renderer.cpp's
  // barrier_after): on GPUs, where they overlap. A CPU device (lavapipe) runs dispatches one
  // after another, and raster_small recorded second can reject what lies behind the tile bounds
  // raster_tiles lowered.
  bool small_first = true;
  uint32_t counter_slots = 0;  // batches the GpuCounters buffer holds
  Buffer counters_readback;    // the counters, copied back after each frame

  Buffer frame_constants;  // GpuFrame (TS_BINDING_FRAME), written before each frame
  // The scene's texels (GpuSceneArrays::texels), which the shaders read at its device address
  // (GpuFrame.texels_address) rather than through a descriptor.
  Buffer texels;

  std::map<ShadeVariant, VkPipeline> shade_variants;  // specialized shading pipelines
  // The passes (by Pass) and generic shading pipelines (by Pipeline, after the passes) for more
  // than one sample per pixel, built on first use: key (index, samples, debug coverage, level
  // of detail, TS_AA_COVERAGE_*, silhouette steps).
  std::map<std::tuple<size_t, uint32_t, bool, bool, uint32_t, uint32_t>, VkPipeline>
      sampled_pipelines;
  // The frame constants the background's colours (GpuBackground, TS_BINDING_BACKGROUND) depend
  // on: those of this frame, and those the buffer was last computed from (none yet).
  struct BackgroundInputs {
    glm::vec3 background{0.0f};
    float exposure_scale = 0.0f;
    uint32_t view = 0, tonemap = 0, hdr_rounding = 0;
    float hdr_max = 0.0f;
    bool operator==(const BackgroundInputs&) const = default;
  };
  BackgroundInputs background_inputs;
  std::optional<BackgroundInputs> background_computed;
  bool dfg_ready = false;  // the DFG tables (TS_BINDING_DFG) are computed on the first frame
  // How the device rounds shader stores to the RGBA16F HDR image, probed by the first frame
  // that uses one: TS_HDR_ROUNDING_HALF_*, or TS_HDR_ROUNDING_AS_IS if the probe found neither
  // way (then the resolve pass runs on its own, reading the image).
  bool hdr_rounding_probed = false;
  uint32_t hdr_half_rounding = TS_HDR_ROUNDING_AS_IS;
  VkQueryPool queries = VK_NULL_HANDLE;
  uint32_t query_capacity = 0;

  explicit State(Context& c) : ctx(c) {}

  uint32_t max_raster_capacity() const {
    const VkPhysicalDeviceLimits& l = ctx.properties.limits;
    uint64_t by_range = l.maxStorageBufferRange / sizeof(gpu::GpuRasterTri);
    uint64_t by_budget = options.max_scratch_buffer_bytes / sizeof(gpu::GpuRasterTri);
    uint64_t by_dispatch = uint64_t(l.maxComputeWorkGroupCount[0]) * TS_GROUP_SIZE;
    return uint32_t(std::min({by_range, by_budget, by_dispatch, uint64_t(0xFFFFFFFFu)}));
  }
  uint32_t max_tile_entry_capacity() const {
    uint64_t by_range = ctx.properties.limits.maxStorageBufferRange / sizeof(uint32_t);
    uint64_t by_budget = options.max_scratch_buffer_bytes / sizeof(uint32_t);
    return uint32_t(std::min({by_range, by_budget, uint64_t(0xFFFFFFFFu)}));
  }
  // Most submitted triangles are culled, so a batch may hold more triangles than the raster
  // buffer: if its survivors overflow a buffer already at its limit, render() halves it.
  uint32_t max_batch() const {
    uint64_t by_dispatch =
        uint64_t(ctx.properties.limits.maxComputeWorkGroupCount[0]) * TS_SETUP_GROUP_SIZE;
    uint64_t limit = std::min<uint64_t>(by_dispatch, 1ull << 26);
    if (options.max_batch_triangles) limit = std::min<uint64_t>(limit, options.max_batch_triangles);
    return uint32_t(std::max<uint64_t>(limit, 1));
  }
};

/// Allocates the image-sized buffers and images for `settings` if the size changed. Returns true
/// if it did.
bool ensure_frame_resources(Renderer::State& s, const FrameSettings& settings);

/// Whether render() resolves in the shading pass (GpuFrame.resolve_in_shading): under
/// RendererOptions::resolve, with an RGBA32F HDR image or an RGBA16F one whose stores' rounding
/// the probe identified. Otherwise render() records the resolve pass, or the caller does.
bool resolves_in_shading(const Renderer::State& s);

/// Sets the scratch capacities and batch size from the scene and options, if not yet set.
void init_capacities(Renderer::State& s);

/// Allocates the scratch buffers for the current capacities and `batches` counter slots.
void ensure_scratch_buffers(Renderer::State& s, uint32_t batches);

/// Records what a frame with `settings` needs computed once, if it has not run yet: the DFG
/// tables (for energy compensation or image-based lighting) and the environment's irradiance
/// and prefiltered cube. The descriptor set must be bound. Returns true if it recorded anything.
bool record_precomputation(Renderer::State& s, VkCommandBuffer cmd, const FrameSettings& settings);

/// The shading pipeline for `settings` and the current scene: specialized to its lights (built
/// and cached on first use), and under shading by tiles to the dispatch `tiles`
/// (TS_SHADE_TILES_*), or the generic one.
VkPipeline shade_pipeline(Renderer::State& s, const FrameSettings& settings,
                          uint32_t tiles = TS_SHADE_TILES_OFF);

/// The pipeline of embedded shader `shader` specialized to `spec` with `samples` per pixel,
/// built on first use and kept in State::sampled_pipelines under `index` (a Pass, or
/// kPassCount + a Pipeline).
VkPipeline sampled_pipeline(Renderer::State& s, size_t index, const char* shader,
                            Specialization spec, uint32_t samples);

/// Size in bytes that Source::sized binding `info` needs now (at least 4).
uint64_t binding_size(const Renderer::State& s, const BindingInfo& info);
/// A Source::sized buffer of binding `info`, `bytes` long, in the memory its row asks for.
Buffer create_binding_buffer(const Context& ctx, const BindingInfo& info, uint64_t bytes);

/// Usage of every storage buffer: read and written by shaders, filled and copied by transfers,
/// and indices drawn from by a graphics pipeline (the hardware baseline).
constexpr VkBufferUsageFlags kStorageUsage =
    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
    VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_INDEX_BUFFER_BIT;

}  // namespace tessera
