#include "compute/renderer.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <string>

#include <glm/gtc/packing.hpp>

#include "compute/pipelines.h"
#include "compute/readback.h"
#include "compute/renderer_internal.h"
#include "compute/renderer_state.h"
#include "compute/scene_upload.h"
#include "compute/timestamps.h"
#include "compute/vk_check.h"
#include "core/check.h"
#include "core/lod.h"
#include "core/pick.h"
#include "shaders/shared/gpu_types.h"

namespace tessera {
namespace {

constexpr uint32_t kMaxAttempts = 64;

uint32_t div_up(uint64_t a, uint64_t b) {
  return uint32_t((a + b - 1) / b);
}

// Whether a frame of `settings` lists outline pixels for the outline pass (silhouette coverage).
bool lists_outlines(const FrameSettings& settings) {
  return settings.samples > 1 && settings.aa_coverage == AaCoverage::silhouette;
}

// Whether the frame's shading empties the keys it reads (FrameSettings::keep_visibility off),
// which the outline pass, reading keys after shading, does not allow.
bool resets_visibility(const FrameSettings& settings) {
  return !settings.keep_visibility && !lists_outlines(settings);
}

// Barrier between two compute passes: writes of the first visible to reads and writes of the
// second, and to indirect-argument reads.
void compute_to_compute(VkCommandBuffer cmd) {
  memory_barrier(
      cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
      VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT,
      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT,
      VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT);
}

void transfer_to_compute(VkCommandBuffer cmd) {
  memory_barrier(
      cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT,
      VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT);
}

// Everything before (earlier submissions included) complete and visible to everything after.
void full_barrier(VkCommandBuffer cmd) {
  memory_barrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_WRITE_BIT,
                 VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                 VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT);
}

uint32_t tonemap_id(ToneMap t) {
  switch (t) {
    case ToneMap::aces:
      return TS_TONEMAP_ACES;
    case ToneMap::reinhard:
      return TS_TONEMAP_REINHARD;
    case ToneMap::clamp:
      return TS_TONEMAP_CLAMP;
  }
  return TS_TONEMAP_ACES;
}

uint32_t view_id(View v) {
  switch (v) {
    case View::shaded:
      return TS_VIEW_SHADED;
    case View::normal:
      return TS_VIEW_NORMAL;
    case View::uv:
      return TS_VIEW_UV;
    case View::triangle:
      return TS_VIEW_TRIANGLE;
    case View::object:
      return TS_VIEW_OBJECT;
  }
  return TS_VIEW_SHADED;
}

// Throws Error unless the device's workgroups hold a tile of `tile_size`^2 threads.
void check_tile_size(const Context& ctx, uint32_t tile_size) {
  validate_tile_size(tile_size);
  const VkPhysicalDeviceLimits& l = ctx.properties.limits;
  if (tile_size * tile_size > l.maxComputeWorkGroupInvocations ||
      tile_size > l.maxComputeWorkGroupSize[0] || tile_size > l.maxComputeWorkGroupSize[1]) {
    throw Error("tile size " + std::to_string(tile_size) + " needs workgroups of " +
                std::to_string(tile_size) + "x" + std::to_string(tile_size) +
                " threads, more than this device's maxComputeWorkGroupInvocations (" +
                std::to_string(l.maxComputeWorkGroupInvocations) + ")");
  }
}

VkFormat hdr_vk_format(HdrFormat format) {
  return format == HdrFormat::fp32 ? VK_FORMAT_R32G32B32A32_SFLOAT : VK_FORMAT_R16G16B16A16_SFLOAT;
}

}  // namespace

const char* tile_lists_name(TileLists lists) {
  switch (lists) {
    case TileLists::counted:
      return "counted";
    case TileLists::direct:
      return "direct";
    case TileLists::automatic:
      break;
  }
  return "automatic";
}

void validate_tile_size(uint32_t tile_size) {
  // 32 (1024 threads a tile) gave other images than 16 on lavapipe at 4 samples per pixel with
  // every triangle binned (docs/architecture.md, "Tile size"): refused until that is explained.
  if (tile_size != 8 && tile_size != 16)
    throw Error("tile size " + std::to_string(tile_size) + " is not 8 or 16");
}

RasterTuning raster_tuning(VkPhysicalDeviceType type) {
  const RendererOptions gpu;
  if (type != VK_PHYSICAL_DEVICE_TYPE_CPU)
    return {.small_triangle_max_area = gpu.small_triangle_max_area,
            .small_triangle_walk_area = gpu.small_triangle_walk_area,
            .depth_rejection = gpu.depth_rejection,
            .shade_tiles = false,
            .tile_lists = gpu.tile_lists,
            .raster_shade = true};
  // A CPU device runs both sides of every branch and at least one iteration of every loop for
  // each group of 8 lanes: one workgroup of 256 threads per tile pays that for all of its
  // subgroups however little the tile holds, where one thread per triangle pays it once for 8
  // triangles; and the shading pass pays the whole shading code for background pixels unless
  // they are not dispatched to it, as rasterizing and shading in one pass would for every pixel
  // (one grid sphere at 512x512: 32.7 ms, against 14.0 with these settings).
  // Each box is walked whole by one thread (its walk area is the small-triangle area), as in
  // the measurements that chose these settings; shorter walks were not measured apart there.
  return {.small_triangle_max_area = kCpuSmallTriangleArea,
          .small_triangle_walk_area = kCpuSmallTriangleArea,
          .depth_rejection = gpu.depth_rejection,
          .shade_tiles = true,
          .tile_lists = TileLists::counted,
          .raster_shade = false};
}

RendererOptions tuned_for_device(const Context& ctx, RendererOptions options) {
  const RasterTuning t = raster_tuning(ctx.properties.deviceType);
  options.small_triangle_max_area = t.small_triangle_max_area;
  options.small_triangle_walk_area = t.small_triangle_walk_area;
  options.depth_rejection = t.depth_rejection;
  options.shade_tiles = t.shade_tiles;
  options.tile_lists = t.tile_lists;
  options.raster_shade = t.raster_shade;
  return options;
}

Renderer::Renderer(Context& ctx, const RendererOptions& options)
    : s_(std::make_unique<State>(ctx)) {
  s_->options = options;
  // The generic shading pipelines shade every pixel (RendererOptions::shade_tiles).
  s_->shade_tiles =
      options.shade_tiles.value_or(raster_tuning(ctx.properties.deviceType).shade_tiles) &&
      options.specialize_lights;
  s_->raster_shade =
      options.raster_shade.value_or(raster_tuning(ctx.properties.deviceType).raster_shade) &&
      options.specialize_lights;
  s_->small_first = ctx.properties.deviceType != VK_PHYSICAL_DEVICE_TYPE_CPU;
  check_tile_size(ctx, options.tile_size);
  if (options.small_triangle_walk_area == 0)
    throw Error("small-triangle walk area must be at least 1 pixel");
  if (options.staging_chunk_bytes == 0) throw Error("staging chunk must be at least 1 byte");
  s_->pipelines =
      create_pipelines(ctx, options.tile_size, options.depth_rejection, s_->shade_tiles);

  constexpr VkDescriptorType kTypes[] = {
      VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
      VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER};
  static_assert(bindings_of_type(kTypes[0]) + bindings_of_type(kTypes[1]) +
                        bindings_of_type(kTypes[2]) + bindings_of_type(kTypes[3]) ==
                    TS_BINDING_COUNT,
                "the pool has room for every descriptor type of kBindings");
  std::vector<VkDescriptorPoolSize> sizes;
  for (VkDescriptorType type : kTypes) {
    if (bindings_of_type(type)) sizes.push_back({type, bindings_of_type(type)});
  }
  VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pool_info.maxSets = 1;
  pool_info.poolSizeCount = uint32_t(sizes.size());
  pool_info.pPoolSizes = sizes.data();
  VK_CHECK(vkCreateDescriptorPool(ctx.device, &pool_info, nullptr, &s_->descriptor_pool));
  VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  alloc.descriptorPool = s_->descriptor_pool;
  alloc.descriptorSetCount = 1;
  alloc.pSetLayouts = &s_->pipelines.set_layout;
  VK_CHECK(vkAllocateDescriptorSets(ctx.device, &alloc, &s_->set));

  for (const BindingInfo& b : kBindings) {
    if (b.source == Source::sized && b.scale == Scale::fixed) {
      s_->buffer(b.binding) = create_binding_buffer(ctx, b, binding_size(*s_, b));
    }
  }
  s_->frame_constants = create_buffer(ctx, sizeof(gpu::GpuFrame),
                                      VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, MemoryKind::upload);
  validate_environment_options(options.environment);
  create_environment_gpu(ctx, s_->env);
}

Renderer::~Renderer() {
  Context& ctx = s_->ctx;
  vkDeviceWaitIdle(ctx.device);
  for (Buffer& b : s_->buffers) destroy_buffer(ctx, b);
  destroy_buffer(ctx, s_->texels);
  destroy_buffer(ctx, s_->counters_readback);
  destroy_buffer(ctx, s_->frame_constants);
  destroy_environment_gpu(ctx, s_->env);
  // shade_variants, sampled_pipelines and `pipelines` belong to the context (PipelineCache).
  destroy_image(ctx, s_->hdr);
  destroy_image(ctx, s_->ldr);
  if (s_->queries) vkDestroyQueryPool(ctx.device, s_->queries, nullptr);
  vkDestroyDescriptorPool(ctx.device, s_->descriptor_pool, nullptr);
  destroy_pipelines(ctx, s_->pipelines);
}

