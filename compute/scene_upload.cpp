#include "compute/scene_upload.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include <glm/gtc/packing.hpp>

#include "compute/renderer.h"
#include "core/check.h"
#include "core/mesh_adjacency.h"
#include "core/parallel.h"
#include "core/texture.h"

namespace tessera {
namespace {

// `d` (non-zero, finite) normalised. Where |d|^2 is not a normal float (|d| below 1e-19 or
// above 1e19) float arithmetic would give 0, Inf or NaN: double then.
glm::vec3 unit_direction(glm::vec3 d) {
  const float length2 = glm::dot(d, d);
  if (length2 >= std::numeric_limits<float>::min() && length2 <= std::numeric_limits<float>::max())
    return glm::normalize(d);
  return glm::vec3(glm::normalize(glm::dvec3(d)));
}

gpu::GpuMaterial gpu_material(const Material& m) {
  return {.base_color = m.base_color,
          .metallic = m.metallic,
          .emissive = m.emissive,
          .roughness = m.roughness,
          .occlusion = m.occlusion,
          .normal_scale = m.normal_scale,
          .double_sided = m.double_sided ? 1u : 0u,
          .emissive_map = m.emissive_map,
          .base_color_map = m.base_color_map,
          .metallic_roughness_map = m.metallic_roughness_map,
          .normal_map = m.normal_map,
          .occlusion_map = m.occlusion_map,
          .uv1_maps = m.uv1_maps};
}

// The same conversion for every kind: each kind's shader branch reads the fields it needs.
gpu::GpuLight gpu_light(const Light& l) {
  // A point light's direction may be zero (validation allows it).
  const bool has_direction = l.direction != glm::vec3(0.0f);
  // Spot cone as saturate(cos * scale + offset): 1 inside the inner cone, 0 outside the outer.
  const float cos_inner = std::cos(l.inner_angle), cos_outer = std::cos(l.outer_angle);
  const float scale = 1.0f / std::max(cos_inner - cos_outer, float(TS_MIN_SPOT_COSINE_GAP));
  return {.position = l.position,
          .kind = uint32_t(l.kind),
          .direction = has_direction ? unit_direction(l.direction) : glm::vec3(0.0f),
          .falloff = uint32_t(l.falloff),
          .radiance = l.color * l.intensity,
          .inv_range4 = l.range > 0.0f ? 1.0f / (l.range * l.range * l.range * l.range) : 0.0f,
          .attenuation = l.attenuation,
          .cone_scale = scale,
          .cone_offset = -cos_outer * scale};
}

// Builds e.texels and e.descriptor from e.source.
void pack_texture(TextureCache::Entry& e) {
  const Texture& t = e.source;
  const MipChain chain = build_mip_chain(t);
  TESSERA_CHECK(chain.levels.size() <= TS_MAX_TEXTURE_LEVELS);
  e.descriptor.size = glm::uvec2(t.width, t.height);
  e.descriptor.levels = uint32_t(chain.levels.size());
  size_t total = 0;
  for (const MipChain::Level& level : chain.levels) total += level.texels.size();
  e.texels.reserve(total);
  for (size_t l = 0; l < chain.levels.size(); ++l) {
    e.descriptor.level_offset[l / 4][l % 4] = uint32_t(e.texels.size());
    for (const glm::vec4& c : chain.levels[l].texels) {
      e.texels.push_back({glm::packHalf2x16({c.r, c.g}), glm::packHalf2x16({c.b, c.a})});
    }
  }
}

bool same_texture(const Texture& a, const Texture& b) {
  return a.width == b.width && a.height == b.height && a.srgb == b.srgb &&
         a.texels.size() == b.texels.size() &&
         std::memcmp(a.texels.data(), b.texels.data(), a.texels.size() * sizeof(glm::u8vec4)) == 0;
}

// Index of the entry holding `t` (hash first, then the whole texture), or entries.size().
size_t find_entry(const std::vector<TextureCache::Entry>& entries, const Texture& t,
                  uint64_t hash) {
  for (size_t k = 0; k < entries.size(); ++k) {
    if (entries[k].hash == hash && same_texture(entries[k].source, t)) return k;
  }
  return entries.size();
}

// Appends every texture's packed chain to out.texels and its descriptor to out.textures. Chains
// missing from `cache` are built in parallel, each distinct content once.
void pack_textures(const std::vector<Texture>& textures, TextureCache* cache, GpuSceneArrays& out) {
  std::vector<uint64_t> hashes(textures.size());
  parallel_for(textures.size(), [&](size_t i) { hashes[i] = texture_hash(textures[i]); });
  TextureCache next;
  std::vector<size_t> entry_of(textures.size());
  std::vector<size_t> to_build;  // texture indices, one per distinct missing content
  for (size_t i = 0; i < textures.size(); ++i) {
    // A content seen earlier in this scene shares that texture's entry.
    entry_of[i] = find_entry(next.entries, textures[i], hashes[i]);
    if (entry_of[i] < next.entries.size()) continue;
    const size_t hit = cache ? find_entry(cache->entries, textures[i], hashes[i]) : 0;
    if (cache && hit < cache->entries.size()) {
      next.entries.push_back(std::move(cache->entries[hit]));
      // Moved from: a later texture with the same content finds it in next.entries instead.
      cache->entries[hit].hash = ~hashes[i];
    } else {
      next.entries.push_back({.hash = hashes[i], .source = textures[i]});
      to_build.push_back(i);
    }
  }
  parallel_for(to_build.size(),
               [&](size_t b) { pack_texture(next.entries[entry_of[to_build[b]]]); });
  out.mip_chains_built = uint32_t(to_build.size());
  for (size_t i = 0; i < textures.size(); ++i) {
    const TextureCache::Entry& e = next.entries[entry_of[i]];
    if (out.texels.size() > 0xFFFFFFFFull - e.texels.size()) {
      throw Error(
          "the scene's textures have more than 2^32 texels with their mip levels: "
          "texture " +
          std::to_string(i) + " (" + std::to_string(textures[i].width) + "x" +
          std::to_string(textures[i].height) + ", " + std::to_string(e.texels.size()) +
          " texels with its mip levels) takes them past it");
    }
    gpu::GpuTexture g = e.descriptor;
    g.wrap = uint32_t(textures[i].wrap_u) | uint32_t(textures[i].wrap_v) << 2;
    for (uint32_t l = 0; l < g.levels; ++l)
      g.level_offset[l / 4][l % 4] += uint32_t(out.texels.size());
    out.texels.insert(out.texels.end(), e.texels.begin(), e.texels.end());
    out.textures.push_back(g);
  }
  if (cache) *cache = std::move(next);
}

// Appends `mesh`'s adjacency to out.adjacency, in step with its indices in out.indices.
void append_adjacency(const Mesh& mesh, GpuSceneArrays& out) {
  static_assert(kNoNeighbour == TS_NO_NEIGHBOUR);
  const std::vector<uint32_t> adjacency = triangle_adjacency(mesh);
  out.adjacency.insert(out.adjacency.end(), adjacency.begin(), adjacency.end());
}

// Appends the vertices of `mesh` with `tangents` (empty: zero) to out.vertices, and its uv set 1
// (zero where it has none) to out.uv1s when `uv1`.
void append_vertices(const Mesh& mesh, const std::vector<glm::vec4>& tangents, bool uv1,
                     GpuSceneArrays& out) {
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    const glm::vec2 uv = mesh.uvs.empty() ? glm::vec2(0.0f) : mesh.uvs[v];
    out.vertices.push_back({.position_u = glm::vec4(mesh.positions[v], uv.x),
                            .normal_v = glm::vec4(mesh.normals[v], uv.y),
                            .tangent = tangents.empty() ? glm::vec4(0.0f) : tangents[v]});
  }
  if (uv1) {
    if (mesh.uvs1.empty()) {
      out.uv1s.resize(out.uv1s.size() + mesh.positions.size(), glm::vec2(0.0f));
    } else {
      out.uv1s.insert(out.uv1s.end(), mesh.uvs1.begin(), mesh.uvs1.end());
    }
  }
}

// The error for a scene of more than 2^32 - 1 triangle instances, naming the mesh that makes
// most of them (a mesh placed by many objects, or a very large one).
Error too_many_triangles(const Scene& scene, const ObjectNumbering& numbering) {
  std::vector<uint64_t> placements(scene.meshes.size());
  for (const Object& o : scene.objects) placements[o.mesh]++;
  size_t top = 0;
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    if (placements[m] * scene.meshes[m].triangle_count() >
        placements[top] * scene.meshes[top].triangle_count())
      top = m;
  }
  const uint64_t triangles = scene.meshes[top].triangle_count();
  return Error("the scene has " + std::to_string(numbering.triangle_count) +
               " triangle instances, more than the 2^32 - 1 Tessera can number: " +
               std::to_string(placements[top] * triangles) + " of them are the " +
               std::to_string(triangles) + " triangles of mesh " + std::to_string(top) +
               ", which " + std::to_string(placements[top]) +
               (placements[top] == 1 ? " object places" : " objects place"));
}

