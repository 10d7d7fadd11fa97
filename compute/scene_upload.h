#pragma once
// Flattening a Scene into the arrays the GPU reads, in a canonical order.

#include <array>
#include <cstdint>
#include <vector>

#include "core/scene.h"
#include "shaders/shared/gpu_types.h"

namespace tessera {

struct GpuSceneArrays {
  std::vector<gpu::GpuVertex> vertices;  // all meshes, one after another
  std::vector<uint32_t> indices;         // all meshes, relative to each mesh's first vertex
  std::vector<gpu::GpuObject> objects;   // canonical order (see flatten_scene)
  std::vector<gpu::GpuMaterial> materials;
  std::vector<gpu::GpuLight> lights;                         // sorted by kind (TS_LIGHT_* order)
  std::array<uint32_t, TS_LIGHT_KIND_COUNT> light_counts{};  // lights of each kind, by TS_LIGHT_*
  std::vector<gpu::GpuTexture> textures;                     // per Scene::textures entry
  std::vector<glm::uvec2> texels;        // every mip level of every texture, fp16 RGBA
  uint32_t texture_maps = 0;             // TS_MAP_* bits of the maps any material uses
  std::vector<uint32_t> object_of_slot;  // GPU object slot -> index in Scene::objects
  uint64_t triangle_count = 0;           // triangle instances over all objects
};

/// Flattens `scene` (which must have passed validate_scene). Objects are uploaded in the order
/// of number_objects (core/scene.h), so the image does not depend on submission order.
/// Tangents missing from a mesh are generated (generate_tangents) when a material has a normal
/// map; texture mip chains are built (build_mip_chain) and packed as fp16.
/// Throws Error if the scene has more than 2^32 - 1 triangle instances or 2^32 texels.
GpuSceneArrays flatten_scene(const Scene& scene);

}  // namespace tessera