namespace {

struct PendingCopy {
  VkBuffer dst;
  VkDeviceSize dst_offset;
  const void* data;
  VkDeviceSize size;
};

// Makes `buffer` a new one of at least `bytes` if it is smaller (or none); returns whether it did.
// `extra_usage` VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT: a buffer the shaders read at its
// address (the texels), which no descriptor binds.
bool reallocate_if_smaller(const Context& ctx, Buffer& buffer, VkDeviceSize bytes,
                           UploadStats& stats, bool& dirty, VkBufferUsageFlags extra_usage = 0) {
  if (buffer.buffer && buffer.size >= bytes) return false;
  destroy_buffer(ctx, buffer);
  // Never empty (Vulkan forbids size 0); room to grow so small edits do not reallocate, but not
  // past what a descriptor binds whole (check_scene_buffers refused a larger `bytes`) or, for a
  // buffer read by address, past what the device allocates (check_texel_buffer).
  const uint64_t cap = extra_usage & VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT
                           ? largest_addressed_buffer(addressed_buffer_limits(ctx))
                           : ctx.properties.limits.maxStorageBufferRange;
  const VkDeviceSize room =
      std::min<VkDeviceSize>(bytes + bytes / 4, std::max<VkDeviceSize>(bytes, cap));
  buffer = create_buffer(ctx, std::max<VkDeviceSize>(room, 256), kStorageUsage | extra_usage,
                         MemoryKind::device);
  stats.buffers_created++;
  dirty = true;
  return true;
}

// Reallocates `buffer` and queues a copy of all of `next` if the buffer is too small for it.
// Returns true if it did.
template <typename T>
bool queue_reallocation(const Context& ctx, Buffer& buffer, const std::vector<T>& next,
                        std::vector<PendingCopy>& copies, UploadStats& stats, bool& dirty,
                        VkBufferUsageFlags extra_usage = 0) {
  const VkDeviceSize bytes = next.size() * sizeof(T);
  if (!reallocate_if_smaller(ctx, buffer, bytes, stats, dirty, extra_usage)) return false;
  if (bytes) copies.push_back({buffer.buffer, 0, next.data(), bytes});
  return true;
}

// Makes `buffer` hold `array`, given that it holds its first `from` elements.
template <typename T>
void queue_tail_upload(const Context& ctx, Buffer& buffer, const std::vector<T>& array, size_t from,
                       std::vector<PendingCopy>& copies, UploadStats& stats, bool& dirty) {
  if (queue_reallocation(ctx, buffer, array, copies, stats, dirty) || from >= array.size()) return;
  copies.push_back(
      {buffer.buffer, from * sizeof(T), &array[from], (array.size() - from) * sizeof(T)});
}

// Queues a copy of the range of elements of `next` that differ from `previous`, which `buffer`
// holds from byte `offset` on (nothing if none does).
template <typename T>
void queue_changed_range(const Buffer& buffer, VkDeviceSize offset, const std::vector<T>& previous,
                         const std::vector<T>& next, std::vector<PendingCopy>& copies) {
  size_t first = 0;
  size_t common = std::min(previous.size(), next.size());
  while (first < common && std::memcmp(&previous[first], &next[first], sizeof(T)) == 0) ++first;
  if (first == next.size()) return;
  size_t last = next.size();  // one past the last element that differs
  while (last > first && last <= common &&
         std::memcmp(&previous[last - 1], &next[last - 1], sizeof(T)) == 0) {
    --last;
  }
  copies.push_back(
      {buffer.buffer, offset + first * sizeof(T), &next[first], (last - first) * sizeof(T)});
}

// Makes `buffer` hold `next`, given that it holds `previous`: reallocates if it is too small,
// else queues a copy of the range of elements that differ (nothing if none does).
template <typename T>
void queue_array_upload(const Context& ctx, Buffer& buffer, const std::vector<T>& previous,
                        const std::vector<T>& next, std::vector<PendingCopy>& copies,
                        UploadStats& stats, bool& dirty, VkBufferUsageFlags extra_usage = 0) {
  if (queue_reallocation(ctx, buffer, next, copies, stats, dirty, extra_usage)) return;
  queue_changed_range(buffer, 0, previous, next, copies);
}

// Makes the objects' buffer hold next.objects and after them next.group_objects (the group
// table, TS_TRIANGLE_GROUP_BITS), given that it holds prev's: as queue_array_upload, the table
// copied whole when the objects' count moved it.
void queue_objects_upload(const Context& ctx, Buffer& buffer, const GpuSceneArrays& prev,
                          const GpuSceneArrays& next, std::vector<PendingCopy>& copies,
                          UploadStats& stats, bool& dirty) {
  const VkDeviceSize object_bytes = next.objects.size() * sizeof(gpu::GpuObject);
  const VkDeviceSize table_bytes = next.group_objects.size() * sizeof(uint32_t);
  const bool reallocated =
      reallocate_if_smaller(ctx, buffer, object_bytes + table_bytes, stats, dirty);
  if (reallocated || prev.objects.size() != next.objects.size()) {
    if (object_bytes) copies.push_back({buffer.buffer, 0, next.objects.data(), object_bytes});
    if (table_bytes) {
      copies.push_back({buffer.buffer, object_bytes, next.group_objects.data(), table_bytes});
    }
    return;
  }
  queue_changed_range(buffer, 0, prev.objects, next.objects, copies);
  queue_changed_range(buffer, object_bytes, prev.group_objects, next.group_objects, copies);
}

// Copies `copies` to the GPU (through a staging buffer of at most `chunk` bytes,
// RendererOptions::staging_chunk_bytes, refilled as often as they need) and waits. Returns the
// bytes copied.
VkDeviceSize submit_copies(const Context& ctx, const std::vector<PendingCopy>& copies,
                           VkDeviceSize chunk) {
  VkDeviceSize total = 0;
  for (const PendingCopy& c : copies) total += c.size;
  if (total == 0) return 0;
  Buffer staging = create_buffer(ctx, std::min(total, chunk), VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                 MemoryKind::upload);
  size_t next = 0;        // the copy being staged
  VkDeviceSize done = 0;  // its bytes staged before
  while (next < copies.size()) {
    std::vector<VkBufferCopy> regions;  // with each region's destination buffer
    std::vector<VkBuffer> dsts;
    VkDeviceSize offset = 0;
    while (next < copies.size() && offset < staging.size) {
      const PendingCopy& c = copies[next];
      const VkDeviceSize n = std::min(c.size - done, staging.size - offset);
      std::memcpy(static_cast<char*>(staging.mapped) + offset,
                  static_cast<const char*>(c.data) + done, n);
      regions.push_back({offset, c.dst_offset + done, n});
      dsts.push_back(c.dst);
      offset += n;
      done += n;
      if (done == c.size) {
        ++next;
        done = 0;
      }
    }
    submit_and_wait(ctx, [&](VkCommandBuffer cmd) {
      full_barrier(cmd);
      for (size_t i = 0; i < regions.size(); ++i)
        vkCmdCopyBuffer(cmd, staging.buffer, dsts[i], 1, &regions[i]);
      transfer_to_compute(cmd);
    });
  }
  destroy_buffer(ctx, staging);
  return total;
}

// The chain of `mesh` from `cache` if it holds one for the same content, else built.
LodChain chain_of(const Mesh& mesh, const std::vector<LodChain>& cache) {
  for (const LodChain& c : cache) {
    const Mesh& base = *c.levels[c.base_level].mesh;
    if (base.triangle_count() == mesh.triangle_count() && base == mesh) return c;
  }
  return build_lod_chain(mesh);
}

// Builds (or reuses) the chains of the scene's meshes and uploads them, once per scene.
void prepare_lod(Renderer::State& s) {
  if (s.lod_uploaded) return;
  std::vector<LodChain> chains(s.meshes.size());
  std::vector<LodChain> cache;
  for (size_t m = 0; m < s.meshes.size(); ++m) {
    if (s.meshes[m].triangle_count() == 0) continue;
    chains[m] = chain_of(s.meshes[m], s.lod_chains);
    cache.push_back(chains[m]);
  }
  s.lod_chains = std::move(cache);
  GpuSceneArrays& a = s.uploaded;
  const size_t vertices = a.vertices.size(), indices = a.indices.size(), uv1s = a.uv1s.size();
  append_lod_chains(chains, a);
  try {
    check_scene_buffers(buffer_counts(a), s.ctx.properties.limits.maxStorageBufferRange,
                        "the scene with its level-of-detail chains");
  } catch (const SceneSizeError&) {
    // The arrays as set_scene left them, which the GPU holds: frames without level of detail
    // still render this scene.
    a.vertices.resize(vertices);
    a.indices.resize(indices);
    a.adjacency.resize(indices);
    a.uv1s.resize(uv1s);
    a.lod_levels.clear();
    a.lod_meshes.clear();
    throw;
  }
  std::vector<PendingCopy> copies;
  UploadStats stats;
  bool& dirty = s.descriptors_dirty;
  queue_tail_upload(s.ctx, s.buffer(TS_BINDING_VERTICES), a.vertices, vertices, copies, stats,
                    dirty);
  queue_tail_upload(s.ctx, s.buffer(TS_BINDING_INDICES), a.indices, indices, copies, stats, dirty);
  queue_tail_upload(s.ctx, s.buffer(TS_BINDING_ADJACENCY), a.adjacency, indices, copies, stats,
                    dirty);
  queue_tail_upload(s.ctx, s.buffer(TS_BINDING_UV1), a.uv1s, uv1s, copies, stats, dirty);
  queue_tail_upload(s.ctx, s.buffer(TS_BINDING_LOD_LEVELS), a.lod_levels, 0, copies, stats, dirty);
  queue_tail_upload(s.ctx, s.buffer(TS_BINDING_LOD_MESHES), a.lod_meshes, 0, copies, stats, dirty);
  submit_copies(s.ctx, copies, s.options.staging_chunk_bytes);
  s.lod_uploaded = true;
}

// Puts the meshes' own triangles back into the GPU's objects after frames with level of detail.
void restore_objects(Renderer::State& s) {
  if (!s.objects_hold_lod) return;
  const std::vector<gpu::GpuObject>& objects = s.uploaded.objects;
  if (!objects.empty()) {
    submit_copies(s.ctx,
                  {{s.buffer(TS_BINDING_OBJECTS).buffer, 0, objects.data(),
                    objects.size() * sizeof(gpu::GpuObject)}},
                  s.options.staging_chunk_bytes);
  }
  s.objects_hold_lod = false;
}

}  // namespace

void Renderer::set_camera(const Camera& camera) {
  State& s = *s_;
  if (!s.has_scene) throw Error("set_camera before set_scene");
  validate_camera(camera);
  s.camera = camera;
  s.nothing_to_clip.reset();  // predicted again for the new camera
}

UploadStats Renderer::set_scene(const Scene& scene) {
  validate_scene(scene);
  State& s = *s_;
  GpuSceneArrays next = flatten_scene(scene, &s.texture_cache);
  // Before any buffer is touched, so that a refused scene leaves the previous one in place.
  check_scene_buffers(buffer_counts(next), s.ctx.properties.limits.maxStorageBufferRange);
  check_texel_buffer(next.texels.size(), addressed_buffer_limits(s.ctx));
  UploadStats stats;
  stats.mip_chains_built = next.mip_chains_built;
  std::vector<PendingCopy> copies;
  const GpuSceneArrays& prev = s.uploaded;
  queue_array_upload(s.ctx, s.buffer(TS_BINDING_VERTICES), prev.vertices, next.vertices, copies,
                     stats, s.descriptors_dirty);
  queue_array_upload(s.ctx, s.buffer(TS_BINDING_INDICES), prev.indices, next.indices, copies, stats,
                     s.descriptors_dirty);
  queue_array_upload(s.ctx, s.buffer(TS_BINDING_ADJACENCY), prev.adjacency, next.adjacency, copies,
                     stats, s.descriptors_dirty);
  queue_objects_upload(s.ctx, s.buffer(TS_BINDING_OBJECTS), prev, next, copies, stats,
                       s.descriptors_dirty);
  queue_array_upload(s.ctx, s.buffer(TS_BINDING_MATERIALS), prev.materials, next.materials, copies,
                     stats, s.descriptors_dirty);
  queue_array_upload(s.ctx, s.buffer(TS_BINDING_LIGHTS), prev.lights, next.lights, copies, stats,
                     s.descriptors_dirty);
  // Read at its address, which each frame's GpuFrame carries: no descriptor to rewrite.
  bool texels_moved = false;
  queue_array_upload(s.ctx, s.texels, prev.texels, next.texels, copies, stats, texels_moved,
                     VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT);
  queue_array_upload(s.ctx, s.buffer(TS_BINDING_TEXTURES), prev.textures, next.textures, copies,
                     stats, s.descriptors_dirty);
  queue_array_upload(s.ctx, s.buffer(TS_BINDING_UV1), prev.uv1s, next.uv1s, copies, stats,
                     s.descriptors_dirty);
  // Empty until a frame asks for level of detail (prepare_lod), but bound in every frame.
  queue_array_upload(s.ctx, s.buffer(TS_BINDING_LOD_LEVELS), prev.lod_levels, next.lod_levels,
                     copies, stats, s.descriptors_dirty);
  queue_array_upload(s.ctx, s.buffer(TS_BINDING_LOD_MESHES), prev.lod_meshes, next.lod_meshes,
                     copies, stats, s.descriptors_dirty);
  if (scene.environment != s.env.source) {
    set_environment(s.ctx, s.env, scene.environment, s.options.environment);
    s.descriptors_dirty = true;
    stats.environment_changed = true;
  }

  stats.bytes = submit_copies(s.ctx, copies, s.options.staging_chunk_bytes);
  if (next.triangle_count != s.uploaded.triangle_count) {
    // Size the batches and raster buffer for this scene (buffers only grow, never shrink).
    s.batch_triangles = 0;
    s.raster_capacity = 0;
    s.lod_triangles = 0;           // another scene's levels would size this one's batches
    s.tile_lists_counted = false;  // another scene's lists may fit the direct layout
  }
  s.uploaded = std::move(next);
  s.meshes = scene.meshes;
  s.mesh_boxes.clear();
  for (const Mesh& mesh : s.meshes) s.mesh_boxes.push_back(mesh_box(mesh));
  s.nothing_to_clip.reset();  // predicted again for the new objects and camera
  s.lod_uploaded = false;
  s.camera = scene.camera;
  s.background = scene.background;
  s.ambient = scene.ambient;
  s.has_scene = true;
  return stats;
}

