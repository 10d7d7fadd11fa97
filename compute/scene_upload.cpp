#include "compute/scene_upload.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <glm/gtc/packing.hpp>

#include "core/check.h"
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

}  // namespace
GpuSceneArrays flatten_scene(const Scene& scene) {
  GpuSceneArrays out;
  std::vector<uint32_t> first_index(scene.meshes.size());
  std::vector<uint32_t> base_vertex(scene.meshes.size());
  bool normal_maps = false;
  for (const Material& m : scene.materials) normal_maps |= m.normal_map != kNoTexture;
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    first_index[m] = uint32_t(out.indices.size());
    base_vertex[m] = uint32_t(out.vertices.size());
    std::vector<glm::vec4> generated;
    if (normal_maps && mesh.tangents.empty()) {
      generated = generate_tangents(mesh.positions, mesh.normals, mesh.uvs, mesh.indices);
    }
    const std::vector<glm::vec4>& tangents = mesh.tangents.empty() ? generated : mesh.tangents;
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
      out.vertices.push_back({glm::vec4(mesh.positions[v], mesh.uvs[v].x),
                              glm::vec4(mesh.normals[v], mesh.uvs[v].y),
                              tangents.empty() ? glm::vec4(0.0f) : tangents[v]});
    }
    out.indices.insert(out.indices.end(), mesh.indices.begin(), mesh.indices.end());
  }

  const ObjectNumbering numbering = number_objects(scene);
  // The all-ones id is never used: it marks empty pixels in the visibility buffer.
  if (numbering.triangle_count > 0xFFFFFFFFull) {
    throw Error("the scene has " + std::to_string(numbering.triangle_count) +
                " triangle instances, more than the 2^32 - 1 Tessera can number");
  }
  out.object_of_slot = numbering.objects;
  out.triangle_count = numbering.triangle_count;
  for (size_t slot = 0; slot < numbering.objects.size(); ++slot) {
    const Object& o = scene.objects[numbering.objects[slot]];
    gpu::GpuObject g{};
    g.model = o.transform;
    g.normal_matrix = glm::mat4(glm::transpose(glm::inverse(glm::mat3(o.transform))));
    g.first_index = first_index[o.mesh];
    g.base_vertex = base_vertex[o.mesh];
    g.triangle_count = uint32_t(scene.meshes[o.mesh].triangle_count());
    g.material = o.material;
    g.first_triangle = uint32_t(numbering.first_triangle[slot]);
    out.objects.push_back(g);
  }

  for (const Material& m : scene.materials) {
    const glm::uvec4 maps(m.base_color_map, m.metallic_roughness_map, m.normal_map,
                          m.occlusion_map);
    out.materials.push_back({glm::vec4(m.base_color, 1.0f), glm::vec4(m.emissive, m.occlusion),
                             m.metallic, m.roughness, m.normal_scale, 0.0f, maps});
    for (int k = 0; k < 4; ++k) {
      if (maps[k] != kNoTexture) out.texture_maps |= 1u << k;
    }
  }
  for (const Texture& t : scene.textures) {
    const MipChain chain = build_mip_chain(t);
    gpu::GpuTexture g{};
    g.size = glm::uvec4(t.width, t.height, uint32_t(chain.levels.size()), 0);
    TESSERA_CHECK(chain.levels.size() <= TS_MAX_TEXTURE_LEVELS);
    for (size_t l = 0; l < chain.levels.size(); ++l) {
      if (out.texels.size() > 0xFFFFFFFFull - chain.levels[l].texels.size()) {
        throw Error("the scene's textures have more than 2^32 texels with their mip levels");
      }
      g.level_offset[l / 4][l % 4] = uint32_t(out.texels.size());
      for (const glm::vec4& c : chain.levels[l].texels) {
        out.texels.push_back({glm::packHalf2x16({c.r, c.g}), glm::packHalf2x16({c.b, c.a})});
      }
    }
    out.textures.push_back(g);
  }
  // Sorted by kind (stably), so a shading pipeline specialized to the counts of each kind can
  // loop over each kind separately.
  std::vector<const Light*> sorted;
  for (LightKind kind : {LightKind::point, LightKind::spot, LightKind::directional}) {
    for (const Light& l : scene.lights) {
      if (l.kind != kind) continue;
      sorted.push_back(&l);
      out.light_counts[kind == LightKind::point ? 0 : kind == LightKind::spot ? 1 : 2]++;
    }
  }
  for (const Light* light : sorted) {
    const Light& l = *light;
    gpu::GpuLight g{};
    g.position = glm::vec4(l.position, 1.0f);
    const glm::vec3 dir =
        l.kind == LightKind::point ? glm::vec3(0.0f) : unit_direction(l.direction);
    g.direction = glm::vec4(dir, 0.0f);
    g.radiance = glm::vec4(l.color * l.intensity, 0.0f);
    const float inv_range4 = l.range > 0.0f ? 1.0f / (l.range * l.range * l.range * l.range) : 0.0f;
    g.falloff = glm::vec4(inv_range4, l.attenuation);
    // Spot cone as saturate(cos * scale + offset): 1 inside the inner cone, 0 outside the outer.
    // Equal angles would divide by zero: 1e-4 makes the edge a hard step instead.
    const float cos_inner = std::cos(l.inner_angle), cos_outer = std::cos(l.outer_angle);
    const float scale = 1.0f / std::max(cos_inner - cos_outer, 1e-4f);
    g.cone = glm::vec4(scale, -cos_outer * scale, 0.0f, 0.0f);
    const uint32_t kind = l.kind == LightKind::directional ? TS_LIGHT_DIRECTIONAL
                          : l.kind == LightKind::spot      ? TS_LIGHT_SPOT
                                                           : TS_LIGHT_POINT;
    g.kind = glm::uvec4(
        kind, l.falloff == Falloff::classic ? TS_FALLOFF_CLASSIC : TS_FALLOFF_INVERSE_SQUARE, 0, 0);
    out.lights.push_back(g);
  }
  return out;
}

}  // namespace tessera