constexpr uint64_t kMiB = 1u << 20;

// `bytes` for a message: in MiB from 1 MiB on, rounded down; in bytes below.
std::string size_text(uint64_t bytes) {
  return bytes < kMiB ? std::to_string(bytes) + " bytes" : std::to_string(bytes / kMiB) + " MiB";
}

// "a 153 MiB object buffer" (MiB rounded up), or "an object buffer of 1004 bytes" below 1 MiB.
std::string sized_buffer(const std::string& buffer, uint64_t bytes) {
  if (bytes >= kMiB) return "a " + std::to_string((bytes + kMiB - 1) / kMiB) + " MiB " + buffer;
  const bool vowel = buffer[0] == 'i' || buffer[0] == 'o';  // index, object
  return (vowel ? "an " : "a ") + buffer + " of " + std::to_string(bytes) + " bytes";
}

// The smallest float >= x (x >= 0, finite).
float float_at_least(double x) {
  float f = float(x);
  if (double(f) < x) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

}  // namespace

static_assert(uint32_t(TextureWrap::repeat) == TS_WRAP_REPEAT &&
              uint32_t(TextureWrap::clamp_to_edge) == TS_WRAP_CLAMP_TO_EDGE &&
              uint32_t(TextureWrap::mirrored_repeat) == TS_WRAP_MIRRORED_REPEAT);