void check_image_size(const Context& ctx, uint32_t width, uint32_t height, uint32_t samples,
                      uint32_t tile_size) {
  const VkPhysicalDeviceLimits& l = ctx.properties.limits;
  if (width == 0 || height == 0) throw ImageSizeError(width, height, "is empty");
  const uint32_t max_side = std::min<uint32_t>(TS_MAX_IMAGE_SIDE, l.maxImageDimension2D);
  if (width > max_side || height > max_side) {
    throw ImageSizeError(width, height,
                         "is over the largest side of " + std::to_string(max_side) + " px");
  }
  if (div_up(std::max(width, height), tile_size) > TS_MAX_TILES_PER_SIDE) {
    throw ImageSizeError(width, height,
                         "is over the largest side of " +
                             std::to_string(TS_MAX_TILES_PER_SIDE * tile_size) +
                             " px that tiles of " + std::to_string(tile_size) + " px hold");
  }
  // The visibility buffer is the largest per-pixel buffer: one 64-bit key per sample.
  const uint64_t key_bytes = uint64_t(samples) * sizeof(uint64_t);
  const uint64_t vis_bytes = uint64_t(width) * height * key_bytes;
  if (vis_bytes > l.maxStorageBufferRange) {
    // The largest square within it, as an example of a size that fits.
    const uint64_t max_pixels = l.maxStorageBufferRange / key_bytes;
    uint64_t side = uint64_t(std::sqrt(double(max_pixels)));
    while (side * side > max_pixels) --side;
    while ((side + 1) * (side + 1) <= max_pixels) ++side;
    side = std::min<uint64_t>(side, max_side);
    const std::string at_samples = std::to_string(samples) + (samples > 1 ? " samples" : " sample");
    throw ImageSizeError(
        width, height,
        (samples > 1 ? "at " + at_samples + " " : std::string()) + "needs a " +
            std::to_string((vis_bytes + (1u << 20) - 1) >> 20) +
            " MiB visibility buffer, more than this device's maxStorageBufferRange (" +
            std::to_string(uint64_t(l.maxStorageBufferRange) >> 20) + " MiB): it takes at most " +
            std::to_string(max_pixels) + " pixels at " + at_samples + ", e.g. " +
            std::to_string(side) + "x" + std::to_string(side));
  }
}

Buffer create_binding_buffer(const Context& ctx, const BindingInfo& b, uint64_t bytes) {
  return create_buffer(ctx, bytes, kStorageUsage | b.extra_usage,
                       b.host_mapped ? MemoryKind::device_mapped : MemoryKind::device);
}

uint64_t binding_size(const Renderer::State& s, const BindingInfo& b) {
  uint64_t count = 1;
  switch (b.scale) {
    case Scale::fixed:
      break;
    case Scale::pixels:
      count = uint64_t(s.width) * s.height;
      break;
    case Scale::samples:
      count = uint64_t(s.width) * s.height * s.samples;
      break;
    case Scale::pixels_if_coverage:
      if (!s.options.debug_coverage) return 4;
      count = uint64_t(s.width) * s.height;
      break;
    case Scale::tiles:
      count = uint64_t(s.tiles_x) * s.tiles_y;
      break;
    case Scale::raster_capacity:
      count = s.raster_capacity;
      break;
    case Scale::objects:
      count = s.uploaded.objects.size();
      break;
    case Scale::lod_groups:
      count = div_up(s.uploaded.objects.size(), TS_LOD_GROUP_SIZE);
      break;
    case Scale::objects_if_lod_draws:
      if (!s.lod_draws) return 4;
      count = s.uploaded.objects.size();
      break;
    case Scale::tile_entry_capacity:
      count = s.tile_entry_capacity;
      break;
    case Scale::batches:
      count = s.counter_slots;
      break;
    case Scale::pixels_if_outlines:
      if (!s.outlines) return 4;
      count = uint64_t(s.width) * s.height;
      break;
  }
  return std::max<uint64_t>((count + b.extra) * b.bytes, 4);  // Vulkan forbids size 0
}

namespace {

bool sized_by_frame(Scale scale) {
  return scale == Scale::pixels || scale == Scale::samples || scale == Scale::pixels_if_coverage ||
         scale == Scale::tiles;
}

// Whether a sized buffer holds anything this frame (the coverage buffer only when counted).
bool in_use(const Renderer::State& s, const BindingInfo& b) {
  if (b.binding == TS_BINDING_TILE_DRAWN) return s.shade_tiles;
  return b.scale != Scale::pixels_if_coverage || s.options.debug_coverage;
}

// Fills the sized buffers cleared `when` (kBindings) with their clear value. A buffer the host
// has mapped (the counters, where the device has host-visible device-local memory) is filled by
// the host as the frame is recorded: every earlier submission that used it has completed
// (render() waits for its frame), and the submission makes the host's writes visible. Returns
// whether it recorded a fill, which the first pass must then wait for.
bool clear_buffers(Renderer::State& s, VkCommandBuffer cmd, Clear when) {
  bool recorded = false;
  for (const BindingInfo& b : kBindings) {
    // The last frame's shading may have emptied the visibility buffer already.
    const bool emptied = b.binding == TS_BINDING_VISIBILITY && s.visibility_clean;
    if (b.clear == when && in_use(s, b) && !emptied) {
      const Buffer& buffer = s.buffer(b.binding);
      if (buffer.mapped != nullptr) {
        std::fill_n(static_cast<uint32_t*>(buffer.mapped), buffer.size / 4, b.clear_value);
      } else {
        vkCmdFillBuffer(cmd, buffer.buffer, 0, VK_WHOLE_SIZE, b.clear_value);
        recorded = true;
      }
    }
  }
  return recorded;
}

}  // namespace

bool ensure_frame_resources(Renderer::State& s, const FrameSettings& settings) {
  Context& ctx = s.ctx;
  // The outline list is allocated by ensure_scratch_buffers from the first frame that needs it.
  s.outlines = s.outlines || lists_outlines(settings);
  check_image_size(ctx, settings.width, settings.height, settings.samples, s.options.tile_size);
  if (settings.width == s.width && settings.height == s.height && settings.samples == s.samples &&
      settings.hdr_format == s.hdr_format)
    return false;
  s.width = settings.width;
  s.height = settings.height;
  s.samples = settings.samples;
  s.visibility_clean = false;  // a new buffer, filled by the next frame's clear
  s.nothing_to_clip.reset();   // the guard band and the aspect changed
  s.hdr_format = settings.hdr_format;
  s.tiles_x = div_up(s.width, s.options.tile_size);
  s.tiles_y = div_up(s.height, s.options.tile_size);
  for (const BindingInfo& b : kBindings) {
    if (b.source != Source::sized || !sized_by_frame(b.scale)) continue;
    Buffer& buffer = s.buffer(b.binding);
    destroy_buffer(ctx, buffer);
    buffer = create_binding_buffer(ctx, b, binding_size(s, b));
    if (b.clear == Clear::on_creation) s.creation_clears_pending = true;
  }
  destroy_image(ctx, s.hdr);
  destroy_image(ctx, s.ldr);
  // A copy destination too: the hardware baseline copies its colour attachment into it. Sampled
  // by the resolve pass (TS_BINDING_HDR_TEXTURE).
  s.hdr = create_storage_image(ctx, s.width, s.height, hdr_vk_format(s.hdr_format),
                               VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_SAMPLED_BIT);
  s.ldr = create_storage_image(ctx, s.width, s.height, VK_FORMAT_R8G8B8A8_UNORM);
  s.images_generation++;
  s.descriptors_dirty = true;
  return true;
}

void init_capacities(Renderer::State& s) {
  const uint64_t total = s.uploaded.triangle_count;
  if (s.batch_triangles == 0) {
    s.batch_triangles = uint32_t(std::min<uint64_t>(std::max<uint64_t>(total, 1), s.max_batch()));
  }
  if (s.raster_capacity == 0) {
    s.raster_capacity = s.options.initial_raster_capacity
                            ? s.options.initial_raster_capacity
                            : std::min<uint32_t>(s.batch_triangles + 1024, s.max_raster_capacity());
  }
  if (s.tile_entry_capacity == 0) {
    s.tile_entry_capacity =
        s.options.initial_tile_entry_capacity
            ? s.options.initial_tile_entry_capacity
            : std::min<uint32_t>(std::max<uint32_t>(s.tiles_x * s.tiles_y * 4, 1u << 16),
                                 s.max_tile_entry_capacity());
  }
}

// Projection * view of the scene's camera for the current image size, as the frame constants
// hold it (in single precision).
glm::dmat4 clip_from_world(const Renderer::State& s) {
  const float aspect = float(s.width) / float(s.height);
  return glm::dmat4(projection_matrix(s.camera, aspect)) * glm::dmat4(view_matrix(s.camera));
}

// GpuFrame::camera_rays: from clip_from_world's inverse with the view's translation left out
// (the same rotation and projection, so that the rays go through the points rasterized), the
// far plane's point relative to the eye, which is linear in NDC x and y: its two slopes and
// its value at the centre, worked out in double.
glm::dmat4 camera_rays(const Renderer::State& s) {
  const float aspect = float(s.width) / float(s.height);
  glm::dmat4 view(view_matrix(s.camera));
  view[3] = glm::dvec4(0.0, 0.0, 0.0, 1.0);
  const glm::dmat4 eye_from_clip =
      glm::inverse(glm::dmat4(projection_matrix(s.camera, aspect)) * view);
  // On the far plane (NDC z = 1) w is the same for every x and y.
  const glm::dvec4 centre = eye_from_clip * glm::dvec4(0.0, 0.0, 1.0, 1.0);
  return glm::dmat4(eye_from_clip[0] / centre.w, eye_from_clip[1] / centre.w, centre / centre.w,
                    glm::dvec4(0.0));
}

// NDC range whose pixel coordinates stay within +-TS_GUARD_BAND_PX.
glm::vec2 guard_band(const Renderer::State& s) {
  return glm::vec2(float(2.0 * TS_GUARD_BAND_PX / s.width - 1.0),
                   float(2.0 * TS_GUARD_BAND_PX / s.height - 1.0));
}

