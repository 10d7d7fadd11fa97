#include "compute/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <string>

#include <glm/gtc/packing.hpp>

#include "compute/pipelines.h"
#include "compute/readback.h"
#include "compute/renderer_state.h"
#include "compute/scene_upload.h"
#include "compute/vk_check.h"
#include "core/check.h"
#include "shaders/shared/gpu_types.h"

namespace tessera {
namespace {

constexpr uint32_t kMaxAttempts = 64;

uint32_t div_up(uint64_t a, uint64_t b) {
  return uint32_t((a + b - 1) / b);
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

}  // namespace

const char* pass_name(Pass pass) {
  static const char* const kNames[] = {"environment",  "clear", "setup",  "clip",
                                       "count",        "scan",  "fill",   "raster_tiles",
                                       "raster_small", "shade", "resolve"};
  static_assert(std::size(kNames) == kPassCount);
  return kNames[size_t(pass)];
}

Renderer::Renderer(Context& ctx, const RendererOptions& options)
    : s_(std::make_unique<State>(ctx)) {
  s_->options = options;
  s_->pipelines = create_pipelines(ctx);

  VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
                                  {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, TS_BINDING_COUNT},
                                  {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 2},
                                  {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2}};
  VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pool_info.maxSets = 1;
  pool_info.poolSizeCount = uint32_t(std::size(sizes));
  pool_info.pPoolSizes = sizes;
  VK_CHECK(vkCreateDescriptorPool(ctx.device, &pool_info, nullptr, &s_->descriptor_pool));
  VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  alloc.descriptorPool = s_->descriptor_pool;
  alloc.descriptorSetCount = 1;
  alloc.pSetLayouts = &s_->pipelines.set_layout;
  VK_CHECK(vkAllocateDescriptorSets(ctx.device, &alloc, &s_->set));

