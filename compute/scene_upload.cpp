#include "compute/scene_upload.h"

#include <algorithm>
#include <numeric>
#include <string>
#include <tuple>

#include "core/check.h"

namespace tessera {
namespace {

// Total order on objects by content. Validation has excluded NaN, so < is a strict weak order.
bool content_less(const Object& a, const Object& b) {
  if (a.mesh != b.mesh) return a.mesh < b.mesh;
  if (a.material != b.material) return a.material < b.material;
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) {
      if (a.transform[c][r] != b.transform[c][r]) return a.transform[c][r] < b.transform[c][r];
    }
  }
  return false;
}

}  // namespace

GpuSceneArrays flatten_scene(const Scene& scene) {
  GpuSceneArrays out;
  std::vector<uint32_t> first_index(scene.meshes.size());
  std::vector<uint32_t> base_vertex(scene.meshes.size());
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    first_index[m] = uint32_t(out.indices.size());
    base_vertex[m] = uint32_t(out.vertices.size());
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
      out.vertices.push_back(
          {glm::vec4(mesh.positions[v], mesh.uvs[v].x), glm::vec4(mesh.normals[v], mesh.uvs[v].y)});
    }
    out.indices.insert(out.indices.end(), mesh.indices.begin(), mesh.indices.end());
  }

  out.object_of_slot.resize(scene.objects.size());
  std::iota(out.object_of_slot.begin(), out.object_of_slot.end(), 0u);
  std::stable_sort(
      out.object_of_slot.begin(), out.object_of_slot.end(),
      [&](uint32_t a, uint32_t b) { return content_less(scene.objects[a], scene.objects[b]); });

  uint64_t next_triangle = 0;
  for (uint32_t slot : out.object_of_slot) {
    const Object& o = scene.objects[slot];
    const uint32_t triangles = uint32_t(scene.meshes[o.mesh].triangle_count());
    if (triangles == 0) continue;  // nothing to draw; keeps first_triangle strictly ordered
    gpu::GpuObject g{};
    g.model = o.transform;
    g.normal_matrix = glm::mat4(glm::transpose(glm::inverse(glm::mat3(o.transform))));
    g.first_index = first_index[o.mesh];
    g.base_vertex = base_vertex[o.mesh];
    g.triangle_count = triangles;
    g.material = o.material;
    g.first_triangle = uint32_t(next_triangle);
    next_triangle += triangles;
    // The all-ones id is never used: it marks empty pixels in the visibility buffer.
    if (next_triangle > 0xFFFFFFFFull) {
      throw Error(
          "the scene has more than 2^32 - 2 triangle instances, more than Tessera can number");
    }
    out.objects.push_back(g);
  }
  // Keep the slot -> object map aligned with the objects actually uploaded.
  std::erase_if(out.object_of_slot, [&](uint32_t o) {
    return scene.meshes[scene.objects[o].mesh].triangle_count() == 0;
  });
  out.triangle_count = next_triangle;

  for (const Material& m : scene.materials) {
    out.materials.push_back({glm::vec4(m.base_color, 1.0f), m.metallic, m.roughness, 0.0f, 0.0f});
  }
  for (const Light& l : scene.lights) {
    gpu::GpuLight g{};
    g.position = glm::vec4(l.position, 1.0f);
    glm::vec3 dir =
        l.kind == LightKind::directional ? glm::normalize(l.direction) : glm::vec3(0.0f);
    g.direction = glm::vec4(dir, 0.0f);
    g.radiance = glm::vec4(l.color * l.intensity, 0.0f);
    g.kind = glm::uvec4(l.kind == LightKind::directional ? TS_LIGHT_DIRECTIONAL : TS_LIGHT_POINT, 0,
                        0, 0);
    out.lights.push_back(g);
  }
  return out;
}

}  // namespace tessera