// Whether frames without level of detail (whose objects may have other meshes) can leave the
// clip pass out: no object's mesh box reaches behind the near plane or out of the guard band
// (core/clip_prediction.h). Past kClipPredictionObjects the test would cost the CPU more than
// the pass costs the GPU: then the pass is recorded (and finds nothing if there is nothing).
constexpr size_t kClipPredictionObjects = 16384;
bool predicts_nothing_to_clip(const Renderer::State& s) {
  if (s.uploaded.objects.size() > kClipPredictionObjects) return false;
  const glm::dmat4 clip = glm::dmat4(glm::mat4(clip_from_world(s)));
  const glm::dvec2 band(guard_band(s));
  for (const gpu::GpuObject& o : s.uploaded.objects) {
    if (o.mesh >= s.mesh_boxes.size() ||
        may_need_clipping(s.mesh_boxes[o.mesh], clip, glm::dmat4(o.model), s.camera.near_plane,
                          band))
      return false;
  }
  return true;
}

// Chooses the tile lists' layout for the next attempt (RendererOptions::tile_lists) and makes
// room for direct lists of the current stride.
void prepare_tile_lists(Renderer::State& s) {
  if (s.options.tile_lists == TileLists::counted || s.tile_lists_counted) {
    s.tile_list_stride = 0;
    return;
  }
  const uint64_t tiles = uint64_t(s.tiles_x) * s.tiles_y;
  // Start with the room the entry buffer has (at least 4 a tile: init_capacities).
  if (s.tile_list_stride == 0)
    s.tile_list_stride = uint32_t(std::max<uint64_t>(4, s.tile_entry_capacity / tiles));
  const uint64_t needed = tiles * s.tile_list_stride;
  if (needed > s.max_tile_entry_capacity()) {
    s.tile_lists_counted = true;  // direct lists this long cannot be held
    s.tile_list_stride = 0;
    return;
  }
  s.tile_entry_capacity = uint32_t(std::max<uint64_t>(s.tile_entry_capacity, needed));
}

// After a frame with direct tile lists whose longest list had `longest` entries of the `entries`
// binned: grows the stride to hold it, or under TileLists::automatic turns to counted lists
// when direct ones would take more than twice the memory (and 4 MiB). Returns whether the
// frame must be redone.
bool fit_tile_lists(Renderer::State& s, uint64_t longest, uint64_t entries) {
  if (longest <= s.tile_list_stride) return false;
  const uint64_t tiles = uint64_t(s.tiles_x) * s.tiles_y;
  const uint64_t stride = longest + longest / 4;
  const bool too_large = tiles * stride > s.max_tile_entry_capacity() ||
                         (s.options.tile_lists == TileLists::automatic &&
                          tiles * stride > std::max<uint64_t>(2 * entries, 1u << 20));
  if (too_large) {
    s.tile_lists_counted = true;
    s.tile_list_stride = 0;
    if (entries > s.tile_entry_capacity) {
      s.tile_entry_capacity =
          uint32_t(std::min<uint64_t>(entries + entries / 4, s.max_tile_entry_capacity()));
    }
  } else {
    s.tile_list_stride = uint32_t(stride);
  }
  return true;
}

void ensure_scratch_buffers(Renderer::State& s, uint32_t batches) {
  Context& ctx = s.ctx;
  s.counter_slots = std::max({s.counter_slots, batches, 1u});
  for (const BindingInfo& b : kBindings) {
    if (b.source != Source::sized || b.scale == Scale::fixed || sized_by_frame(b.scale)) continue;
    Buffer& buffer = s.buffer(b.binding);
    const uint64_t bytes = binding_size(s, b);
    if (buffer.buffer && buffer.size >= bytes) continue;
    destroy_buffer(ctx, buffer);
    buffer = create_binding_buffer(ctx, b, bytes);
    if (b.clear == Clear::on_creation) s.creation_clears_pending = true;
    s.descriptors_dirty = true;
  }
  const Buffer& counters = s.buffer(TS_BINDING_COUNTERS);
  if (s.counters_readback.size != counters.size) {
    s.last_counts.valid = false;
    destroy_buffer(ctx, s.counters_readback);
    s.counters_readback =
        create_buffer(ctx, counters.size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryKind::readback);
  }
}

namespace {

bool compensates(const FrameSettings& settings) {
  return settings.energy_compensation && settings.brdf != Brdf::blinn_phong;
}

// TS_AA_COVERAGE_* of `settings`: a specialization constant, so that the count's pipelines
// carry no analytic code (a uniform branch around it made lavapipe's 4-sample shading 4x slower).
uint32_t aa_coverage_id(const FrameSettings& settings) {
  switch (settings.aa_coverage) {
    case AaCoverage::analytic:
      return TS_AA_COVERAGE_ANALYTIC;
    case AaCoverage::silhouette:
      return TS_AA_COVERAGE_SILHOUETTE;
    default:
      return TS_AA_COVERAGE_COUNT;
  }
}

// The shading variant of the current scene for `settings` (with RendererOptions::
// specialize_lights).
ShadeVariant shade_variant(const Renderer::State& s, const FrameSettings& settings) {
  return {uint32_t(settings.brdf), compensates(settings),   s.uploaded.light_counts,
          s.uploaded.texture_maps, s.env.source != nullptr, s.uploaded.uv1_maps,
          settings.samples,        aa_coverage_id(settings)};
}

}  // namespace

// The pipeline of the pass that rasterizes and shades small frames (Pass::raster_shade),
// specialized to the scene as the shading pass is (RendererOptions::raster_shade needs
// specialize_lights).
VkPipeline raster_shade_pipeline(Renderer::State& s, const FrameSettings& settings) {
  TESSERA_CHECK(s.options.specialize_lights && settings.samples == 1);
  ShadeVariant v = shade_variant(s, settings);
  v.tile_size = s.options.tile_size;
  v.rasterizes = true;
  v.depth_rejection = s.options.depth_rejection;
  auto [it, inserted] = s.shade_variants.try_emplace(v, VK_NULL_HANDLE);
  if (inserted) it->second = create_shade_pipeline(s.ctx, v);
  return it->second;
}

bool Renderer::builds_shading_pipeline(const FrameSettings& settings) const {
  const State& s = *s_;
  if (!s.options.specialize_lights) return false;
  // The variant shade_pipeline takes for the pass itself (the background's is one for all).
  ShadeVariant v = shade_variant(s, settings);
  v.shade_tiles = s.shade_tiles ? TS_SHADE_TILES_DRAWN : TS_SHADE_TILES_OFF;
  v.tile_size = s.options.tile_size;
  return !has_compute_pipeline(s.ctx, "shade", shade_specialization(v));
}

VkPipeline shade_pipeline(Renderer::State& s, const FrameSettings& settings, uint32_t tiles) {
  const bool compensate = compensates(settings);
  if (s.options.specialize_lights) {
    ShadeVariant v = shade_variant(s, settings);
    v.shade_tiles = tiles;
    v.tile_size = s.options.tile_size;
    auto [it, inserted] = s.shade_variants.try_emplace(v, VK_NULL_HANDLE);
    if (inserted && tiles == TS_SHADE_TILES_BACKGROUND) {
      // Only what the background reads: the same pipeline (the context's cache) for every
      // light configuration.
      it->second = create_compute_pipeline(s.ctx, "shade_background",
                                           {.ibl = v.ibl ? TS_IBL_ON : TS_IBL_OFF,
                                            .samples = v.samples,
                                            .tile_size = v.tile_size,
                                            .shade_tiles = tiles});
    } else if (inserted) {
      it->second = create_shade_pipeline(s.ctx, v);
    }
    return it->second;
  }
  Pipeline generic = Pipeline::shade_classic;
  switch (settings.brdf) {
    case Brdf::classic:
      generic = compensate ? Pipeline::shade_classic_compensated : Pipeline::shade_classic;
      break;
    case Brdf::filament:
      generic = compensate ? Pipeline::shade_filament_compensated : Pipeline::shade_filament;
      break;
    case Brdf::blinn_phong:
      generic = Pipeline::shade_blinn_phong;
      break;
  }
  // Specialized to the tile size: the shading pass resets each tile's depth bound.
  Specialization spec = kPipelines[size_t(generic)].spec;
  spec.tile_size = s.options.tile_size;
  if (settings.samples == 1) {
    VkPipeline& pipeline = s.pipelines.pipelines[size_t(generic)];  // null until first used
    if (!pipeline)
      pipeline = create_compute_pipeline(s.ctx, kPipelines[size_t(generic)].shader, spec);
    return pipeline;
  }
  spec.aa_coverage = aa_coverage_id(settings);
  return sampled_pipeline(s, kPassCount + size_t(generic), kPipelines[size_t(generic)].shader, spec,
                          settings.samples);
}

VkPipeline sampled_pipeline(Renderer::State& s, size_t index, const char* shader,
                            Specialization spec, uint32_t samples) {
  auto [it, inserted] = s.sampled_pipelines.try_emplace(
      std::make_tuple(index, samples, spec.debug_coverage == VK_TRUE, spec.lod == VK_TRUE,
                      spec.aa_coverage, spec.silhouette_steps),
      VK_NULL_HANDLE);
  if (inserted) {
    spec.samples = samples;
    it->second = create_compute_pipeline(s.ctx, shader, spec);
  }
  return it->second;
}

namespace {

void record_dfg(Renderer::State& s, VkCommandBuffer cmd) {
  for (Pipeline p : {Pipeline::dfg_classic, Pipeline::dfg_filament}) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, s.pipelines[p]);
    vkCmdDispatch(cmd, 1, TS_DFG_SIZE, 1);  // a workgroup per roughness row
  }
  memory_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                 VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT |
                     VK_PIPELINE_STAGE_TRANSFER_BIT,
                 VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT);
  s.dfg_ready = true;  // the frame it is recorded in always runs to completion or throws
}

}  // namespace

bool record_precomputation(Renderer::State& s, VkCommandBuffer cmd, const FrameSettings& settings) {
  // Image-based lighting needs the DFG tables too (the split-sum's specular albedo).
  const bool dfg = !s.dfg_ready && (settings.energy_compensation || s.env.source);
  const bool environment = s.env.precompute_pending;
  if (dfg) record_dfg(s, cmd);
  record_environment_precompute(cmd, s.env, s.pipelines);
  const bool background = s.background_computed != s.background_inputs;
  if (background) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, s.pipelines[Pipeline::background]);
    vkCmdDispatch(cmd, 1, 1, 1);
    // Read by the shading pass, which may be the next one; the hardware baseline's fragment
    // shader reads the DFG tables of the same buffer.
    memory_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                   VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                   VK_ACCESS_SHADER_READ_BIT);
    s.background_computed = s.background_inputs;  // the frame runs to completion or throws
  }
  return dfg || environment || background;
}

