#pragma once
// The compute rasterizer: created once per device, renders many frames of many scenes.
//
// Per frame: the passes of compute/passes.h (setup -> clip -> count -> scan -> fill ->
// raster_tiles -> raster_small per batch of triangle instances, then shade, which also resolves
// unless RendererOptions::resolve is off; see docs/architecture.md). The output
// stays on the GPU in two storage images (linear HDR, RGBA16F or RGBA32F as
// FrameSettings::hdr_format says, and display RGBA8) until read back.

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "compute/context.h"
#include "compute/environment_gpu.h"
#include "compute/gpu_memory.h"
#include "compute/passes.h"
#include "core/frame_settings.h"
#include "core/image.h"
#include "core/scene.h"

namespace tessera {

/// Layout of the per-tile lists of binned triangles (RendererOptions::tile_lists).
enum class TileLists {
  /// Counted: a count pass counts each tile's entries, a scan pass gives each list its packed
  /// range, and the fill pass writes them. Memory is the entries' alone.
  counted,
  /// Direct: each tile's list has a fixed number of slots (the stride), so the fill pass writes
  /// an entry at once and the count and scan passes are not run. The stride grows to the
  /// longest list (the frame is redone when a list overflows it), so the lists take the number
  /// of tiles times the longest list's length: with heavy overdraw in a few tiles, many times
  /// the entries.
  direct,
  /// Direct while the stride's lists take at most twice the memory counted lists would (and
  /// 4 MiB at least), counted from then on, until set_scene gives a scene of another triangle
  /// count.
  automatic,
};
const char* tile_lists_name(TileLists lists);  // "counted", "direct", "automatic"

struct RendererOptions {
  /// Triangles whose pixel box has at most this many pixels are rasterized one thread per
  /// triangle; larger ones are binned into tiles. Any value gives the same image.
  uint32_t small_triangle_max_area = 128;
  /// Pixels one thread of the per-triangle rasterizer walks, about: the rows of a larger box are
  /// dealt out among ceil(box pixels / this) threads (at most one per row), so that one thread
  /// does not walk a box alone while the rest of its SIMD group waits. At least 1 (the
  /// constructor throws Error otherwise). Any value gives the same image.
  uint32_t small_triangle_walk_area = 32;
  /// Side of the screen tiles that large triangles are binned into and rasterized by, one
  /// workgroup of tile_size^2 threads per tile: 8 or 16 (validate_tile_size). Either gives
  /// the same image; it trades binning work against idle threads. Size 8 holds images up to
  /// 8192 px a side (TS_MAX_TILES_PER_SIDE); the renderer throws Error for a size the device's
  /// workgroup limits cannot hold.
  uint32_t tile_size = TS_TILE_SIZE;
  /// Hierarchical depth rejection: the per-tile rasterizer skips tile-list entries, and the
  /// per-triangle one small triangles, whose nearest depth lies strictly behind a bound on
  /// everything already drawn in their tile(s) (FrameStats::rejected_*). Either setting gives
  /// the same image; off, every entry and small triangle is rasterized (for comparisons).
  bool depth_rejection = true;
  /// Shading by tiles: the rasterizers mark the screen tiles they draw into, a pass lists them
  /// (Pass::list_tiles), and the shading pass runs over those tiles only, with a background
  /// pass for the others that reads no visibility key and runs no shading code. Either setting
  /// gives the same image. It saves most on CPU devices, which run a shader's every instruction
  /// for every pixel dispatched, and costs GPUs a pass (raster_tuning). Unset: the device's
  /// choice, raster_tuning's. Only with specialize_lights: the generic shading pipelines shade
  /// every pixel.
  std::optional<bool> shade_tiles;
  /// Small frames rasterized and shaded in one pass (Pass::raster_shade): every screen tile's
  /// workgroup tests every raster triangle whose pixel box meets the tile, then shades its
  /// pixels, in place of the bin, fill, rasterizer and shading passes and the barriers between
  /// them. Taken by a frame of one batch at one sample, with no clip pass, no level of detail,
  /// no debug coverage and no shading by tiles, whose last frame (of the same scene) set up at
  /// most kRasterShadeMaxTriangles raster triangles, of which at most
  /// kRasterShadeMaxTrianglesPerTile large ones per tile on average. Either setting gives the same
  /// image. Unset: the device's choice, raster_tuning's (on for GPUs). Only with specialize_lights.
  std::optional<bool> raster_shade;
  /// How the tile lists of binned triangles are laid out (TileLists). Every choice gives the
  /// same image; direct lists skip two passes of every batch.
  TileLists tile_lists = TileLists::automatic;
  /// Most triangle instances set up per batch (0: as many as the scratch buffers allow).
  uint32_t max_batch_triangles = 0;
  /// Starting capacities of the scratch buffers (0: sized from the scene). They grow, and the
  /// frame is rendered again, whenever a frame needs more: nothing is ever dropped.
  uint32_t initial_raster_capacity = 0;
  uint32_t initial_tile_entry_capacity = 0;
  /// Upper bound on each scratch buffer, in bytes, besides the device's maxStorageBufferRange.
  /// Past it the renderer splits the frame into more batches instead of growing.
  uint64_t max_scratch_buffer_bytes = 256ull << 20;
  /// Largest staging buffer through which set_scene (and level of detail) uploads, in bytes,
  /// refilled as often as the uploads need: a scene's uploads may exceed the device's
  /// maxMemoryAllocationSize (2^30 at least) with a texel buffer near it. Any value gives the
  /// same scene; tests set a few bytes to split every upload. At least 1 (the constructor
  /// throws Error otherwise).
  uint64_t staging_chunk_bytes = 256ull << 20;
  /// Specializes the shading pass to the scene: its light counts, the texture maps its
  /// materials use and whether it has an environment (pipelines built on first use of a
  /// combination, then cached). Off, one generic pipeline with every feature decides at run
  /// time, per light, per material map and per frame.
  bool specialize_lights = true;
  /// Which faces setup culls. Back faces by default; tests of closed meshes use the others.
  CullMode cull = CullMode::back;
  /// Counts every covered sample per pixel (read_coverage), to check that each pixel is
  /// covered exactly once. Slower; for tests.
  bool debug_coverage = false;
  /// Resolves in render() (tone mapping, sRGB encoding into the display image, done by the
  /// shading pass: GpuFrame.resolve_in_shading).
  /// Off, render() stops after shading and the caller records the resolve into an image of its
  /// own (RendererInternal::record_resolve_into), as the window does into swapchain images;
  /// read_ldr and output_image then hold what the caller resolved there.
  bool resolve = true;
  /// Resolutions and sample counts of the image-based lighting, applied when a scene's
  /// environment is set (set_scene throws Error for values out of range).
  EnvironmentOptions environment;
};

/// Throws Error naming `tile_size` unless it is 8 or 16.
void validate_tile_size(uint32_t tile_size);

/// What Renderer::render throws for an image size (with its samples per pixel) that this
/// device, or the tile size, cannot take, told apart from other errors: where a command line
/// asked for the size, the tool reports a bad command line (host/report.h).
struct ImageSizeError : Error {
  ImageSizeError(uint32_t width, uint32_t height, const std::string& reason)
      : Error("image size " + std::to_string(width) + "x" + std::to_string(height) + " " + reason),
        width(width),
        height(height),
        reason(reason) {}
  uint32_t width, height;
  /// Why, after the size, with the largest the device takes where that is simple ("needs a
  /// 2048 MiB visibility buffer, ...: this device takes at most 16777216 pixels at 1 sample,
  /// 4096x4096").
  std::string reason;
};

/// What Renderer::set_scene (and render, for the level-of-detail chains it appends) throws for a
/// scene one of whose storage buffers would be larger than this device's maxStorageBufferRange,
/// the most a descriptor may bind, before any of it is uploaded: told apart from other errors so
/// that `tessera bench` can name the --objects count that needs it.
struct SceneSizeError : Error {
  SceneSizeError(const std::string& message, std::string buffer, uint64_t bytes, uint64_t limit)
      : Error(message), buffer(std::move(buffer)), bytes(bytes), limit(limit) {}
  std::string buffer;  // "object buffer"
  uint64_t bytes;      // that the scene needs in it
  uint64_t limit;      // maxStorageBufferRange
};

/// The rasterizer settings of RendererOptions that change the speed and never the image.
struct RasterTuning {
  uint32_t small_triangle_max_area;
  uint32_t small_triangle_walk_area;
  bool depth_rejection;
  bool shade_tiles;
  TileLists tile_lists;
  bool raster_shade;
};

/// The settings measured fastest on a device of `type` (docs/performance.md, "Device-tuned
/// rasterization"): RendererOptions' defaults, tuned on GPUs, except on CPU devices
/// (VK_PHYSICAL_DEVICE_TYPE_CPU, such as lavapipe), which take every triangle whose pixel box
/// has up to kCpuSmallTriangleArea pixels on the per-triangle rasterizer, walking each box with
/// one thread (small_triangle_walk_area = kCpuSmallTriangleArea), shade by tiles and
/// count their tile lists (with direct lists raster_small's dispatch, sized as setup appends, is
/// rounded up to 1,024 triangles, and lavapipe ran one sphere's 8 workgroups of triangles and 8
/// empty ones in 1.45 ms instead of 0.96).
RasterTuning raster_tuning(VkPhysicalDeviceType type);
constexpr uint32_t kCpuSmallTriangleArea = 4096;
/// Most raster triangles (FrameStats::raster_triangles) of the last frame for which a frame
/// rasterizes and shades in one pass (RendererOptions::raster_shade): each tile's workgroup
/// tests them all, so the pass's work grows with tiles times triangles. On the H200 one grid
/// sphere (328 raster triangles) took 0.050 ms instead of 0.064 at 1920x1080 and 0.029 instead
/// of 0.038 at 512x512, ten (4,200) 0.149 instead of 0.089 and 0.050 instead of 0.033; the
/// lines cross near 800 and 1,700 triangles (docs/performance.md, "Issue 13, thirteenth round").
constexpr uint32_t kRasterShadeMaxTriangles = 512;
/// And at most this many large triangles (pixel boxes over the small-triangle area) per tile on
/// average, counting each in every tile its box meets (FrameStats::large_box_tiles): the pass
/// tests every pixel of a tile against each, without the depth rejection of the separate
/// passes. On the H200 at 1920x1080 four triangles each covering the image (the huge family)
/// took 0.146 ms in one pass against 0.166 in the separate passes, eight 0.192 against 0.168
/// (docs/performance.md, "Issue 13, thirteenth round").
constexpr uint32_t kRasterShadeMaxTrianglesPerTile = 4;

/// `options` with raster_tuning's settings for `ctx`'s device: what the command-line tool
/// starts from, before the options its user gives.
RendererOptions tuned_for_device(const Context& ctx, RendererOptions options);

/// What a frame's GPU timestamps measure.
enum class Timing {
  per_pass,  // each pass (FrameStats::pass_ms) and the frame
  frame,     // the frame alone (pass_ms all 0): a timestamp after every pass costs the H200
             // about 0.8 us each, 6 % of a one-sphere frame (docs/performance.md, "Issue 13,
             // sixth round"), so the frame's own time is measured without them
};

struct FrameStats {
  bool has_timestamps = false;               // false if the queue cannot write timestamps
  std::array<double, kPassCount> pass_ms{};  // GPU time per Pass of the final attempt, summed
                                             // over batches (0 under Timing::frame)
  double gpu_total_ms = 0.0;
  // GPU time of the precomputation (Pass::environment) this frame ran, in whichever attempt ran
  // it: a frame redone after growing a buffer (the first with level of detail, say) ran it in
  // its first attempt, and pass_ms, of the final attempt, has 0 for it. 0 under Timing::frame.
  double precompute_ms = 0.0;
  double cpu_record_submit_ms = 0.0;   // recording and submitting the final attempt
  uint64_t triangles_submitted = 0;    // triangle instances set up (after the level of detail)
  uint64_t triangles_without_lod = 0;  // triangle instances of the meshes as they are
  uint64_t raster_triangles = 0;       // after culling and clipping
  uint64_t small_triangles = 0;
  uint64_t big_triangles = 0;
  uint64_t tile_entries = 0;
  // The (tile, triangle) pairs of the pixel boxes of triangles larger than the small-triangle
  // area (at least tile_entries, which leaves out tiles a triangle's edges miss): what
  // RendererOptions::raster_shade's choice goes by.
  uint64_t large_box_tiles = 0;
  uint32_t tile_list_stride = 0;  // slots per tile list (TileLists::direct), 0 if counted
  uint64_t culled_backface = 0;   // culled by facing (RendererOptions::cull)
  uint64_t culled_frustum = 0;
  uint64_t culled_empty = 0;
  uint64_t culled_nonfinite = 0;
  uint64_t clipped = 0;
  uint64_t rejected_entries = 0;  // tile-list entries skipped by depth rejection, unrasterized
  uint64_t rejected_small = 0;    // small triangles skipped likewise
  // Shading by tiles (RendererOptions::shade_tiles; else 0): screen tiles the rasterizers drew
  // into, which the shading pass shaded, and the others, given the background alone.
  uint64_t shaded_tiles = 0;
  uint64_t background_tiles = 0;
  uint32_t batches = 0;
  uint32_t attempts = 0;  // 1, plus one per re-render after growing a buffer or splitting
  // The final attempt dispatched the passes after setup directly, sized by the frame before
  // (direct tile lists, from a scene's second frame on; docs/architecture.md, "The frame").
  bool dispatched_directly = false;
  // The final attempt rasterized and shaded in one pass (RendererOptions::raster_shade). Such
  // a frame fills no lists: small_triangles, big_triangles, tile_entries and the rejected
  // counts are 0.
  bool rasterized_and_shaded = false;
};

struct UploadStats {
  uint64_t bytes = 0;                // bytes copied to the GPU
  uint32_t buffers_created = 0;      // buffers (re)allocated because they were too small
  bool environment_changed = false;  // the environment was uploaded and will be precomputed
  uint32_t mip_chains_built = 0;     // textures whose content the previous scene did not have
};

/// Throws ImageSizeError unless a Renderer with tiles of `tile_size` on `ctx` renders frames of
/// `width` x `height` at `samples` per pixel: what render checks first, for a command to refuse
/// a size before it builds a renderer (or opens a window).
void check_image_size(const Context& ctx, uint32_t width, uint32_t height, uint32_t samples,
                      uint32_t tile_size);

class Renderer {
 public:
  /// Builds every pipeline once. `ctx` must outlive the renderer.
  explicit Renderer(Context& ctx, const RendererOptions& options = {});
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Validates `scene` (throws Error on bad input, SceneSizeError for a buffer larger than the
  /// device binds) and makes it the scene rendered next; a refused scene leaves the previous one.
  /// Compared with the scene set before, only the changed range of each array is uploaded.
  UploadStats set_scene(const Scene& scene);

  /// Makes `camera` the camera of the scene set last, as set_scene with only the camera changed
  /// would, without flattening or comparing the scene's arrays again: what a window's orbiting
  /// needs every frame (a scene of 300,000 objects took 1.5 s a frame through set_scene).
  /// Throws Error for a camera validate_scene refuses, or when no scene was set.
  void set_camera(const Camera& camera);

  /// Whether render(settings) of the current scene builds its shading pass's pipeline first:
  /// with RendererOptions::specialize_lights, one per set of lights (by kind), material maps,
  /// environment, BRDF, energy compensation and samples, built the first time a context
  /// renders that set (lavapipe: 1.4 to 2.4 s on a loaded 2-core machine), as when a light is
  /// added. Never with specialize_lights off (the generic pipelines take any scene).
  bool builds_shading_pipeline(const FrameSettings& settings) const;

  /// Renders the current scene into the output images. Throws ImageSizeError for a size the
  /// device cannot handle, SceneSizeError when the level-of-detail chains (FrameSettings::lod)
  /// make a buffer larger than the device binds, Error when no scene was set.
  FrameStats render(const FrameSettings& settings, Timing timing = Timing::per_pass);

  /// Copies of the last frame. read_coverage needs RendererOptions::debug_coverage; it counts
  /// covered samples per pixel. read_visibility holds FrameSettings::samples keys per pixel,
  /// row-major, each pixel's samples together in the order of their TS_SAMPLES_* positions;
  /// it and read_visibility_at throw Error if the last frame did not keep them
  /// (FrameSettings::keep_visibility).
  ImageF read_hdr() const;
  Image8 read_ldr() const;
  std::vector<uint64_t> read_visibility() const;
  std::vector<uint32_t> read_coverage() const;
  /// The last frame's visibility key at pixel (x, y) (< the frame's size; TS_VIS_EMPTY where
  /// no triangle covers it; its first sample with several): an 8-byte read-back, for picking.
  uint64_t read_visibility_at(uint32_t x, uint32_t y) const;

  /// The DFG tables (classic, then filament; TS_DFG_SIZE^2 each, rows by roughness): x the
  /// Schlick-weighted, y the whole specular albedo with F = 1, z the cosine-weighted mean of
  /// the Schlick factor (1 - V.H)^5 over light directions (the classic diffuse term under a
  /// uniform environment), at N.V and roughness
  /// i / (TS_DFG_SIZE - 1). Then TS_DFG_SIZE rows per variant (classic, filament), one per
  /// roughness: the cosine-weighted means over N.V of E (x), E_Fc (y) and E_Fc / E (z).
  /// Computed by the first frame with energy compensation; throws
  /// Error before that.
  std::vector<glm::vec4> read_dfg_table() const;

  /// The display image (RGBA8, VK_IMAGE_LAYOUT_GENERAL, usable as a copy or blit source).
  const StorageImage& output_image() const;
  /// Maps a triangle-instance id from read_visibility to its index in Scene::objects (after a
  /// frame with level of detail, through the levels that frame chose: a read-back).
  uint32_t object_of_triangle(uint32_t triangle_id) const;
  /// How the last frame numbered its triangle instances (core/pick.h): the scene's numbering,
  /// or after a frame with level of detail the levels it chose (a read-back). For mapping many
  /// visibility keys at once with pick_object.
  ObjectNumbering triangle_numbering() const;

  struct State;  // internal (compute/renderer_state.h)

 private:
  friend class RendererInternal;  // the internal interface (compute/renderer_internal.h)

  void update_descriptors();
  void write_frame_constants(const FrameSettings& settings);
  // `query_passes`: the pass that ends at each timestamp after the first, Pass::count for the
  // frame's end under Timing::frame.
  void record_frame(VkCommandBuffer cmd, uint32_t batches, bool timestamps, Timing timing,
                    std::vector<Pass>& query_passes, const FrameSettings& settings);

  std::unique_ptr<State> s_;
};

}  // namespace tessera
