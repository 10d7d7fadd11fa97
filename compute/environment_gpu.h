#pragma once
// The environment on the GPU: the equirectangular map with its mip chain, the prefiltered
// specular cube and the irradiance coefficients, and the passes that compute the last two
// (shaders/env_irradiance.comp, shaders/env_prefilter.comp) when the environment is set.

#include <memory>

#include <vulkan/vulkan.h>

#include "compute/gpu_memory.h"
#include "compute/pipelines.h"
#include "core/environment.h"

namespace tessera {

/// Resolutions and sample counts of the image-based lighting precomputation.
struct EnvironmentOptions {
  /// Side of the prefiltered cube's level 0 in texels: a power of two, 1 to 512. Level k holds
  /// roughness k / (levels - 1), levels = log2(side) + 1.
  uint32_t specular_size = 128;
  /// GGX importance samples per texel of the prefiltered levels above 0 (1 to 65536).
  uint32_t specular_samples = 128;
  /// The irradiance is projected from the map's largest mip level at most this wide (>= 1).
  uint32_t irradiance_size = 64;
};

/// Throws Error naming the first option out of range.
void validate_environment_options(const EnvironmentOptions& options);

struct EnvironmentGpu {
  StorageImage map;                           // equirectangular radiance, RGBA16F, full mip chain
  StorageImage specular;                      // prefiltered cube, RGBA16F, levels by roughness
  Buffer irradiance;                          // 9 vec4: SH coefficients of irradiance / pi
  Buffer level_texels;                        // the prefilter's output, copied into `specular`
  VkSampler map_sampler = VK_NULL_HANDLE;     // linear, mip-mapped, repeat in u, clamp in v
  VkSampler cube_sampler = VK_NULL_HANDLE;    // linear, mip-mapped (cube sampling is seamless)
  std::shared_ptr<const Environment> source;  // what the images hold; null: black placeholders
  EnvironmentOptions options;
  uint32_t irradiance_level = 0;  // map level the irradiance is projected from
  bool precompute_pending = false;
};

/// Creates the samplers and black 1x1 placeholders (for scenes without an environment, so
/// that the descriptors stay valid). `env` starts empty.
void create_environment_gpu(const Context& ctx, EnvironmentGpu& env);

/// Replaces the environment with `source` (null: the placeholders): uploads the map and builds
/// its mip chain (blits), allocates the cube and buffers, and marks the precomputation pending.
/// `source` must have passed validate_environment, `options` validate_environment_options.
void set_environment(const Context& ctx, EnvironmentGpu& env,
                     std::shared_ptr<const Environment> source, const EnvironmentOptions& options);

/// Records the irradiance and prefilter passes and the copies into the cube, with the shared
/// descriptor set (already bound, pointing at env's resources) and `pipelines`.
void record_environment_precompute(VkCommandBuffer cmd, EnvironmentGpu& env,
                                   const Pipelines& pipelines);

/// Levels of the prefiltered cube.
inline uint32_t specular_levels(const EnvironmentGpu& env) {
  return env.specular.levels;
}

void destroy_environment_gpu(const Context& ctx, EnvironmentGpu& env);

}  // namespace tessera