namespace {

// Throws Error for a frame that cannot be rendered: no scene yet, or settings out of range.
void check_frame(const Renderer::State& s, const FrameSettings& settings, const char* caller) {
  if (!s.has_scene) throw Error(std::string(caller) + " was called before set_scene()");
  if (!std::isfinite(settings.exposure_ev) || std::abs(settings.exposure_ev) > 64.0f) {
    throw Error("exposure " + std::to_string(settings.exposure_ev) + " EV is outside [-64, 64]");
  }
  validate_samples(settings.samples);
  if (settings.max_anisotropy < 1 || settings.max_anisotropy > 16) {
    throw Error("texture anisotropy " + std::to_string(settings.max_anisotropy) +
                " is outside 1..16");
  }
  if (settings.silhouette_steps == 1) {
    throw Error("a silhouette coverage walk of 1 step is not one: 0 (no limit) or 2 and more");
  }
  if (!std::isfinite(settings.lod_error_px) || settings.lod_error_px <= 0.0f) {
    throw Error("level-of-detail error bound " + std::to_string(settings.lod_error_px) +
                " px is not a positive number");
  }
}

// Whether this frame dispatches the passes after setup directly (State::direct_dispatch). An
// indirect dispatch must wait for the writes of the pass before it to reach the command
// processor, and its barrier makes every pass in between wait the same way: on the H200, direct
// dispatches sized by the last frame took 6 us off one sphere's 0.069 ms and 3.5 us off the
// default scene's 0.094 (docs/performance.md, "Issue 13, eleventh round"). The sizes are a guess
// (direct_groups): fill and raster_small loop over their lists however many workgroups run, so
// a guess too small costs time, never the image. Only with direct tile lists (counted ones run
// the count pass, dispatched by setup's count) and without the clip and level-of-detail passes
// (dispatched by setup's and lod_scan's counts), and once the last frame's counts are of the same
// batches and triangles (the scene's geometry or the batch size changed otherwise).
bool dispatches_directly(const Renderer::State& s, bool lod, uint32_t batches) {
  return s.tile_list_stride != 0 && s.skip_clip && !lod && s.last_counts.valid &&
         s.last_counts.batches == batches && s.last_counts.triangles == s.uploaded.triangle_count;
}

// Whether this frame rasterizes and shades in one pass (RendererOptions::raster_shade): a frame
// of one batch at one sample with nothing to clip, without level of detail, debug coverage or
// shading by tiles, after a frame of the same scene that set up at most kRasterShadeMaxTriangles
// raster triangles, of which at most kRasterShadeMaxTrianglesPerTile large ones per tile on
// average (GpuCounters::large_box_tiles). On the H200 each dependent pass of a small frame costs
// about 8 us of waiting for the one before, for a few microseconds of work (docs/performance.md,
// "Issue 13, thirteenth round"). The last frame's counts only choose the speed: a frame of more
// triangles is rendered the same, each tile testing them all.
bool rasterizes_and_shades_in_one_pass(const Renderer::State& s, const FrameSettings& settings,
                                       bool lod, uint32_t batches) {
  if (!s.raster_shade || lod || batches != 1 || settings.samples != 1 || !s.skip_clip ||
      s.shade_tiles || s.options.debug_coverage || !s.last_counts.valid ||
      s.last_counts.batches != batches || s.last_counts.triangles != s.uploaded.triangle_count)
    return false;
  const auto& last = *static_cast<const gpu::GpuCounters*>(s.counters_readback.mapped);
  return last.raster_tris <= kRasterShadeMaxTriangles &&
         last.large_box_tiles <= uint64_t(kRasterShadeMaxTrianglesPerTile) * s.tiles_x * s.tiles_y;
}

// Whether setup forms each triangle's view_proj * model itself and the frame records no
// object_clip pass. Up to kObjectClipInlineTriangles triangle instances that costs less than a
// pass of its own and the barrier after it: ~5 us on the H200, where 2^17 triangles' 64
// multiply-adds take ~0.3 us of its ALUs; ~0.2 ms at most on lavapipe (2 threads). Only setup has
// the variant: the clip pass and analytic coverage (several samples) read the pass's transforms,
// and level of detail keeps the pass (its frames already have three passes more).
bool forms_object_clip_in_setup(const Renderer::State& s, const FrameSettings& settings, bool lod) {
  constexpr uint64_t kObjectClipInlineTriangles = uint64_t(1) << 17;
  return !lod && s.skip_clip && settings.samples == 1 &&
         s.uploaded.triangle_count <= kObjectClipInlineTriangles;
}

}  // namespace

bool resolves_in_shading(const Renderer::State& s) {
  return s.options.resolve &&
         (s.hdr_format == HdrFormat::fp32 || s.hdr_half_rounding != TS_HDR_ROUNDING_AS_IS);
}

namespace {

// Finds how the device rounds shader stores to the RGBA16F HDR image (hdr_rounding.comp has
// the values and what each way stores), through texel (0, 0) of the current one, which the
// frame then overwrites. Precondition: the descriptors bind that image.
void probe_hdr_rounding(Renderer::State& s) {
  TESSERA_CHECK(s.hdr_format == HdrFormat::fp16);
  submit_and_wait(s.ctx, [&](VkCommandBuffer cmd) {
    full_barrier(cmd);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, s.pipelines.layout, 0, 1, &s.set,
                            0, nullptr);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, s.pipelines[Pipeline::hdr_rounding]);
    vkCmdDispatch(cmd, 1, 1, 1);
  });
  const std::vector<uint16_t> texels = download_image<uint16_t>(s.ctx, s.hdr, 4);
  constexpr std::array<uint16_t, 4> kNearestEven{0x3C01, 0xBC01, 0x3C02, 0x0011};
  constexpr std::array<uint16_t, 4> kTowardZero{0x3C00, 0xBC00, 0x3C01, 0x0010};
  const std::array<uint16_t, 4> stored{texels[0], texels[1], texels[2], texels[3]};
  s.hdr_half_rounding = stored == kNearestEven  ? TS_HDR_ROUNDING_HALF_NEAREST_EVEN
                        : stored == kTowardZero ? TS_HDR_ROUNDING_HALF_TOWARD_ZERO
                                                : TS_HDR_ROUNDING_AS_IS;
  s.hdr_rounding_probed = true;
}