  s_->dfg = create_buffer(ctx, 2 * (TS_DFG_SIZE + 1) * TS_DFG_SIZE * sizeof(glm::vec4),
                          kStorageUsage, MemoryKind::device);
  s_->frame_constants = create_buffer(ctx, sizeof(gpu::GpuFrame),
                                      VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, MemoryKind::upload);
  validate_environment_options(options.environment);
  create_environment_gpu(ctx, s_->env);
}

Renderer::~Renderer() {
  Context& ctx = s_->ctx;
  vkDeviceWaitIdle(ctx.device);
  for (Buffer* b :
       {&s_->vertices,     &s_->indices,           &s_->objects,         &s_->materials,
        &s_->lights,       &s_->visibility,        &s_->coverage,        &s_->tile_counts,
        &s_->tile_offsets, &s_->tile_cursors,      &s_->raster_tris,     &s_->small_list,
        &s_->big_list,     &s_->clip_list,         &s_->tile_entries,    &s_->dfg,
        &s_->counters,     &s_->counters_readback, &s_->frame_constants, &s_->texels,
        &s_->textures}) {
    destroy_buffer(ctx, *b);
  }
  destroy_hardware_baseline(*s_);
  destroy_environment_gpu(ctx, s_->env);
  for (auto& [variant, pipeline] : s_->shade_variants)
    vkDestroyPipeline(ctx.device, pipeline, nullptr);
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

// Makes `buffer` hold `next`, given that it holds `previous`: reallocates if it is too small,
// else queues a copy of the range of elements that differ (nothing if none does).
template <typename T>
void queue_array_upload(const Context& ctx, Buffer& buffer, const std::vector<T>& previous,
                        const std::vector<T>& next, std::vector<PendingCopy>& copies,
                        UploadStats& stats, bool& dirty) {
  const VkDeviceSize bytes = next.size() * sizeof(T);
  if (!buffer.buffer || buffer.size < bytes) {
    destroy_buffer(ctx, buffer);
    // Never empty (Vulkan forbids size 0); room to grow so small edits do not reallocate.
    buffer = create_buffer(ctx, std::max<VkDeviceSize>(bytes + bytes / 4, 256), kStorageUsage,
                           MemoryKind::device);
    stats.buffers_created++;
    dirty = true;
    if (bytes) copies.push_back({buffer.buffer, 0, next.data(), bytes});
    return;
  }
  size_t first = 0;
  size_t common = std::min(previous.size(), next.size());
  while (first < common && std::memcmp(&previous[first], &next[first], sizeof(T)) == 0) ++first;
  if (first == next.size()) return;
  size_t last = next.size();  // one past the last element that differs
  while (last > first && last <= common &&
         std::memcmp(&previous[last - 1], &next[last - 1], sizeof(T)) == 0) {
    --last;
  }
  copies.push_back({buffer.buffer, first * sizeof(T), &next[first], (last - first) * sizeof(T)});
}

}  // namespace

UploadStats Renderer::set_scene(const Scene& scene) {
  validate_scene(scene);
  GpuSceneArrays next = flatten_scene(scene);
  State& s = *s_;
  UploadStats stats;
  std::vector<PendingCopy> copies;
  const GpuSceneArrays& prev = s.uploaded;
  queue_array_upload(s.ctx, s.vertices, prev.vertices, next.vertices, copies, stats,
                     s.descriptors_dirty);
  queue_array_upload(s.ctx, s.indices, prev.indices, next.indices, copies, stats,
                     s.descriptors_dirty);
  queue_array_upload(s.ctx, s.objects, prev.objects, next.objects, copies, stats,
                     s.descriptors_dirty);
  queue_array_upload(s.ctx, s.materials, prev.materials, next.materials, copies, stats,
                     s.descriptors_dirty);
  queue_array_upload(s.ctx, s.lights, prev.lights, next.lights, copies, stats, s.descriptors_dirty);
  queue_array_upload(s.ctx, s.texels, prev.texels, next.texels, copies, stats, s.descriptors_dirty);
  queue_array_upload(s.ctx, s.textures, prev.textures, next.textures, copies, stats,
                     s.descriptors_dirty);
  if (scene.environment != s.env.source) {
    set_environment(s.ctx, s.env, scene.environment, s.options.environment);
    s.descriptors_dirty = true;
    stats.environment_changed = true;
  }

  VkDeviceSize total = 0;
  for (const PendingCopy& c : copies) total += c.size;
  if (total > 0) {
    Buffer staging =
        create_buffer(s.ctx, total, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryKind::upload);
    VkDeviceSize offset = 0;
    for (const PendingCopy& c : copies) {
      std::memcpy(static_cast<char*>(staging.mapped) + offset, c.data, c.size);
      offset += c.size;
    }
    submit_and_wait(s.ctx, [&](VkCommandBuffer cmd) {
      full_barrier(cmd);
      VkDeviceSize src = 0;
      for (const PendingCopy& c : copies) {
        VkBufferCopy region{src, c.dst_offset, c.size};
        vkCmdCopyBuffer(cmd, staging.buffer, c.dst, 1, &region);
        src += c.size;
      }
      transfer_to_compute(cmd);
    });
    destroy_buffer(s.ctx, staging);
  }
  stats.bytes = total;
  if (next.triangle_count != s.uploaded.triangle_count) {
    // Size the batches and raster buffer for this scene (buffers only grow, never shrink).
    s.batch_triangles = 0;
    s.raster_capacity = 0;
  }
  s.uploaded = std::move(next);
  s.camera = scene.camera;
  s.background = scene.background;
  s.ambient = scene.ambient;
  s.has_scene = true;
  return stats;
}

namespace {

void check_frame_size(const Context& ctx, uint32_t width, uint32_t height) {
  const VkPhysicalDeviceLimits& l = ctx.properties.limits;
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  if (width == 0 || height == 0) throw Error("image size " + size + " is empty");
  const uint32_t max_side = std::min<uint32_t>(TS_MAX_IMAGE_SIDE, l.maxImageDimension2D);
  if (width > max_side || height > max_side) {
    throw Error("image size " + size + " is over the largest side of " + std::to_string(max_side) +
                " px");
  }
  const uint64_t vis_bytes = uint64_t(width) * height * sizeof(uint64_t);
  if (vis_bytes > l.maxStorageBufferRange) {
    throw Error("image size " + size + " needs a " + std::to_string(vis_bytes >> 20) +
                " MiB visibility buffer, more than this device's maxStorageBufferRange (" +
                std::to_string(uint64_t(l.maxStorageBufferRange) >> 20) + " MiB)");
  }
}

}  // namespace

void ensure_frame_resources(Renderer::State& s, const FrameSettings& settings) {
  Context& ctx = s.ctx;
  check_frame_size(ctx, settings.width, settings.height);
  if (settings.width != s.width || settings.height != s.height) {
    for (Buffer* b :
         {&s.visibility, &s.coverage, &s.tile_counts, &s.tile_offsets, &s.tile_cursors}) {
      destroy_buffer(ctx, *b);
    }
    destroy_image(ctx, s.hdr);
    destroy_image(ctx, s.ldr);
    s.width = settings.width;
    s.height = settings.height;
    s.tiles_x = div_up(s.width, TS_TILE_SIZE);
    s.tiles_y = div_up(s.height, TS_TILE_SIZE);
    const uint64_t pixels = uint64_t(s.width) * s.height;
    const uint64_t tiles = uint64_t(s.tiles_x) * s.tiles_y;
    s.visibility = create_buffer(ctx, pixels * 8, kStorageUsage, MemoryKind::device);
    s.coverage = create_buffer(ctx, s.options.debug_coverage ? pixels * 4 : 4, kStorageUsage,
                               MemoryKind::device);
    s.tile_counts = create_buffer(ctx, tiles * 4, kStorageUsage, MemoryKind::device);
    s.tile_offsets = create_buffer(ctx, (tiles + 1) * 4, kStorageUsage, MemoryKind::device);
    s.tile_cursors = create_buffer(ctx, tiles * 4, kStorageUsage, MemoryKind::device);
    // A colour attachment too, for the graphics baseline.
    s.hdr = create_storage_image(ctx, s.width, s.height, VK_FORMAT_R16G16B16A16_SFLOAT,
                                 VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT);
    s.ldr = create_storage_image(ctx, s.width, s.height, VK_FORMAT_R8G8B8A8_UNORM);
    s.descriptors_dirty = true;
  }
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

void ensure_scratch_buffers(Renderer::State& s, uint32_t batches) {
  Context& ctx = s.ctx;
  if (!s.raster_tris.buffer ||
      s.raster_tris.size < uint64_t(s.raster_capacity) * sizeof(gpu::GpuRasterTri)) {
    for (Buffer* b : {&s.raster_tris, &s.small_list, &s.big_list, &s.clip_list})
      destroy_buffer(ctx, *b);
    s.raster_tris = create_buffer(ctx, uint64_t(s.raster_capacity) * sizeof(gpu::GpuRasterTri),
                                  kStorageUsage, MemoryKind::device);
    s.small_list =
        create_buffer(ctx, uint64_t(s.raster_capacity) * 4, kStorageUsage, MemoryKind::device);
    s.big_list = create_buffer(ctx, uint64_t(s.raster_capacity) * sizeof(glm::uvec2), kStorageUsage,
                               MemoryKind::device);  // (raster triangle, tile block) bin entries
    s.clip_list =
        create_buffer(ctx, uint64_t(s.raster_capacity) * 4, kStorageUsage, MemoryKind::device);
    s.descriptors_dirty = true;
  }
  if (!s.tile_entries.buffer || s.tile_entries.size < uint64_t(s.tile_entry_capacity) * 4) {
    destroy_buffer(ctx, s.tile_entries);
    s.tile_entries =
        create_buffer(ctx, uint64_t(s.tile_entry_capacity) * 4, kStorageUsage, MemoryKind::device);
    s.descriptors_dirty = true;
  }
  if (s.counter_slots < std::max(batches, 1u)) {
    destroy_buffer(ctx, s.counters);
    destroy_buffer(ctx, s.counters_readback);
    s.counter_slots = std::max(batches, 1u);
    const VkDeviceSize bytes = VkDeviceSize(s.counter_slots) * sizeof(gpu::GpuCounters);
    s.counters = create_buffer(ctx, bytes, kStorageUsage | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT,
                               MemoryKind::device);
    s.counters_readback =
        create_buffer(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryKind::readback);
    s.descriptors_dirty = true;
  }
}

VkPipeline shade_pipeline(Renderer::State& s, const FrameSettings& settings) {
  const bool compensate = settings.energy_compensation && settings.brdf != Brdf::blinn_phong;
  if (s.options.specialize_lights) {
    const ShadeVariant v{uint32_t(settings.brdf), compensate, s.uploaded.light_counts,
                         s.uploaded.texture_maps, s.env.source != nullptr};
    auto [it, inserted] = s.shade_variants.try_emplace(v, VK_NULL_HANDLE);
    if (inserted) it->second = create_shade_pipeline(s.ctx, s.pipelines, v);
    return it->second;
  }
  switch (settings.brdf) {
    case Brdf::classic:
      return s
          .pipelines[compensate ? Pipeline::shade_classic_compensated : Pipeline::shade_classic];
    case Brdf::filament:
      return s
          .pipelines[compensate ? Pipeline::shade_filament_compensated : Pipeline::shade_filament];
    case Brdf::blinn_phong:
      return s.pipelines[Pipeline::shade_blinn_phong];
  }
  return s.pipelines[Pipeline::shade_classic];
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
  return dfg || environment;
}

FrameStats Renderer::render(const FrameSettings& settings) {
  State& s = *s_;
  Context& ctx = s.ctx;
  if (!s.has_scene) throw Error("render() was called before set_scene()");
  if (!std::isfinite(settings.exposure_ev) || std::abs(settings.exposure_ev) > 64.0f) {
    throw Error("exposure " + std::to_string(settings.exposure_ev) + " EV is outside [-64, 64]");
  }
  if (settings.max_anisotropy < 1 || settings.max_anisotropy > 16) {
    throw Error("texture anisotropy " + std::to_string(settings.max_anisotropy) +
                " is outside 1..16");
  }

  ensure_frame_resources(s, settings);

  const uint64_t total = s.uploaded.triangle_count;
  init_capacities(s);

  FrameStats stats;
  stats.triangles_submitted = total;
  for (uint32_t attempt = 1;; ++attempt) {
    if (attempt > kMaxAttempts) {
      throw Error("the frame still overflowed its buffers after " + std::to_string(kMaxAttempts) +
                  " attempts (batch of " + std::to_string(s.batch_triangles) + " triangles)");
    }
    const uint32_t batches = total == 0 ? 0 : div_up(total, s.batch_triangles);
    ensure_scratch_buffers(s, batches);
    const bool timestamps = ctx.timestamp_valid_bits > 0;
    const uint32_t queries_needed = 3 + 7 * batches + 2;
    if (timestamps && s.query_capacity < queries_needed) {
      if (s.queries) vkDestroyQueryPool(ctx.device, s.queries, nullptr);
      VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
      info.queryType = VK_QUERY_TYPE_TIMESTAMP;
      info.queryCount = queries_needed;
      VK_CHECK(vkCreateQueryPool(ctx.device, &info, nullptr, &s.queries));
      s.query_capacity = queries_needed;
    }
    if (s.descriptors_dirty) {
      update_descriptors();
      s.descriptors_dirty = false;
    }
    write_frame_constants(settings);

    std::vector<Pass> query_passes;  // pass that ends at each timestamp after the first
    const auto start = std::chrono::steady_clock::now();
    submit_and_wait(ctx, [&](VkCommandBuffer cmd) {
      record_frame(cmd, batches, timestamps, query_passes, settings);
      stats.cpu_record_submit_ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
              .count();
    });

    // Read the counters: did any batch need more room than it had?
    const auto* counters = static_cast<const gpu::GpuCounters*>(s.counters_readback.mapped);
    uint64_t need_raster = 0, need_entries = 0;
    for (uint32_t b = 0; b < batches; ++b) {
      need_raster =
          std::max<uint64_t>({need_raster, counters[b].raster_tris, counters[b].clip_list});
      need_entries = std::max<uint64_t>(need_entries, counters[b].tile_entries);
    }
    bool redo = false;
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
    if (redo) continue;

    stats.attempts = attempt;
    stats.batches = batches;
    for (uint32_t b = 0; b < batches; ++b) {
      const gpu::GpuCounters& c = counters[b];
      stats.raster_triangles += c.raster_tris;
      stats.small_triangles += c.small_tris;
      stats.big_triangles += c.big_tris;
      stats.tile_entries += c.tile_entries;
      stats.culled_backface += c.culled_backface;
      stats.culled_frustum += c.culled_frustum;
      stats.culled_empty += c.culled_empty;
      stats.culled_nonfinite += c.culled_nonfinite;
      stats.clipped += c.clipped;
    }
    if (timestamps) {
      std::vector<uint64_t> ticks(query_passes.size() + 1);
      VK_CHECK(vkGetQueryPoolResults(
          ctx.device, s.queries, 0, uint32_t(ticks.size()), ticks.size() * sizeof(uint64_t),
          ticks.data(), sizeof(uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
      const uint64_t mask =
          ctx.timestamp_valid_bits >= 64 ? ~0ull : (1ull << ctx.timestamp_valid_bits) - 1;
      const double ns_per_tick = ctx.properties.limits.timestampPeriod;
      for (size_t i = 0; i < query_passes.size(); ++i) {
        const uint64_t delta = ((ticks[i + 1] & mask) - (ticks[i] & mask)) & mask;
        stats.pass_ms[size_t(query_passes[i])] += double(delta) * ns_per_tick * 1e-6;
      }
      const uint64_t all = ((ticks.back() & mask) - (ticks.front() & mask)) & mask;
      stats.gpu_total_ms = double(all) * ns_per_tick * 1e-6;
      stats.has_timestamps = true;
    }
    return stats;
  }
}

void Renderer::update_descriptors() {
  State& s = *s_;
  struct BufferBinding {
    uint32_t binding;
    const Buffer* buffer;
  };
  const BufferBinding buffers[] = {
      {TS_BINDING_FRAME, &s.frame_constants},
      {TS_BINDING_VERTICES, &s.vertices},
      {TS_BINDING_INDICES, &s.indices},
      {TS_BINDING_OBJECTS, &s.objects},
      {TS_BINDING_MATERIALS, &s.materials},
      {TS_BINDING_LIGHTS, &s.lights},
      {TS_BINDING_RASTER_TRIS, &s.raster_tris},
      {TS_BINDING_SMALL_LIST, &s.small_list},
      {TS_BINDING_BIG_LIST, &s.big_list},
      {TS_BINDING_TILE_COUNTS, &s.tile_counts},
      {TS_BINDING_TILE_OFFSETS, &s.tile_offsets},
      {TS_BINDING_TILE_CURSORS, &s.tile_cursors},
      {TS_BINDING_TILE_ENTRIES, &s.tile_entries},
      {TS_BINDING_COUNTERS, &s.counters},
      {TS_BINDING_VISIBILITY, &s.visibility},
      {TS_BINDING_COVERAGE, &s.coverage},
      {TS_BINDING_CLIP_LIST, &s.clip_list},
      {TS_BINDING_DFG, &s.dfg},
      {TS_BINDING_TEXELS, &s.texels},
      {TS_BINDING_TEXTURES, &s.textures},
      {TS_BINDING_ENV_LEVELS, &s.env.level_texels},
      {TS_BINDING_ENV_IRRADIANCE, &s.env.irradiance},
  };
  std::vector<VkDescriptorBufferInfo> buffer_infos;
  buffer_infos.reserve(std::size(buffers));
  std::vector<VkWriteDescriptorSet> writes;
  for (const BufferBinding& b : buffers) {
    TESSERA_CHECK(b.buffer->buffer != VK_NULL_HANDLE);
    buffer_infos.push_back({b.buffer->buffer, 0, VK_WHOLE_SIZE});
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstSet = s.set;
    w.dstBinding = b.binding;
    w.descriptorCount = 1;
    w.descriptorType = b.binding == TS_BINDING_FRAME ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER
                                                     : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    w.pBufferInfo = &buffer_infos.back();
    writes.push_back(w);
  }
  const VkDescriptorImageInfo images[] = {{VK_NULL_HANDLE, s.hdr.view, VK_IMAGE_LAYOUT_GENERAL},
                                          {VK_NULL_HANDLE, s.ldr.view, VK_IMAGE_LAYOUT_GENERAL}};
  for (uint32_t i = 0; i < 2; ++i) {
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstSet = s.set;
    w.dstBinding = i == 0 ? TS_BINDING_HDR_IMAGE : TS_BINDING_LDR_IMAGE;
    w.descriptorCount = 1;
    w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    w.pImageInfo = &images[i];
    writes.push_back(w);
  }
  const VkDescriptorImageInfo sampled[] = {
      {s.env.map_sampler, s.env.map.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
      {s.env.cube_sampler, s.env.specular.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}};
  for (uint32_t i = 0; i < 2; ++i) {
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstSet = s.set;
    w.dstBinding = i == 0 ? TS_BINDING_ENV_MAP : TS_BINDING_ENV_SPECULAR;
    w.descriptorCount = 1;
    w.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    w.pImageInfo = &sampled[i];
    writes.push_back(w);
  }
  vkUpdateDescriptorSets(s.ctx.device, uint32_t(writes.size()), writes.data(), 0, nullptr);
}

void Renderer::write_frame_constants(const FrameSettings& settings) {
  State& s = *s_;
  const Camera& camera = s.camera;
  const float aspect = float(s.width) / float(s.height);
  const glm::dmat4 view_proj =
      glm::dmat4(projection_matrix(camera, aspect)) * glm::dmat4(view_matrix(camera));
  gpu::GpuFrame f{};
  f.view_proj = glm::mat4(view_proj);
  f.inv_view_proj = glm::mat4(glm::inverse(view_proj));
  f.camera_position = glm::vec4(camera.position, camera.near_plane);
  f.background = glm::vec4(s.background, 1.0f);
  f.ambient = glm::vec4(s.ambient, 0.0f);
  // Guard band: NDC range whose pixel coordinates stay within +-TS_GUARD_BAND_PX.
  f.raster_params = glm::vec4(float(2.0 * TS_GUARD_BAND_PX / s.width - 1.0),
                              float(2.0 * TS_GUARD_BAND_PX / s.height - 1.0),
                              std::exp2(settings.exposure_ev), 0.0f);
  s.hdr_pre_exposure = settings.view == View::shaded ? f.raster_params.z : 1.0f;
  f.image_size = glm::uvec4(s.width, s.height, s.tiles_x, s.tiles_y);
  f.scene_counts =
      glm::uvec4(uint32_t(s.uploaded.objects.size()), uint32_t(s.uploaded.lights.size()),
                 uint32_t(s.uploaded.triangle_count), tonemap_id(settings.tonemap));
  f.limits = glm::uvec4(s.raster_capacity, s.tile_entry_capacity, s.options.small_triangle_max_area,
                        view_id(settings.view));
  f.flags = glm::uvec4(s.options.cull == CullMode::back    ? TS_CULL_BACK
                       : s.options.cull == CullMode::front ? TS_CULL_FRONT
                                                           : TS_CULL_NONE,
                       s.env.source ? 1u : 0u, specular_levels(s.env), settings.max_anisotropy);
  std::memcpy(s.frame_constants.mapped, &f, sizeof(f));
}

void Renderer::record_frame(VkCommandBuffer cmd, uint32_t batches, bool timestamps,
                            std::vector<Pass>& query_passes, const FrameSettings& settings) {
  State& s = *s_;
  const Pipelines& p = s.pipelines;
  query_passes.clear();
  auto mark = [&](Pass pass) {
    if (!timestamps) return;
    query_passes.push_back(pass);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, s.queries,
                        uint32_t(query_passes.size()));
  };
  auto bind = [&](Pipeline pipeline) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p[pipeline]);
  };

  full_barrier(cmd);  // earlier submissions (uploads, read-backs, the last frame) are done
  if (timestamps) {
    vkCmdResetQueryPool(cmd, s.queries, 0, s.query_capacity);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, s.queries, 0);
  }
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.layout, 0, 1, &s.set, 0, nullptr);
  if (record_precomputation(s, cmd, settings)) mark(Pass::environment);
  vkCmdFillBuffer(cmd, s.visibility.buffer, 0, VK_WHOLE_SIZE, 0xFFFFFFFFu);  // TS_VIS_EMPTY
  if (s.options.debug_coverage) vkCmdFillBuffer(cmd, s.coverage.buffer, 0, VK_WHOLE_SIZE, 0);
  vkCmdFillBuffer(cmd, s.counters.buffer, 0, VK_WHOLE_SIZE, 0);
  transfer_to_compute(cmd);
  mark(Pass::clear);

  const uint64_t total = s.uploaded.triangle_count;
  for (uint32_t b = 0; b < batches; ++b) {
    const uint64_t first = uint64_t(b) * s.batch_triangles;
    gpu::GpuBatch batch{uint32_t(first),
                        uint32_t(std::min<uint64_t>(s.batch_triangles, total - first)), b, 0};
    vkCmdPushConstants(cmd, p.layout, kShaderStages, 0, sizeof(batch), &batch);

    // The tile counts of the previous batch were read by its tile passes.
    memory_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                   VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT,
                   VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
    vkCmdFillBuffer(cmd, s.tile_counts.buffer, 0, VK_WHOLE_SIZE, 0);
    transfer_to_compute(cmd);

    bind(Pipeline::setup);
    vkCmdDispatch(cmd, div_up(batch.triangle_count, TS_SETUP_GROUP_SIZE), 1, 1);
    compute_to_compute(cmd);
    mark(Pass::setup);

    bind(Pipeline::clip);
    vkCmdDispatch(cmd, TS_CLIP_GROUPS, 1, 1);
    compute_to_compute(cmd);
    mark(Pass::clip);

    bind(Pipeline::bin_count);
    vkCmdDispatch(cmd, TS_COUNT_GROUPS, 1, 1);
    compute_to_compute(cmd);
    mark(Pass::bin_count);

    bind(Pipeline::scan);
    vkCmdDispatch(cmd, 1, 1, 1);
    compute_to_compute(cmd);
    mark(Pass::scan);

    const VkDeviceSize slot = VkDeviceSize(b) * sizeof(gpu::GpuCounters);
    bind(Pipeline::fill);
    vkCmdDispatchIndirect(cmd, s.counters.buffer, slot + offsetof(gpu::GpuCounters, big_dispatch));
    compute_to_compute(cmd);
    mark(Pass::fill);

    bind(s.options.debug_coverage ? Pipeline::raster_tiles_coverage : Pipeline::raster_tiles);
    vkCmdDispatchIndirect(cmd, s.counters.buffer,
                          slot + offsetof(gpu::GpuCounters, tiles_dispatch));
    compute_to_compute(cmd);
    mark(Pass::raster_tiles);

    bind(s.options.debug_coverage ? Pipeline::raster_small_coverage : Pipeline::raster_small);
    vkCmdDispatchIndirect(cmd, s.counters.buffer,
                          slot + offsetof(gpu::GpuCounters, small_dispatch));
    compute_to_compute(cmd);
    mark(Pass::raster_small);
  }

  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, shade_pipeline(s, settings));
  vkCmdDispatch(cmd, div_up(s.width, 8), div_up(s.height, 8), 1);
  compute_to_compute(cmd);
  mark(Pass::shade);