uint64_t texture_hash(const Texture& texture) {
  // 64-bit multiply-xorshift mixing of 8 bytes (two texels) at a time.
  auto mix = [](uint64_t h, uint64_t v) {
    h ^= v + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
    h *= 0xBF58476D1CE4E5B9ull;
    return h ^ (h >> 31);
  };
  uint64_t h = mix(mix(0, texture.width), (uint64_t(texture.height) << 1) | texture.srgb);
  const auto* bytes = reinterpret_cast<const unsigned char*>(texture.texels.data());
  const size_t n = texture.texels.size() * sizeof(glm::u8vec4);
  size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    uint64_t v;
    std::memcpy(&v, bytes + i, 8);
    h = mix(h, v);
  }
  if (i < n) {
    uint64_t v = 0;
    std::memcpy(&v, bytes + i, n - i);
    h = mix(h, v);
  }
  return mix(h, n);
}

SceneBufferCounts buffer_counts(const GpuSceneArrays& a) {
  return {.vertices = a.vertices.size(),
          .indices = a.indices.size(),
          .objects = a.objects.size(),
          .group_objects = a.group_objects.size(),
          .materials = a.materials.size(),
          .lights = a.lights.size(),
          .textures = a.textures.size(),
          .uv1s = a.uv1s.size(),
          .lod_levels = a.lod_levels.size(),
          .lod_meshes = a.lod_meshes.size()};
}

void check_scene_buffers(const SceneBufferCounts& c, uint64_t max_range, const std::string& what) {
  // Each storage buffer of the scene (TS_BINDING_*): a descriptor binds it whole, and Vulkan
  // allows no range above maxStorageBufferRange (VUID-VkWriteDescriptorSet-descriptorType-00333):
  // a driver may fail or read wrong data past it even where lavapipe happens not to.
  struct Row {
    const char* buffer;
    uint64_t bytes;
    uint64_t count;
    const char* unit;
  };
  const Row rows[] = {
      {"vertex buffer", c.vertices * sizeof(gpu::GpuVertex), c.vertices, "vertices"},
      {"index buffer", c.indices * sizeof(uint32_t), c.indices, "indices"},
      // Then the group table (group_objects), a word per TS_TRIANGLE_GROUP triangle instances.
      {"object buffer", c.objects * sizeof(gpu::GpuObject) + c.group_objects * sizeof(uint32_t),
       c.objects, "objects"},
      {"material buffer", c.materials * sizeof(gpu::GpuMaterial), c.materials, "materials"},
      {"light buffer", c.lights * sizeof(gpu::GpuLight), c.lights, "lights"},
      {"texture buffer", c.textures * sizeof(gpu::GpuTexture), c.textures, "textures"},
      {"uv set 1 buffer", c.uv1s * sizeof(glm::vec2), c.uv1s, "vertices"},
      {"level-of-detail level buffer", c.lod_levels * sizeof(gpu::GpuLodLevel), c.lod_levels,
       "levels"},
      {"level-of-detail mesh buffer", c.lod_meshes * sizeof(gpu::GpuLodMesh), c.lod_meshes,
       "meshes"},
  };
  static_assert(sizeof(glm::mat4) < sizeof(gpu::GpuObject) &&
                    sizeof(VkDrawIndexedIndirectCommand) < sizeof(gpu::GpuObject),
                "the object buffer is the largest buffer sized by objects");
  for (const Row& r : rows) {
    if (r.bytes <= max_range) continue;
    // As many elements as fit at this buffer's bytes per element (the object buffer's group
    // table shared out over its objects).
    const uint64_t at_most =
        uint64_t((unsigned __int128)max_range * r.count / std::max<uint64_t>(r.bytes, 1));
    throw SceneSizeError(
        what + " needs " + sized_buffer(r.buffer, r.bytes) + " (" + std::to_string(r.count) + " " +
            r.unit + "), more than this device's maxStorageBufferRange (" + size_text(max_range) +
            "): it holds at most " + std::to_string(at_most) + " " + r.unit,
        r.buffer, r.bytes, max_range);
  }
}