// The GPU time of each pass of the attempt just submitted (`query_passes`: the pass that ends
// at each timestamp after the first) and of the whole attempt, into `stats`.
void read_pass_times(const Renderer::State& s, const std::vector<Pass>& query_passes,
                     FrameStats& stats) {
  const Context& ctx = s.ctx;
  std::vector<uint64_t> ticks(query_passes.size() + 1);
  VK_CHECK(vkGetQueryPoolResults(ctx.device, s.queries, 0, uint32_t(ticks.size()),
                                 ticks.size() * sizeof(uint64_t), ticks.data(), sizeof(uint64_t),
                                 VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
  const uint64_t mask =
      ctx.timestamp_valid_bits >= 64 ? ~0ull : (1ull << ctx.timestamp_valid_bits) - 1;
  const double ns_per_tick = ctx.properties.limits.timestampPeriod;
  for (size_t i = 0; i < query_passes.size(); ++i) {
    const uint64_t delta = ((ticks[i + 1] & mask) - (ticks[i] & mask)) & mask;
    if (query_passes[i] != Pass::count)
      stats.pass_ms[size_t(query_passes[i])] += double(delta) * ns_per_tick * 1e-6;
  }
  const uint64_t all = ((ticks.back() & mask) - (ticks.front() & mask)) & mask;
  stats.gpu_total_ms = double(all) * ns_per_tick * 1e-6;
  stats.has_timestamps = true;
}

}  // namespace

FrameStats Renderer::render(const FrameSettings& settings, Timing timing) {
  State& s = *s_;
  Context& ctx = s.ctx;
  check_frame(s, settings, "render()");
  ensure_frame_resources(s, settings);

  const uint64_t total = s.uploaded.triangle_count;
  init_capacities(s);
  // Level of detail: the GPU chooses the levels and sizes setup; the batches are sized by the
  // last such frame's total and the frame is redone if this one's is larger.
  const bool lod = settings.lod == Lod::automatic && total > 0;
  if (lod) {
    prepare_lod(s);
  } else {
    restore_objects(s);
  }

  // The prediction depends only on the scene and the image size: made once for both.
  if (!lod && !s.nothing_to_clip) s.nothing_to_clip = predicts_nothing_to_clip(s);
  s.skip_clip = !lod && *s.nothing_to_clip;

  FrameStats stats;
  stats.triangles_submitted = total;
  stats.triangles_without_lod = total;
  // The precomputation runs in a frame's first attempt only: a redone frame keeps its time.
  double earlier_precompute_ms = 0.0;
  auto keep_precompute_time = [&](bool timestamps, const std::vector<Pass>& query_passes) {
    if (!timestamps || std::find(query_passes.begin(), query_passes.end(), Pass::environment) ==
                           query_passes.end())
      return;
    FrameStats attempt;
    read_pass_times(s, query_passes, attempt);
    earlier_precompute_ms += attempt.pass_ms[size_t(Pass::environment)];
  };
  for (uint32_t attempt = 1;; ++attempt) {
    if (attempt > kMaxAttempts) {
      throw Error("the frame still overflowed its buffers after " + std::to_string(kMaxAttempts) +
                  " attempts (batch of " + std::to_string(s.batch_triangles) + " triangles)");
    }
    const uint64_t setup_triangles = lod ? std::max<uint64_t>(s.lod_triangles, 1) : total;
    const uint32_t batches = total == 0 ? 0 : div_up(setup_triangles, s.batch_triangles);
    s.frame_batches = batches;
    prepare_tile_lists(s);
    ensure_scratch_buffers(s, batches);
    s.object_clip_inline = forms_object_clip_in_setup(s, settings, lod);
    s.direct_dispatch = dispatches_directly(s, lod, batches);
    s.raster_shade_frame = rasterizes_and_shades_in_one_pass(s, settings, lod, batches);
    const bool timestamps = ctx.timestamp_valid_bits > 0;
    const uint32_t queries_needed = timestamps_needed(batches);
    if (timestamps && s.query_capacity < queries_needed) {
      if (s.queries) vkDestroyQueryPool(ctx.device, s.queries, nullptr);
      VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
      info.queryType = VK_QUERY_TYPE_TIMESTAMP;
      info.queryCount = timestamp_pool_size(ctx, queries_needed);
      VK_CHECK(vkCreateQueryPool(ctx.device, &info, nullptr, &s.queries));
      s.query_capacity = queries_needed;
    }
    if (s.descriptors_dirty) {
      update_descriptors();
      s.descriptors_dirty = false;
    }
    if (s.options.resolve && s.hdr_format == HdrFormat::fp16 && !s.hdr_rounding_probed)
      probe_hdr_rounding(s);
    write_frame_constants(settings);

    std::vector<Pass> query_passes;  // pass that ends at each timestamp after the first
    const auto start = std::chrono::steady_clock::now();
    submit_and_wait(ctx, [&](VkCommandBuffer cmd) {
      record_frame(cmd, batches, timestamps, timing, query_passes, settings);
      stats.cpu_record_submit_ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
              .count();
    });
    // Whatever the attempt drew, its shading visited (the rasterizers mark the tiles they
    // write for shading by tiles), so a reset left every key empty.
    s.visibility_clean = resets_visibility(settings);
    s.visibility_kept = !s.visibility_clean;

    // Read the counters: did any batch need more room than it had?
    const auto* counters = static_cast<const gpu::GpuCounters*>(s.counters_readback.mapped);
    s.last_counts = {true, batches, total};
    if (lod) {
      s.objects_hold_lod = true;
      if (counters[0].lod_total == 0xFFFFFFFFu) {
        throw Error(
            "the levels of detail chosen make 2^32 or more triangle instances, more than "
            "Tessera can number: raise --lod-error");
      }
      stats.triangles_submitted = counters[0].lod_total;
      if (counters[0].lod_total > uint64_t(batches) * s.batch_triangles) {
        s.lod_triangles = counters[0].lod_total;
        // The batch size came from the scene's own meshes, which the levels may outnumber many
        // times over (one large sphere: 960 triangles, its level 16,128). Every batch costs a
        // full sequence of dependent passes, so grow the batch instead of adding batches; the
        // raster buffer then grows on demand below, or the batch halves again at its limit.
        s.batch_triangles = uint32_t(std::min<uint64_t>(
            std::max<uint64_t>(s.lod_triangles, s.batch_triangles), s.max_batch()));
        keep_precompute_time(timestamps, query_passes);
        continue;  // more batches
      }
      s.lod_triangles = counters[0].lod_total;
    }
    uint64_t need_raster = 0, need_entries = 0, longest_list = 0;
    bool need_clip = false;
    for (uint32_t b = 0; b < batches; ++b) {
      need_clip = need_clip || counters[b].clip_list > 0;
      need_raster = std::max<uint64_t>({need_raster, counters[b].raster_tris, counters[b].clip_list,
                                        counters[b].small_counts.x});
      need_entries = std::max<uint64_t>(need_entries, counters[b].tile_entries);
      longest_list = std::max<uint64_t>(longest_list, counters[b].tile_list_max);
    }
    bool redo = false;
    if (s.skip_clip && need_clip) {
      // The prediction missed a triangle: record the pass after all, in later frames too.
      s.skip_clip = false;
      s.nothing_to_clip = false;
      redo = true;
    }
    if (s.tile_list_stride != 0) {
      // Direct lists hold every entry unless one overflowed its stride.
      if (fit_tile_lists(s, longest_list, need_entries)) redo = true;
      need_entries = 0;
    }
    if (need_raster > s.raster_capacity) {
      redo = true;
      if (s.raster_capacity < s.max_raster_capacity()) {
        s.raster_capacity =
            uint32_t(std::min<uint64_t>(need_raster + need_raster / 4, s.max_raster_capacity()));
      } else {
        s.batch_triangles = std::max(1u, s.batch_triangles / 2);
      }
    }
    if (need_entries > s.tile_entry_capacity) {
      redo = true;
      if (s.tile_entry_capacity < s.max_tile_entry_capacity()) {
        s.tile_entry_capacity = uint32_t(
            std::min<uint64_t>(need_entries + need_entries / 4, s.max_tile_entry_capacity()));
      } else {
        s.batch_triangles = std::max(1u, s.batch_triangles / 2);
      }
    }
    if (redo) {
      keep_precompute_time(timestamps, query_passes);
      continue;
    }

    stats.attempts = attempt;
    stats.batches = batches;
    stats.dispatched_directly = s.direct_dispatch;
    stats.rasterized_and_shaded = s.raster_shade_frame;
    stats.tile_list_stride = s.tile_list_stride;
    for (uint32_t b = 0; b < batches; ++b) {
      const gpu::GpuCounters& c = counters[b];
      stats.raster_triangles += c.raster_tris;
      stats.small_triangles += c.small_counts.y;
      stats.big_triangles += c.big_tris;
      stats.tile_entries += c.tile_entries;
      stats.large_box_tiles += c.large_box_tiles;
      stats.culled_backface += c.culled_backface;
      stats.culled_frustum += c.culled_frustum;
      stats.culled_empty += c.culled_empty;
      stats.culled_nonfinite += c.culled_nonfinite;
      stats.clipped += c.clipped;
      stats.rejected_entries += c.rejected_entries;
      stats.rejected_small += c.rejected_small;
    }
    if (s.shade_tiles) {
      stats.shaded_tiles = counters[0].drawn_tiles;
      stats.background_tiles = counters[0].background_tiles;
    }
    if (timestamps) {
      read_pass_times(s, query_passes, stats);
      stats.precompute_ms = earlier_precompute_ms + stats.pass_ms[size_t(Pass::environment)];
    }
    return stats;
  }
}

void Renderer::update_descriptors() {
  State& s = *s_;
  // Reserved up front: the writes point into these.
  std::vector<VkDescriptorBufferInfo> buffer_infos;
  std::vector<VkDescriptorImageInfo> image_infos;
  buffer_infos.reserve(TS_BINDING_COUNT);
  image_infos.reserve(TS_BINDING_COUNT);
  std::vector<VkWriteDescriptorSet> writes;
  for (const BindingInfo& b : kBindings) {
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstSet = s.set;
    w.dstBinding = b.binding;
    w.descriptorCount = 1;
    w.descriptorType = b.type;
    if (b.type == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE ||
        b.type == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER) {
      VkDescriptorImageInfo image{VK_NULL_HANDLE, VK_NULL_HANDLE, VK_IMAGE_LAYOUT_GENERAL};
      if (b.binding == TS_BINDING_HDR_IMAGE) image.imageView = s.hdr.view;
      // texelFetch ignores a sampler's filtering and addressing: any sampler serves.
      if (b.binding == TS_BINDING_HDR_TEXTURE)
        image = {s.env.cube_sampler, s.hdr.view, image.imageLayout};
      if (b.binding == TS_BINDING_LDR_IMAGE) image.imageView = s.ldr.view;
      if (b.binding == TS_BINDING_ENV_MAP) {
        image = {s.env.map_sampler, s.env.map.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
      }
      if (b.binding == TS_BINDING_ENV_SPECULAR) {
        image = {s.env.cube_sampler, s.env.specular.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
      }
      TESSERA_CHECK(image.imageView != VK_NULL_HANDLE);
      image_infos.push_back(image);
      w.pImageInfo = &image_infos.back();
    } else {
      const Buffer* buffer = &s.buffer(b.binding);
      if (b.source == Source::frame_constants) buffer = &s.frame_constants;
      if (b.binding == TS_BINDING_ENV_LEVELS) buffer = &s.env.level_texels;
      if (b.binding == TS_BINDING_ENV_IRRADIANCE) buffer = &s.env.irradiance;
      TESSERA_CHECK(buffer->buffer != VK_NULL_HANDLE);
      buffer_infos.push_back({buffer->buffer, 0, VK_WHOLE_SIZE});
      w.pBufferInfo = &buffer_infos.back();
    }
    writes.push_back(w);
  }
  vkUpdateDescriptorSets(s.ctx.device, uint32_t(writes.size()), writes.data(), 0, nullptr);
  ++s.descriptors_generation;
}

void Renderer::write_frame_constants(const FrameSettings& settings) {
  State& s = *s_;
  const Camera& camera = s.camera;
  const glm::dmat4 view_proj = clip_from_world(s);
  const uint32_t hdr_rounding =
      settings.hdr_format == HdrFormat::fp16 ? s.hdr_half_rounding : TS_HDR_ROUNDING_AS_IS;
  const gpu::GpuFrame f{
      .view_proj = glm::mat4(view_proj),
      .camera_rays = glm::mat4(camera_rays(s)),
      .camera_position = camera.position,
      .near_plane = camera.near_plane,
      .background = s.background,
      .exposure_scale = std::exp2(settings.exposure_ev),
      .ambient = s.ambient,
      .view = view_id(settings.view),
      .guard_band = guard_band(s),
      .tonemap = tonemap_id(settings.tonemap),
      .cull = s.options.cull == CullMode::back    ? TS_CULL_BACK
              : s.options.cull == CullMode::front ? TS_CULL_FRONT
                                                  : TS_CULL_NONE,
      .image_size = glm::uvec2(s.width, s.height),
      .tiles = glm::uvec2(s.tiles_x, s.tiles_y),
      .object_count = uint32_t(s.uploaded.objects.size()),
      .light_count = uint32_t(s.uploaded.lights.size()),
      .triangle_count = uint32_t(s.uploaded.triangle_count),
      .raster_capacity = s.raster_capacity,
      .tile_entry_capacity = s.tile_entry_capacity,
      .small_triangle_max_area = s.options.small_triangle_max_area,
      .small_triangle_walk_area = s.options.small_triangle_walk_area,
      .environment = s.env.source ? 1u : 0u,
      .env_levels = specular_levels(s.env),
      .anisotropy = settings.max_anisotropy,
      .lod_scale =
          float(lod_pixels_per_unit(camera, s.width, s.height) / double(settings.lod_error_px)),
      .batch_count = s.frame_batches,
      .batch_triangles = s.batch_triangles,
      .hdr_max = float(hdr_max(settings.hdr_format)),
      .hdr_rounding = hdr_rounding,
      .resolve_in_shading = resolves_in_shading(s) ? 1u : 0u,
      .tile_list_stride = s.tile_list_stride,
      .reset_visibility = resets_visibility(settings) ? 1u : 0u,
      .texels_address = glm::uvec2(uint32_t(s.texels.address), uint32_t(s.texels.address >> 32))};
  s.background_inputs = {f.background, f.exposure_scale, f.view,
                         f.tonemap,    f.hdr_rounding,   f.hdr_max};
  // Pre-exposure (shaders/bindings.glsl): what the HDR image holds is radiance times this.
  s.hdr_pre_exposure = settings.view == View::shaded ? f.exposure_scale : 1.0f;
  std::memcpy(s.frame_constants.mapped, &f, sizeof(f));
}

namespace {

// Pass `pass`'s one-sample specialization for this renderer, as create_pipelines built it.
Specialization pass_variant_specialization(const Renderer::State& s, const PassInfo& pass) {
  return pass_specialization(pass, s.options.tile_size, s.options.depth_rejection, s.shade_tiles);
}

// `slot`, a variant's pipeline in s.pipelines (null until first used): built now if it is
// null, specialized to `spec`. Building it on first use spares the renderers that never run the
// variant its cost (on lavapipe about as much as the pass's own pipeline); the frame that first
// runs it pays it, as with the shading pipelines.
VkPipeline pass_variant_pipeline(Renderer::State& s, VkPipeline& slot, const PassInfo& pass,
                                 const Specialization& spec) {
  if (!slot) slot = create_compute_pipeline(s.ctx, pass.shader, spec);
  return slot;
}

// The pipeline `pass` binds this frame.
VkPipeline pass_pipeline(Renderer::State& s, const PassInfo& pass, const FrameSettings& settings) {
  if (settings.samples > 1 && pass.variants != Variants::shading) {
    // As create_pipelines specializes the single-sample ones (the table's row has the defaults).
    Specialization spec = pass.spec;
    spec.tile_size = s.options.tile_size;
    spec.depth_rejection = s.options.depth_rejection ? VK_TRUE : VK_FALSE;
    spec.shade_tiles = s.shade_tiles ? TS_SHADE_TILES_DRAWN : TS_SHADE_TILES_OFF;
    if (pass.variants == Variants::debug_coverage && s.options.debug_coverage)
      spec.debug_coverage = VK_TRUE;
    if (pass.variants == Variants::lod && settings.lod == Lod::automatic) spec.lod = VK_TRUE;
    if (pass.variants == Variants::silhouette) spec.silhouette_steps = settings.silhouette_steps;
    return sampled_pipeline(s, size_t(pass.pass), pass.shader, spec, settings.samples);
  }
  if (pass.pass == Pass::setup && s.object_clip_inline) {
    Specialization spec = pass_variant_specialization(s, pass);
    spec.object_clip_inline = VK_TRUE;
    if (!s.raster_shade_frame)
      return pass_variant_pipeline(s, s.pipelines.setup_object_clip_inline, pass, spec);
    spec.raster_only = VK_TRUE;
    return pass_variant_pipeline(s, s.pipelines.setup_raster_only, pass, spec);
  }
  switch (pass.variants) {
    case Variants::plain:
      break;
    case Variants::debug_coverage:
      if (s.options.debug_coverage) {
        Specialization spec = pass_variant_specialization(s, pass);
        spec.debug_coverage = VK_TRUE;
        return pass_variant_pipeline(s, s.pipelines.coverage[size_t(pass.pass)], pass, spec);
      }
      break;
    case Variants::shading:
      return shade_pipeline(s, settings, s.shade_tiles ? TS_SHADE_TILES_DRAWN : TS_SHADE_TILES_OFF);
    case Variants::raster_shade:
      return raster_shade_pipeline(s, settings);
    case Variants::lod:
      if (settings.lod == Lod::automatic) {
        Specialization spec = pass_variant_specialization(s, pass);
        spec.lod = VK_TRUE;
        return pass_variant_pipeline(s, s.pipelines.lod[size_t(pass.pass)], pass, spec);
      }
      break;
    case Variants::silhouette:
      TESSERA_CHECK(false);  // recorded only at several samples (above)
      break;
  }
  return s.pipelines[pass.pass];
}

// The workgroups of a direct dispatch of fill, raster_small or raster_tiles
// (State::direct_dispatch) for batch `b`: raster_tiles a workgroup per tile, as setup writes into
// tiles_dispatch; the others what the last frame's list needed, a quarter more and one more, so
// that a list that grows a little takes no second turn of their loops. At least one workgroup,
// which loops over this frame's list if the last one had none; at most what the indirect dispatch
// could launch.
glm::uvec3 direct_groups(const Renderer::State& s, Pass pass, uint32_t b) {
  if (pass == Pass::raster_tiles) return {s.tiles_x, s.tiles_y, 1};
  const auto& last = static_cast<const gpu::GpuCounters*>(s.counters_readback.mapped)[b];
  const bool fill = pass == Pass::fill;
  const uint64_t per_group = fill ? TS_BIN_ENTRIES_PER_GROUP : TS_GROUP_SIZE;
  const uint64_t entries =
      std::min<uint64_t>(fill ? last.big_tris : last.small_counts.x, s.raster_capacity);
  const uint64_t needed = div_up(entries, per_group);
  const uint64_t most = std::max<uint64_t>(div_up(uint64_t(s.raster_capacity), per_group), 1);
  return {uint32_t(std::min<uint64_t>(needed + needed / 4 + 1, most)), 1, 1};
}

// Binds and dispatches one pass of Stage::batch or Stage::frame (`batch`: the batch being
// recorded; batch 0's counters for a frame pass).
void record_dispatch(Renderer::State& s, VkCommandBuffer cmd, const PassInfo& pass,
                     const gpu::GpuBatch& batch, const FrameSettings& settings) {
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pass_pipeline(s, pass, settings));
  switch (pass.dispatch) {
    case Dispatch::none:
      TESSERA_CHECK(false);
      break;
    case Dispatch::fixed:
      vkCmdDispatch(cmd, pass.groups, 1, 1);
      break;
    case Dispatch::per_batch_triangle:
      if (pass.variants == Variants::lod && settings.lod == Lod::automatic) {
        vkCmdDispatchIndirect(
            cmd, s.buffer(TS_BINDING_COUNTERS).buffer,
            VkDeviceSize(batch.index) * sizeof(gpu::GpuCounters) + pass.counter_offset);
      } else {
        vkCmdDispatch(cmd, div_up(batch.triangle_count, pass.group_size), 1, 1);
      }
      break;
    case Dispatch::per_object:
      vkCmdDispatch(cmd, div_up(s.uploaded.objects.size(), pass.group_size), 1, 1);
      break;
    case Dispatch::per_pixel:
      if (pass.pass == Pass::shade && s.shade_tiles) {
        // Over the tiles list_tiles found drawn into, then the background over the others.
        // Each writes its own tiles' pixels alone, but Vulkan sees two writes of each image and
        // the shading pipeline may write the counters (silhouette coverage's list), which the
        // second dispatch reads its size from: a barrier between them (lavapipe runs
        // dispatches one after another anyway; GPUs keep shading by tiles off).
        const VkBuffer counters = s.buffer(TS_BINDING_COUNTERS).buffer;
        vkCmdDispatchIndirect(cmd, counters, offsetof(gpu::GpuCounters, shade_dispatch));
        compute_to_compute(cmd);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE,
                          shade_pipeline(s, settings, TS_SHADE_TILES_BACKGROUND));
        vkCmdDispatchIndirect(cmd, counters, offsetof(gpu::GpuCounters, background_dispatch));
        break;
      }
      vkCmdDispatch(cmd, div_up(s.width, pass.group_size), div_up(s.height, pass.group_size), 1);
      break;
    case Dispatch::per_tile:
      vkCmdDispatch(cmd, div_up(uint64_t(s.tiles_x) * s.tiles_y, pass.group_size), 1, 1);
      break;
    case Dispatch::tile_workgroups:
      vkCmdDispatch(cmd, s.tiles_x, s.tiles_y, 1);
      break;
    case Dispatch::indirect:
      if (s.direct_dispatch && (pass.pass == Pass::fill || pass.pass == Pass::raster_small ||
                                pass.pass == Pass::raster_tiles)) {
        const glm::uvec3 groups = direct_groups(s, pass.pass, batch.index);
        vkCmdDispatch(cmd, groups.x, groups.y, groups.z);
        break;
      }
      // A frame of direct dispatches records its batch passes' barriers without the
      // indirect-command read (barrier_after): any other batch pass read from the counters
      // there would race with the pass that writes them.
      TESSERA_CHECK(!s.direct_dispatch || pass.stage != Stage::batch);
      vkCmdDispatchIndirect(
          cmd, s.buffer(TS_BINDING_COUNTERS).buffer,
          VkDeviceSize(batch.index) * sizeof(gpu::GpuCounters) + pass.counter_offset);
      break;
  }
}

// Shading is the last pass render() records (or the outline pass after it, under silhouette
// coverage): its writes (the images, the counters) are read by the copies after the frame and
// read-backs, and, under RendererOptions::resolve off, by the resolve pass the caller records
// after it. Every other pass feeds the next compute pass.
// The two rasterizers run without a barrier between them (the frame's loop records none after
// the first), on GPUs the per-triangle one first (State::small_first), so the per-tile one's time
// is from the per-triangle one's end to both ends. Each only lowers what it writes (atomicMin
// into the visibility buffer and the tile bounds, a count into the coverage buffer), so whatever
// it reads of the other's writes is exact: a key or a bound read before the other lowered it is
// only higher, which rejects less and changes no sample's final key. The barrier that made
// raster_small wait for the bounds raster_tiles lowers cost more than they saved: on the H200 at
// 1920x1080 one sphere's frame took 6.5 us less without it, and scatter's 10^5 objects, where
// rejection matters most, 0.14 ms less. raster_small goes first: a frame of few small triangles is
// the length of their longest walk (up to 64 pixels, one thread each), which then runs beside
// raster_tiles' thousands of workgroups instead of after them (grid of 1 / 10 / 100 spheres 0.0717
// / 0.0985 / 0.1488 -> 0.0698 / 0.0929 / 0.1445 ms; scatter's 10^5 objects 10.26 -> 10.36 ms;
// docs/performance.md, ninth round). A CPU device runs one dispatch after the other, and there
// raster_tiles goes first so that raster_small rejects behind the bounds it lowered
// (depth_rejection_test).
static_assert(size_t(Pass::raster_tiles) == size_t(Pass::raster_small) + 1);
// `outlines_next`: the outline pass follows, which reads its dispatch from the counters and
// writes pixels again (the wider barrier cost the 1-sample frame's last pass 2 us on the H200).
void barrier_after(VkCommandBuffer cmd, const PassInfo& pass, bool outlines_next = false,
                   bool indirect_next = true) {
  // list_tiles writes the shading pass's indirect dispatches.
  if (pass.stage != Stage::frame || outlines_next || pass.pass == Pass::list_tiles) {
    if (pass.stage == Stage::batch && !indirect_next) {
      // No pass after it reads a dispatch from the counters (State::direct_dispatch).
      memory_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                     VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT,
                     VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                     VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
      return;
    }
    compute_to_compute(cmd);
    return;
  }
  memory_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                 VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                 VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT);
}

}  // namespace