  bind(Pipeline::resolve);
  vkCmdDispatch(cmd, div_up(s.width, 8), div_up(s.height, 8), 1);
  memory_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                 VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
  mark(Pass::resolve);

  VkBufferCopy region{0, 0, s.counters.size};
  vkCmdCopyBuffer(cmd, s.counters.buffer, s.counters_readback.buffer, 1, &region);
  memory_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                 VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
}

ImageF Renderer::read_hdr() const {
  const State& s = *s_;
  TESSERA_CHECK(s.hdr.image != VK_NULL_HANDLE);
  std::vector<uint16_t> halves = download_image<uint16_t>(s.ctx, s.hdr, 4);
  ImageF out{s.width, s.height, std::vector<glm::vec4>(size_t(s.width) * s.height)};
  // The image holds radiance times the pre-exposure: divided back out (alpha excepted), a
  // stored 65504 reads as 65504 / 2^EV, the largest radiance the frame can carry.
  for (size_t i = 0; i < out.pixels.size(); ++i) {
    for (int c = 0; c < 4; ++c) out.pixels[i][c] = glm::unpackHalf1x16(halves[i * 4 + c]);
    out.pixels[i] /= glm::vec4(glm::vec3(s.hdr_pre_exposure), 1.0f);
  }
  return out;
}