AddressedBufferLimits addressed_buffer_limits(const Context& ctx) {
  uint64_t heap = 0;
  const VkPhysicalDeviceMemoryProperties& m = ctx.memory_properties;
  for (uint32_t i = 0; i < m.memoryHeapCount; ++i) {
    if (m.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)
      heap = std::max<uint64_t>(heap, m.memoryHeaps[i].size);
  }
  return {
      .max_allocation = ctx.max_allocation_size, .max_buffer = ctx.max_buffer_size, .heap = heap};
}

uint64_t largest_addressed_buffer(const AddressedBufferLimits& l) {
  return std::min({l.max_allocation, l.max_buffer, l.heap});
}

void check_texel_buffer(uint64_t texels, const AddressedBufferLimits& l, const std::string& what) {
  const uint64_t bytes = texels * sizeof(glm::uvec2);  // texels < 2^32 (flatten_scene)
  const uint64_t limit = largest_addressed_buffer(l);
  if (bytes <= limit) return;
  const char* name = limit == l.max_buffer       ? "maxBufferSize"
                     : limit == l.max_allocation ? "maxMemoryAllocationSize"
                                                 : "largest device-local memory heap";
  throw SceneSizeError(what + " needs " + sized_buffer("texel buffer", bytes) + " (" +
                           std::to_string(texels) +
                           " texels with their mip levels), more than this device's " + name +
                           " (" + size_text(limit) + "): it holds at most " +
                           std::to_string(limit / sizeof(glm::uvec2)) + " texels",
                       "texel buffer", bytes, limit);
}

GpuSceneArrays flatten_scene(const Scene& scene, TextureCache* cache) {
  GpuSceneArrays out;
  std::vector<uint32_t> first_index(scene.meshes.size());
  std::vector<uint32_t> base_vertex(scene.meshes.size());
  bool normal_maps = false;
  bool uv1 = false;
  for (const Material& m : scene.materials) {
    normal_maps |= m.normal_map != kNoTexture;
    uv1 |= m.uv1_maps != 0u;
  }
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    first_index[m] = uint32_t(out.indices.size());
    base_vertex[m] = uint32_t(out.vertices.size());
    std::vector<glm::vec4> generated;
    if (normal_maps && mesh.tangents.empty()) {
      generated = generate_tangents(mesh.positions, mesh.normals, mesh.uvs, mesh.indices);
    }
    const std::vector<glm::vec4>& tangents = mesh.tangents.empty() ? generated : mesh.tangents;
    append_vertices(mesh, tangents, uv1, out);
    out.indices.insert(out.indices.end(), mesh.indices.begin(), mesh.indices.end());
    append_adjacency(mesh, out);
  }

  out.mesh_first_index = first_index;
  out.mesh_base_vertex = base_vertex;
  const ObjectNumbering numbering = number_objects(scene);
  // The all-ones id is never used: it marks empty pixels in the visibility buffer.
  if (numbering.triangle_count > 0xFFFFFFFFull) throw too_many_triangles(scene, numbering);
  out.numbering = numbering;
  out.triangle_count = numbering.triangle_count;
  out.group_objects = group_objects(numbering);
  for (size_t slot = 0; slot < numbering.objects.size(); ++slot) {
    const Object& o = scene.objects[numbering.objects[slot]];
    const gpu::GpuObject g{
        .model = o.transform,
        .normal_matrix = glm::mat4(glm::transpose(glm::inverse(glm::mat3(o.transform)))),
        .first_index = first_index[o.mesh],
        .base_vertex = base_vertex[o.mesh],
        .triangle_count = uint32_t(scene.meshes[o.mesh].triangle_count()),
        .material = o.material,
        .first_triangle = uint32_t(numbering.first_triangle[slot]),
        .mirrored = is_mirroring(o.transform) ? 1u : 0u,
        .double_sided = scene.materials[o.material].double_sided ? 1u : 0u,
        .mesh = o.mesh};
    out.objects.push_back(g);
  }

  for (const Material& m : scene.materials) out.materials.push_back(gpu_material(m));
  for (const gpu::GpuMaterial& m : out.materials) {
    const std::pair<uint32_t, uint32_t> maps[] = {
        {m.base_color_map, TS_MAP_BASE_COLOR},
        {m.metallic_roughness_map, TS_MAP_METALLIC_ROUGHNESS},
        {m.normal_map, TS_MAP_NORMAL},
        {m.occlusion_map, TS_MAP_OCCLUSION},
        {m.emissive_map, TS_MAP_EMISSIVE}};
    for (const auto& [map, bit] : maps) {
      if (map != kNoTexture) out.texture_maps |= bit;
      if (map != kNoTexture && (m.uv1_maps & bit) != 0u) out.uv1_maps |= bit;
    }
  }
  pack_textures(scene.textures, cache, out);
  for (const Texture& t : scene.textures) {
    if (t.wrap_u != TextureWrap::repeat || t.wrap_v != TextureWrap::repeat)
      out.texture_maps |= TS_MAP_WRAP_MODES;
  }
  // Sorted by kind (stably), in TS_LIGHT_* order, so a shading pipeline specialized to the
  // counts of each kind can loop over each kind separately.
  std::vector<const Light*> sorted;
  for (const Light& l : scene.lights) sorted.push_back(&l);
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const Light* a, const Light* b) { return a->kind < b->kind; });
  for (const Light* l : sorted) {
    out.lights.push_back(gpu_light(*l));
    out.light_counts[uint32_t(l->kind)]++;
  }
  return out;
}

}  // namespace tessera