void Renderer::record_frame(VkCommandBuffer cmd, uint32_t batches, bool timestamps, Timing timing,
                            std::vector<Pass>& query_passes, const FrameSettings& settings) {
  State& s = *s_;
  const Pipelines& p = s.pipelines;
  query_passes.clear();
  auto mark = [&](Pass pass) {
    if (!timestamps || (timing == Timing::frame && pass != Pass::count)) return;
    query_passes.push_back(pass);
    write_timestamp(s.ctx, cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, s.queries,
                    uint32_t(query_passes.size()), s.query_capacity);
  };

  full_barrier(cmd);  // earlier submissions (uploads, read-backs, the last frame) are done
  if (timestamps) {
    vkCmdResetQueryPool(cmd, s.queries, 0, timestamp_pool_size(s.ctx, s.query_capacity));
    write_timestamp(s.ctx, cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, s.queries, 0, s.query_capacity);
  }
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.layout, 0, 1, &s.set, 0, nullptr);

  const uint64_t total = s.uploaded.triangle_count;
  for (size_t i = 0; i < kPassCount;) {
    const PassInfo& pass = kPasses[i];
    switch (pass.stage) {
      case Stage::precompute:
        if (record_precomputation(s, cmd, settings)) mark(pass.pass);
        ++i;
        break;
      case Stage::clear: {
        bool filled = clear_buffers(s, cmd, Clear::per_frame);
        if (s.creation_clears_pending) {
          filled = clear_buffers(s, cmd, Clear::on_creation) || filled;
          s.creation_clears_pending = false;
        }
        // Most frames fill nothing: the host zeroes the counters, the shading pass empties the
        // visibility buffer and resets the tile bounds, list_tiles the drawn tiles' marks.
        if (filled) {
          transfer_to_compute(cmd);
          mark(pass.pass);
        }
        ++i;
        break;
      }
      case Stage::objects:
      case Stage::lod:
        // The lod passes are not recorded at all without level of detail, so such frames are
        // as before it.
        if (total > 0 && ((pass.stage == Stage::objects && !s.object_clip_inline) ||
                          (pass.stage == Stage::lod && settings.lod == Lod::automatic))) {
          const gpu::GpuBatch none{};  // lod.comp reads flags
          vkCmdPushConstants(cmd, p.layout, kShaderStages, 0, sizeof(none), &none);
          record_dispatch(s, cmd, pass, none, settings);
          barrier_after(cmd, pass);
          mark(pass.pass);
        }
        ++i;
        break;
      case Stage::batch: {
        size_t end = i;
        while (end < kPassCount && kPasses[end].stage == Stage::batch) ++end;
        for (uint32_t b = 0; b < batches; ++b) {
          const uint64_t first = uint64_t(b) * s.batch_triangles;
          // Under level of detail setup reads its count from the GPU (lod_scan) instead.
          gpu::GpuBatch batch{
              uint32_t(first),
              uint32_t(first < total ? std::min<uint64_t>(s.batch_triangles, total - first) : 0), b,
              0};
          vkCmdPushConstants(cmd, p.layout, kShaderStages, 0, sizeof(batch), &batch);
          for (size_t k = i; k < end; ++k) {
            size_t j = k;  // kPasses has the rasterizers in the order small_first records them
            if (!s.small_first && j == size_t(Pass::raster_small))
              j = size_t(Pass::raster_tiles);
            else if (!s.small_first && j == size_t(Pass::raster_tiles))
              j = size_t(Pass::raster_small);
            // Direct tile lists need no count and no packed ranges (fill.comp).
            const Pass pass = kPasses[j].pass;
            if (s.tile_list_stride != 0 && (pass == Pass::bin_count || pass == Pass::scan))
              continue;
            if (s.skip_clip && pass == Pass::clip) continue;
            // raster_shade takes every pass after setup (and clip, which it runs without).
            if (s.raster_shade_frame && pass != Pass::setup) continue;
            record_dispatch(s, cmd, kPasses[j], batch, settings);
            // None between the two rasterizers.
            if (k != size_t(Pass::raster_small))
              barrier_after(cmd, kPasses[j], false, !s.direct_dispatch);
            mark(kPasses[j].pass);
          }
        }
        i = end;
        break;
      }
      case Stage::frame:
        if ((pass.pass == Pass::outline && !lists_outlines(settings)) ||
            (pass.pass == Pass::list_tiles && !s.shade_tiles) ||
            (pass.pass == Pass::raster_shade && !s.raster_shade_frame) ||
            (pass.pass == Pass::shade && s.raster_shade_frame)) {
          ++i;
          break;
        }
        if (pass.pass == Pass::resolve && (!s.options.resolve || resolves_in_shading(s))) {
          // The shading pass resolved its own pixels (GpuFrame.resolve_in_shading), or the
          // caller records it (RendererOptions::resolve off).
          ++i;
          break;
        }
        record_dispatch(s, cmd, pass, gpu::GpuBatch{}, settings);
        barrier_after(cmd, pass, pass.pass == Pass::shade && lists_outlines(settings));
        mark(pass.pass);
        ++i;
        break;
    }
  }

  if (timing == Timing::frame) mark(Pass::count);  // the frame's end

  const Buffer& counters = s.buffer(TS_BINDING_COUNTERS);
  VkBufferCopy region{0, 0, counters.size};
  vkCmdCopyBuffer(cmd, counters.buffer, s.counters_readback.buffer, 1, &region);
  memory_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                 VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
}