Image8 Renderer::read_ldr() const {
  const State& s = *s_;
  TESSERA_CHECK(s.ldr.image != VK_NULL_HANDLE);
  std::vector<glm::u8vec4> texels = download_image<glm::u8vec4>(s.ctx, s.ldr, 1);
  return Image8{s.width, s.height, std::move(texels)};
}

std::vector<uint64_t> Renderer::read_visibility() const {
  TESSERA_CHECK(s_->visibility.buffer != VK_NULL_HANDLE);
  return download_buffer<uint64_t>(s_->ctx, s_->visibility, uint64_t(s_->width) * s_->height);
}

std::vector<uint32_t> Renderer::read_coverage() const {
  TESSERA_CHECK(s_->options.debug_coverage && s_->coverage.buffer != VK_NULL_HANDLE);
  return download_buffer<uint32_t>(s_->ctx, s_->coverage, uint64_t(s_->width) * s_->height);
}

std::vector<glm::vec4> Renderer::read_dfg_table() const {
  if (!s_->dfg_ready)
    throw Error("the DFG table is computed by the first frame with energy compensation");
  return download_buffer<glm::vec4>(s_->ctx, s_->dfg, 2 * (TS_DFG_SIZE + 1) * TS_DFG_SIZE);
}

const StorageImage& Renderer::output_image() const {
  return s_->ldr;
}

uint32_t Renderer::object_of_triangle(uint32_t triangle_id) const {
  const auto& objects = s_->uploaded.objects;
  auto it =
      std::upper_bound(objects.begin(), objects.end(), triangle_id,
                       [](uint32_t id, const gpu::GpuObject& o) { return id < o.first_triangle; });
  TESSERA_CHECK(it != objects.begin());
  const size_t slot = size_t(it - objects.begin()) - 1;
  TESSERA_CHECK(triangle_id - objects[slot].first_triangle < objects[slot].triangle_count);
  return s_->uploaded.object_of_slot[slot];
}

}  // namespace tessera