namespace tessera {

std::vector<uint32_t> group_objects(const ObjectNumbering& numbering) {
  const uint64_t groups = (numbering.triangle_count + TS_TRIANGLE_GROUP - 1) / TS_TRIANGLE_GROUP;
  std::vector<uint32_t> out(groups);
  size_t slot = 0;
  const size_t objects = numbering.first_triangle.size();
  for (uint64_t k = 0; k < groups; ++k) {
    const uint64_t id = k * TS_TRIANGLE_GROUP;
    while (slot + 1 < objects && numbering.first_triangle[slot + 1] <= id) ++slot;
    out[k] = uint32_t(slot);
  }
  return out;
}

void append_lod_chains(const std::vector<LodChain>& chains, GpuSceneArrays& out) {
  TESSERA_CHECK(chains.size() == out.mesh_first_index.size());
  out.lod_levels.clear();
  out.lod_meshes.clear();
  const bool uv1 = !out.uv1s.empty();
  for (size_t m = 0; m < chains.size(); ++m) {
    const LodChain& chain = chains[m];
    out.lod_meshes.push_back({.centre = glm::vec3(chain.centre),
                              .radius = float_at_least(chain.radius),
                              .first_level = uint32_t(out.lod_levels.size()),
                              .level_count = uint32_t(chain.levels.size())});
    for (const LodLevel& level : chain.levels) {
      const Mesh& mesh = *level.mesh;
      gpu::GpuLodLevel g{.first_index = out.mesh_first_index[m],
                         .base_vertex = out.mesh_base_vertex[m],
                         .triangle_count = uint32_t(mesh.triangle_count()),
                         .error = float_at_least(level.error)};
      if (!level.is_base) {
        const bool indices = out.indices.size() + mesh.indices.size() > 0xFFFFFFFFull;
        if (indices || out.vertices.size() + mesh.positions.size() > 0xFFFFFFFFull) {
          throw Error(std::string("the level-of-detail chains need more than 2^32 ") +
                      (indices ? "indices" : "vertices") + ": mesh " + std::to_string(m) +
                      "'s chain takes them past it");
        }
        g.first_index = uint32_t(out.indices.size());
        out.indices.insert(out.indices.end(), mesh.indices.begin(), mesh.indices.end());
        append_adjacency(mesh, out);
        if (!level.shares_base_vertices) {
          g.base_vertex = uint32_t(out.vertices.size());
          append_vertices(mesh, mesh.tangents, uv1, out);
        }
      }
      out.lod_levels.push_back(g);
    }
  }
}

}  // namespace tessera
