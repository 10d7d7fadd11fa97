#include "compute/scene_upload.h"

#include <string>

#include "core/check.h"

namespace tessera {
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
