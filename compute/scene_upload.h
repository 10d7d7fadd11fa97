#pragma once
// Flattening a Scene into the arrays the GPU reads, in a canonical order.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "compute/context.h"
#include "core/lod.h"
#include "core/scene.h"
#include "core/texture.h"
#include "shaders/shared/gpu_types.h"

namespace tessera {

struct GpuSceneArrays {
  std::vector<gpu::GpuVertex> vertices;  // all meshes, one after another
  std::vector<uint32_t> indices;         // all meshes, relative to each mesh's first vertex
  /// Per entry of `indices`: the mesh's triangle across that corner's edge to the next
  /// (triangle_adjacency, core/mesh_adjacency.h), for silhouette coverage.
  std::vector<uint32_t> adjacency;
  std::vector<gpu::GpuObject> objects;  // canonical order (see flatten_scene)
  /// Per TS_TRIANGLE_GROUP triangle-instance ids: the object holding the group's first
  /// (group_objects); empty for a scene without triangles.
  std::vector<uint32_t> group_objects;
  std::vector<gpu::GpuMaterial> materials;
  std::vector<gpu::GpuLight> lights;                         // sorted by kind (TS_LIGHT_* order)
  std::array<uint32_t, TS_LIGHT_KIND_COUNT> light_counts{};  // lights of each kind, by TS_LIGHT_*
  std::vector<gpu::GpuTexture> textures;                     // per Scene::textures entry
  std::vector<glm::uvec2> texels;  // every mip level of every texture, fp16 RGBA
  uint32_t texture_maps = 0;       // TS_MAP_* bits of the maps any material uses
  ObjectNumbering numbering;       // GPU object slot i is Scene::objects[numbering.objects[i]]
  uint32_t uv1_maps = 0;           // TS_MAP_* bits of the maps any material reads with set 1
  /// Uv set 1 of every vertex (as `vertices`; zero where a mesh has none); empty unless a
  /// material reads set 1, so a scene without one uploads nothing for it.
  std::vector<glm::vec2> uv1s;
  uint64_t triangle_count = 0;             // triangle instances over all objects
  std::vector<uint32_t> mesh_first_index;  // per Scene::meshes entry: its first index
  std::vector<uint32_t> mesh_base_vertex;  // and its first vertex
  /// Level of detail (append_lod_chains; empty until a frame asks for it).
  std::vector<gpu::GpuLodLevel> lod_levels;
  std::vector<gpu::GpuLodMesh> lod_meshes;
  uint32_t mip_chains_built = 0;  // textures whose mip chain was built, not reused
};

/// Elements of each array of GpuSceneArrays that a storage buffer of the renderer holds, for
/// check_scene_buffers: from buffer_counts, or predicted for a scene not built yet (bench). Not
/// the texels, which the shaders read at a device address (check_texel_buffer).
struct SceneBufferCounts {
  uint64_t vertices = 0, indices = 0, objects = 0, group_objects = 0, materials = 0, lights = 0,
           textures = 0, uv1s = 0, lod_levels = 0, lod_meshes = 0;
};

SceneBufferCounts buffer_counts(const GpuSceneArrays& arrays);

/// Throws SceneSizeError (compute/renderer.h) for the first storage buffer that `counts` make
/// larger than `max_range` bytes (the device's maxStorageBufferRange, the most one descriptor
/// may bind), naming the buffer, its size, the limit and how many elements it holds at most.
/// `what` starts the message ("the scene"). The buffers sized by objects besides the object
/// buffer (TS_BINDING_OBJECT_CLIP, _LOD_DRAWS, _LOD_SUMS) take fewer bytes per object, and the
/// adjacency as many as the indices, so they fit when these do.
void check_scene_buffers(const SceneBufferCounts& counts, uint64_t max_range,
                         const std::string& what = "the scene");

/// What caps a buffer the shaders read at its device address (the texels): no descriptor binds
/// it, so maxStorageBufferRange does not, but it is one buffer in one allocation.
struct AddressedBufferLimits {
  uint64_t max_allocation;  // maxMemoryAllocationSize
  uint64_t max_buffer;      // maxBufferSize (2^64 - 1 where the device does not report it)
  uint64_t heap;            // the largest device-local memory heap
};

/// The limits of `ctx`'s device.
AddressedBufferLimits addressed_buffer_limits(const Context& ctx);

/// The most bytes such a buffer may hold: the smallest of the limits.
uint64_t largest_addressed_buffer(const AddressedBufferLimits& limits);

/// Throws SceneSizeError (compute/renderer.h) if `texels` (GpuSceneArrays::texels, 8 bytes
/// each) need more bytes than `limits` allow, naming the smallest limit and how many texels it
/// holds. (More than 2^32 texels flatten_scene refuses: the shaders index them in 32 bits.)
void check_texel_buffer(uint64_t texels, const AddressedBufferLimits& limits,
                        const std::string& what = "the scene");

/// Packed mip chains of the textures of the last flattened scene, by content, so that
/// flattening an edited scene rebuilds only the chains of textures that changed. A hit
/// compares the whole texture, not only its hash, so a hash collision cannot reuse a wrong
/// chain. Holds a copy of each texture it caches (its RGBA8 texels) besides the chain.
struct TextureCache {
  struct Entry {
    uint64_t hash = 0;
    Texture source;                  // the texture the chain was built from
    gpu::GpuTexture descriptor{};    // level_offset relative to the start of `texels`
    std::vector<glm::uvec2> texels;  // every level, fp16 RGBA, as GpuSceneArrays::texels
  };
  std::vector<Entry> entries;
};

/// A hash of a texture's size, sRGB flag and texels (not cryptographic: TextureCache compares
/// the texture itself on a hit).
uint64_t texture_hash(const Texture& texture);

/// Flattens `scene` (which must have passed validate_scene). Objects are uploaded in the order
/// of number_objects (core/scene.h), so the image does not depend on submission order.
/// Tangents missing from a mesh are generated (generate_tangents) when a material has a normal
/// map; texture mip chains are built (build_mip_chain, textures in parallel) and packed as
/// fp16. With a `cache`, chains of textures it holds are reused rather than built, and the cache
/// is left holding exactly the textures of `scene`; the arrays are the same either way.
/// Throws Error if the scene has more than 2^32 - 1 triangle instances or 2^32 texels, naming
/// the object or texture that goes past it. Buffer sizes are checked by check_scene_buffers.
GpuSceneArrays flatten_scene(const Scene& scene, TextureCache* cache = nullptr);

/// The object slot of `numbering` that holds id k * TS_TRIANGLE_GROUP, for every k with
/// k * TS_TRIANGLE_GROUP < numbering.triangle_count: as object_of_triangle (core/pick.h), the
/// last slot whose first id is <= it, so an object without triangles is never the answer.
/// Setup searches only between the entries around a subgroup's first id (two adjacent words)
/// instead of over every object: at 10^6 grid objects the search's scattered loads cost a
/// fifth of setup's time on the H200 (docs/performance.md). O(objects + groups).
std::vector<uint32_t> group_objects(const ObjectNumbering& numbering);

/// Appends the level-of-detail chains of the flattened scene's meshes (`chains`, one per
/// Scene::meshes entry, as build_lod_chains makes them) to `arrays`: the levels other than the
/// base mesh add their indices, and sphere tessellations their vertices (uv set 1 zero), after
/// everything flatten_scene wrote, so that the arrays without level of detail stay a prefix;
/// lod_levels and lod_meshes are rewritten. Errors and radii are rounded up to float, so the
/// GPU's choice is never less fine than the double-precision one but by its own rounding.
/// Throws Error past 2^32 vertices or indices.
void append_lod_chains(const std::vector<LodChain>& chains, GpuSceneArrays& arrays);

}  // namespace tessera