ImageF Renderer::read_hdr() const {
  const State& s = *s_;
  TESSERA_CHECK(s.hdr.image != VK_NULL_HANDLE);
  ImageF out{s.width, s.height, std::vector<glm::vec4>(size_t(s.width) * s.height)};
  if (s.hdr_format == HdrFormat::fp32) {
    out.pixels = download_image<glm::vec4>(s.ctx, s.hdr, 1);
  } else {
    std::vector<uint16_t> halves = download_image<uint16_t>(s.ctx, s.hdr, 4);
    for (size_t i = 0; i < out.pixels.size(); ++i) {
      for (int c = 0; c < 4; ++c) out.pixels[i][c] = glm::unpackHalf1x16(halves[i * 4 + c]);
    }
  }
  // The image holds radiance times the pre-exposure: divided back out (alpha excepted), a
  // stored 65504 (fp16) reads as 65504 / 2^EV, the largest radiance the frame can carry.
  for (glm::vec4& p : out.pixels) p /= glm::vec4(glm::vec3(s.hdr_pre_exposure), 1.0f);
  return out;
}

Image8 Renderer::read_ldr() const {
  const State& s = *s_;
  TESSERA_CHECK(s.ldr.image != VK_NULL_HANDLE);
  std::vector<glm::u8vec4> texels = download_image<glm::u8vec4>(s.ctx, s.ldr, 1);
  return Image8{s.width, s.height, std::move(texels)};
}

namespace {

void require_kept_visibility(const Renderer::State& s) {
  if (!s.visibility_kept)
    throw Error(
        "the last frame did not keep its visibility buffer: render with "
        "FrameSettings::keep_visibility on to read it");
}

}  // namespace

std::vector<uint64_t> Renderer::read_visibility() const {
  const Buffer& visibility = s_->buffer(TS_BINDING_VISIBILITY);
  TESSERA_CHECK(visibility.buffer != VK_NULL_HANDLE);
  require_kept_visibility(*s_);
  return download_buffer<uint64_t>(s_->ctx, visibility,
                                   uint64_t(s_->width) * s_->height * s_->samples);
}

uint64_t Renderer::read_visibility_at(uint32_t x, uint32_t y) const {
  const Buffer& visibility = s_->buffer(TS_BINDING_VISIBILITY);
  TESSERA_CHECK(visibility.buffer != VK_NULL_HANDLE && x < s_->width && y < s_->height);
  require_kept_visibility(*s_);
  return download_buffer<uint64_t>(s_->ctx, visibility, 1,
                                   (uint64_t(y) * s_->width + x) * s_->samples)[0];
}

std::vector<uint32_t> Renderer::read_coverage() const {
  const Buffer& coverage = s_->buffer(TS_BINDING_COVERAGE);
  TESSERA_CHECK(s_->options.debug_coverage && coverage.buffer != VK_NULL_HANDLE);
  return download_buffer<uint32_t>(s_->ctx, coverage, uint64_t(s_->width) * s_->height);
}

std::vector<glm::vec4> Renderer::read_dfg_table() const {
  if (!s_->dfg_ready)
    throw Error("the DFG table is computed by the first frame with energy compensation");
  return download_buffer<glm::vec4>(s_->ctx, s_->buffer(TS_BINDING_DFG),
                                    2 * (TS_DFG_SIZE + 1) * TS_DFG_SIZE);
}

const StorageImage& Renderer::output_image() const {
  return s_->ldr;
}

uint32_t Renderer::object_of_triangle(uint32_t triangle_id) const {
  return tessera::object_of_triangle(triangle_numbering(), triangle_id);
}

ObjectNumbering Renderer::triangle_numbering() const {
  const State& s = *s_;
  if (!s.objects_hold_lod) return s.uploaded.numbering;
  // The last frame's levels numbered the triangles: its first_triangle per object.
  const std::vector<gpu::GpuObject> objects = download_buffer<gpu::GpuObject>(
      s.ctx, s.buffer(TS_BINDING_OBJECTS), s.uploaded.objects.size());
  ObjectNumbering numbering = s.uploaded.numbering;
  numbering.triangle_count = 0;
  for (size_t i = 0; i < objects.size(); ++i) {
    numbering.first_triangle[i] = objects[i].first_triangle;
    numbering.triangle_count = uint64_t(objects[i].first_triangle) + objects[i].triangle_count;
  }
  return numbering;
}

RendererInternal::Frame RendererInternal::prepare_frame(Renderer& renderer,
                                                        const FrameSettings& settings) {
  Renderer::State& s = *renderer.s_;
  check_frame(s, settings, "a frame outside render()");
  ensure_frame_resources(s, settings);
  init_capacities(s);
  const bool lod = settings.lod == Lod::automatic && s.uploaded.triangle_count > 0;
  if (lod) {
    prepare_lod(s);
    s.lod_draws = true;
  } else {
    restore_objects(s);
  }
  s.frame_batches = 0;  // lod_scan sizes no setup
  ensure_scratch_buffers(s, 1);
  if (s.descriptors_dirty) {
    renderer.update_descriptors();
    s.descriptors_dirty = false;
  }
  renderer.write_frame_constants(settings);
  Frame f;
  f.set = s.set;
  f.layout = s.pipelines.layout;
  f.hdr_image = s.hdr.image;
  f.images_generation = s.images_generation;
  f.width = s.width;
  f.height = s.height;
  f.indices = s.buffer(TS_BINDING_INDICES).buffer;
  f.objects = s.uploaded.objects;
  // Pre-exposed and clamped like every value the shading pass writes (shade.comp).
  f.background = glm::min(s.background * s.hdr_pre_exposure, glm::vec3(hdr_max(s.hdr_format)));
  f.cull = s.options.cull;
  f.lod = lod;
  f.lod_draws = s.buffer(TS_BINDING_LOD_DRAWS).buffer;
  // What shade_pipeline specializes the shading pass to; the generic pipelines' constants
  // otherwise (kPipelines).
  f.shading =
      s.options.specialize_lights
          ? shade_specialization(shade_variant(s, settings))
          : Specialization{.brdf = uint32_t(settings.brdf),
                           .energy_compensation = compensates(settings) ? VK_TRUE : VK_FALSE};
  return f;
}

void RendererInternal::record_lod(Renderer& renderer, VkCommandBuffer cmd) {
  Renderer::State& s = *renderer.s_;
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, s.pipelines.layout, 0, 1, &s.set, 0,
                          nullptr);
  const gpu::GpuBatch draws{0, 0, 0, TS_BATCH_LOD_DRAWS};
  vkCmdPushConstants(cmd, s.pipelines.layout, kShaderStages, 0, sizeof(draws), &draws);
  FrameSettings lod;
  lod.lod = Lod::automatic;
  for (const PassInfo& pass : kPasses) {
    if (pass.stage != Stage::lod) continue;
    record_dispatch(s, cmd, pass, draws, lod);
    compute_to_compute(cmd);
  }
  // The draws and the objects feed the graphics pipeline's indirect reads and vertex shader.
  memory_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                 VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_VERTEX_SHADER_BIT |
                     VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                 VK_ACCESS_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_SHADER_READ_BIT);
  s.objects_hold_lod = true;
}

void RendererInternal::record_precomputation(Renderer& renderer, VkCommandBuffer cmd,
                                             const FrameSettings& settings) {
  tessera::record_precomputation(*renderer.s_, cmd, settings);
}

void RendererInternal::record_resolve(Renderer& renderer, VkCommandBuffer cmd) {
  Renderer::State& s = *renderer.s_;
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, s.pipelines.layout, 0, 1, &s.set, 0,
                          nullptr);
  record_dispatch(s, cmd, kPasses[size_t(Pass::resolve)], gpu::GpuBatch{}, FrameSettings{});
  memory_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                 VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
}

RendererInternal::SharedSet RendererInternal::shared_set(const Renderer& renderer) {
  const Renderer::State& s = *renderer.s_;
  return {s.set, s.pipelines.set_layout, s.descriptors_generation};
}

void RendererInternal::record_resolve_into(Renderer& renderer, VkCommandBuffer cmd,
                                           VkDescriptorSet set, bool bgra) {
  Renderer::State& s = *renderer.s_;
  TESSERA_CHECK(s.hdr.image != VK_NULL_HANDLE && set != VK_NULL_HANDLE);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, s.pipelines.layout, 0, 1, &set, 0,
                          nullptr);
  const PassInfo& pass = kPasses[size_t(Pass::resolve)];
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE,
                    bgra ? s.pipelines[Pipeline::resolve_bgra] : s.pipelines[Pass::resolve]);
  vkCmdDispatch(cmd, div_up(s.width, pass.group_size), div_up(s.height, pass.group_size), 1);
}

const Buffer& RendererInternal::buffer(const Renderer& renderer, uint32_t binding) {
  TESSERA_CHECK(binding < TS_BINDING_COUNT);
  return renderer.s_->buffer(binding);
}

Context& RendererInternal::context(const Renderer& renderer) {
  return renderer.s_->ctx;
}

}  // namespace tessera
