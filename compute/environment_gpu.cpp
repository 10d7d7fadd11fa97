#include "compute/environment_gpu.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <string>
#include <vector>

#include <glm/gtc/packing.hpp>

#include "compute/vk_check.h"
#include "core/check.h"
#include "shaders/shared/gpu_types.h"

namespace tessera {
namespace {

constexpr VkFormat kFormat = VK_FORMAT_R16G16B16A16_SFLOAT;

uint32_t mip_levels(uint32_t width, uint32_t height) {
  return uint32_t(std::bit_width(std::max(width, height)));
}

constexpr VkPipelineStageFlags kShaderStagesRead =
    VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;

// Layout transition of `count` levels from `first` of every layer of `image`.
void transition(VkCommandBuffer cmd, const StorageImage& image, uint32_t first, uint32_t count,
                VkImageLayout from, VkImageLayout to, VkPipelineStageFlags src_stage,
                VkAccessFlags src_access, VkPipelineStageFlags dst_stage,
                VkAccessFlags dst_access) {
  VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  b.srcAccessMask = src_access;
  b.dstAccessMask = dst_access;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image.image;
  b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, first, count, 0, image.layers};
  vkCmdPipelineBarrier(cmd, src_stage, dst_stage, 0, 0, nullptr, 0, nullptr, 1, &b);
}

// A fresh image, every level, ready to be written by transfers.
void to_transfer_dst(VkCommandBuffer cmd, const StorageImage& image) {
  transition(cmd, image, 0, image.levels, VK_IMAGE_LAYOUT_UNDEFINED,
             VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0,
             VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
}

// Levels written by transfers, ready for the shaders to sample.
void to_shader_read(VkCommandBuffer cmd, const StorageImage& image, uint32_t first, uint32_t count,
                    VkImageLayout from) {
  transition(cmd, image, first, count, from, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
             VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, kShaderStagesRead,
             VK_ACCESS_SHADER_READ_BIT);
}

// Writes of transfers visible to shader reads (compute and the baseline's fragments).
void transfer_to_shaders(VkCommandBuffer cmd) {
  memory_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                 kShaderStagesRead, VK_ACCESS_SHADER_READ_BIT);
}

void release(const Context& ctx, EnvironmentGpu& env) {
  destroy_image(ctx, env.map);
  destroy_image(ctx, env.specular);
  destroy_buffer(ctx, env.irradiance);
  destroy_buffer(ctx, env.level_texels);
}

constexpr VkImageUsageFlags kUsage =
    VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;

void create_placeholders(const Context& ctx, EnvironmentGpu& env) {
  env.map = create_image(ctx, 1, 1, 1, false, kFormat, kUsage, VK_IMAGE_ASPECT_COLOR_BIT);
  env.specular = create_image(ctx, 1, 1, 1, true, kFormat, kUsage, VK_IMAGE_ASPECT_COLOR_BIT);
  env.irradiance = create_buffer(
      ctx, 9 * sizeof(glm::vec4),
      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryKind::device);
  env.level_texels =
      create_buffer(ctx, 256, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryKind::device);
  submit_and_wait(ctx, [&](VkCommandBuffer cmd) {
    to_transfer_dst(cmd, env.map);
    to_transfer_dst(cmd, env.specular);
    const VkClearColorValue black{};
    const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 6};
    VkImageSubresourceRange one = all;
    one.layerCount = 1;
    vkCmdClearColorImage(cmd, env.map.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &black, 1, &one);
    vkCmdClearColorImage(cmd, env.specular.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &black, 1,
                         &all);
    vkCmdFillBuffer(cmd, env.irradiance.buffer, 0, VK_WHOLE_SIZE, 0);
    to_shader_read(cmd, env.map, 0, 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    to_shader_read(cmd, env.specular, 0, 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    transfer_to_shaders(cmd);
  });
}

}  // namespace

void validate_environment_options(const EnvironmentOptions& o) {
  if (o.specular_size < 1 || o.specular_size > (1u << (TS_ENV_MAX_LEVELS - 1)) ||
      !std::has_single_bit(o.specular_size)) {
    throw Error("environment specular size " + std::to_string(o.specular_size) +
                " is not a power of two from 1 to " +
                std::to_string(1u << (TS_ENV_MAX_LEVELS - 1)));
  }
  if (o.specular_samples < 1 || o.specular_samples > 65536) {
    throw Error("environment specular samples " + std::to_string(o.specular_samples) +
                " is outside 1..65536");
  }
  if (o.irradiance_size < 1) throw Error("environment irradiance size must be at least 1");
}

void create_environment_gpu(const Context& ctx, EnvironmentGpu& env) {
  VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  info.magFilter = VK_FILTER_LINEAR;
  info.minFilter = VK_FILTER_LINEAR;
  info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
  info.addressModeU = VK_SAMPLER_ADDRESS_MODE_REPEAT;
  info.addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  info.maxLod = VK_LOD_CLAMP_NONE;
  VK_CHECK(vkCreateSampler(ctx.device, &info, nullptr, &env.map_sampler));
  info.addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  VK_CHECK(vkCreateSampler(ctx.device, &info, nullptr, &env.cube_sampler));
  create_placeholders(ctx, env);
}

void set_environment(const Context& ctx, EnvironmentGpu& env,
                     std::shared_ptr<const Environment> source, const EnvironmentOptions& options) {
  vkDeviceWaitIdle(ctx.device);
  release(ctx, env);
  env.source = std::move(source);
  env.options = options;
  env.precompute_pending = false;
  if (!env.source) {
    create_placeholders(ctx, env);
    return;
  }
  const ImageF& radiance = env.source->radiance;
  const uint32_t w = radiance.width, h = radiance.height;
  const uint32_t map_levels = mip_levels(w, h);
  env.map = create_image(ctx, w, h, map_levels, false, kFormat, kUsage, VK_IMAGE_ASPECT_COLOR_BIT);
  const uint32_t side = options.specular_size;
  const uint32_t cube_levels = uint32_t(std::bit_width(side));
  env.specular =
      create_image(ctx, side, side, cube_levels, true, kFormat, kUsage, VK_IMAGE_ASPECT_COLOR_BIT);
  env.irradiance = create_buffer(ctx, 9 * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                 MemoryKind::device);
  VkDeviceSize texels = 0;
  for (uint32_t l = 0; l < cube_levels; ++l) texels += 6ull * (side >> l) * (side >> l);
  // A descriptor binds the levels whole (TS_BINDING_ENV_LEVELS): at the largest side that
  // validate_environment_options allows, 6 (4^TS_ENV_MAX_LEVELS - 1) / 3 texels of 8 bytes (16
  // MiB at 512) fit the 2^27 bytes of maxStorageBufferRange that Vulkan guarantees on every
  // device, so no scene or option needs a check against the device's own.
  static_assert(2ull * ((1ull << (2 * TS_ENV_MAX_LEVELS)) - 1) * 8 <= (1ull << 27));
  env.level_texels = create_buffer(
      ctx, texels * 8, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
      MemoryKind::device);
  env.irradiance_level = 0;
  while (env.irradiance_level + 1 < map_levels &&
         (w >> env.irradiance_level) > options.irradiance_size)
    ++env.irradiance_level;

  // Level 0 from the file's float radiance, as fp16 (values above TS_MAX_HALF saturate to it).
  Buffer staging = create_buffer(ctx, VkDeviceSize(w) * h * 8, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                 MemoryKind::upload);
  auto* out = static_cast<uint16_t*>(staging.mapped);
  for (size_t i = 0; i < radiance.pixels.size(); ++i) {
    for (int c = 0; c < 4; ++c) {
      const float v = c == 3 ? 1.0f : std::min(radiance.pixels[i][c], float(TS_MAX_HALF));
      out[i * 4 + c] = uint16_t(glm::packHalf1x16(v));
    }
  }
  submit_and_wait(ctx, [&](VkCommandBuffer cmd) {
    to_transfer_dst(cmd, env.map);
    // The cube is written by record_environment_precompute; until then it reads as black.
    to_transfer_dst(cmd, env.specular);
    const VkClearColorValue black{};
    const VkImageSubresourceRange cube_all{VK_IMAGE_ASPECT_COLOR_BIT, 0, cube_levels, 0, 6};
    vkCmdClearColorImage(cmd, env.specular.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &black, 1,
                         &cube_all);
    to_shader_read(cmd, env.specular, 0, cube_levels, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {w, h, 1};
    vkCmdCopyBufferToImage(cmd, staging.buffer, env.map.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                           1, &region);
    // The mip chain by linear 2:1 blits, each level from the one before.
    for (uint32_t l = 1; l < map_levels; ++l) {
      transition(cmd, env.map, l - 1, 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                 VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
                 VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                 VK_ACCESS_TRANSFER_READ_BIT);
      VkImageBlit blit{};
      blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, l - 1, 0, 1};
      blit.srcOffsets[1] = {int32_t(std::max(w >> (l - 1), 1u)),
                            int32_t(std::max(h >> (l - 1), 1u)), 1};
      blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, l, 0, 1};
      blit.dstOffsets[1] = {int32_t(std::max(w >> l, 1u)), int32_t(std::max(h >> l, 1u)), 1};
      vkCmdBlitImage(cmd, env.map.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, env.map.image,
                     VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
    }
    if (map_levels > 1) {
      to_shader_read(cmd, env.map, 0, map_levels - 1, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    }
    to_shader_read(cmd, env.map, map_levels - 1, 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
  });
  destroy_buffer(ctx, staging);
  env.precompute_pending = true;
}

void record_environment_precompute(VkCommandBuffer cmd, EnvironmentGpu& env,
                                   const Pipelines& pipelines) {
  if (!env.precompute_pending) return;
  const uint32_t side = env.options.specular_size;
  const uint32_t levels = env.specular.levels;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines[Pipeline::env_irradiance]);
  gpu::GpuEnvPass pass{env.irradiance_level, 0, 0, levels};
  vkCmdPushConstants(cmd, pipelines.layout, kShaderStages, 0, sizeof(pass), &pass);
  vkCmdDispatch(cmd, 1, 1, 1);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines[Pipeline::env_prefilter]);
  for (uint32_t l = 0; l < levels; ++l) {
    const uint32_t size = side >> l;
    pass = {l, size, env.options.specular_samples, levels};
    vkCmdPushConstants(cmd, pipelines.layout, kShaderStages, 0, sizeof(pass), &pass);
    vkCmdDispatch(cmd, (size + 7) / 8, (size + 7) / 8, 6);
  }
  memory_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                 VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT |
                     VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                 VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_SHADER_READ_BIT);
  std::vector<VkBufferImageCopy> regions;
  VkDeviceSize offset = 0;
  for (uint32_t l = 0; l < levels; ++l) {
    const uint32_t size = side >> l;
    VkBufferImageCopy r{};
    r.bufferOffset = offset;
    r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, l, 0, 6};
    r.imageExtent = {size, size, 1};
    regions.push_back(r);
    offset += 6ull * size * size * 8;
  }
  transition(cmd, env.specular, 0, levels, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
             VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, kShaderStagesRead, VK_ACCESS_SHADER_READ_BIT,
             VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
  vkCmdCopyBufferToImage(cmd, env.level_texels.buffer, env.specular.image,
                         VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, uint32_t(regions.size()),
                         regions.data());
  to_shader_read(cmd, env.specular, 0, levels, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
  env.precompute_pending = false;
}

void destroy_environment_gpu(const Context& ctx, EnvironmentGpu& env) {
  release(ctx, env);
  if (env.map_sampler) vkDestroySampler(ctx.device, env.map_sampler, nullptr);
  if (env.cube_sampler) vkDestroySampler(ctx.device, env.cube_sampler, nullptr);
  env = EnvironmentGpu{};
}

}  // namespace tessera
