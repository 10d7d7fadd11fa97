#include "core/scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "core/check.h"
#include "core/clip_prediction.h"

namespace tessera {
namespace {

bool finite(float v) {
  return std::isfinite(v);
}
template <int N>
bool finite(const glm::vec<N, float>& v) {
  for (int i = 0; i < N; ++i) {
    if (!std::isfinite(v[i])) return false;
  }
  return true;
}
bool finite(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c) {
    if (!finite(m[c])) return false;
  }
  return true;
}

// A float as printed in messages: shortest form ("0", "1.5").
std::string number(float v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

[[noreturn]] void fail(const std::string& what) {
  throw Error("invalid scene: " + what);
}

void require(bool ok, const std::string& what) {
  if (!ok) fail(what);
}

void validate_mesh(const Mesh& mesh, size_t m) {
  const std::string name = "mesh " + std::to_string(m);
  require(mesh.normals.size() == mesh.positions.size(),
          name + " has " + std::to_string(mesh.normals.size()) + " normals for " +
              std::to_string(mesh.positions.size()) + " positions");
  require(mesh.uvs.empty() || mesh.uvs.size() == mesh.positions.size(),
          name + " has " + std::to_string(mesh.uvs.size()) + " uvs for " +
              std::to_string(mesh.positions.size()) + " positions (give none or one per vertex)");
  require(mesh.uvs1.empty() || mesh.uvs1.size() == mesh.positions.size(),
          name + " has " + std::to_string(mesh.uvs1.size()) + " uvs of set 1 for " +
              std::to_string(mesh.positions.size()) + " positions (give none or one per vertex)");
  for (size_t v = 0; v < mesh.uvs1.size(); ++v) {
    if (!finite(mesh.uvs1[v]))
      fail(name + " vertex " + std::to_string(v) + " has a NaN or infinite uv of set 1");
  }
  require(mesh.indices.size() % 3 == 0,
          name + " has " + std::to_string(mesh.indices.size()) + " indices, not a multiple of 3");
  require(mesh.tangents.empty() || mesh.tangents.size() == mesh.positions.size(),
          name + " has " + std::to_string(mesh.tangents.size()) + " tangents for " +
              std::to_string(mesh.positions.size()) + " positions (give none or one per vertex)");
  for (size_t v = 0; v < mesh.tangents.size(); ++v) {
    if (!finite(mesh.tangents[v]))
      fail(name + " tangent " + std::to_string(v) + " has a NaN or infinite component");
  }
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    if (!finite(mesh.positions[v]) || !finite(mesh.normals[v]) ||
        (!mesh.uvs.empty() && !finite(mesh.uvs[v])))
      fail(name + " vertex " + std::to_string(v) + " has a NaN or infinite coordinate");
  }
  for (size_t i = 0; i < mesh.indices.size(); ++i) {
    if (mesh.indices[i] >= mesh.positions.size())
      fail(name + " index " + std::to_string(i) + " is " + std::to_string(mesh.indices[i]) +
           ", past its " + std::to_string(mesh.positions.size()) + " vertices");
  }
}

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

void validate_light(const Light& light, size_t l) {
  const std::string name = "light " + std::to_string(l);
  require(finite(light.position) && finite(light.direction) && finite(light.color) &&
              finite(light.intensity),
          name + " has a NaN or infinite value");
  const bool positioned = light.kind != LightKind::directional;
  require(!positioned || within_scene_coordinates(light.position),
          name + " position is outside +-" + number(kMaxSceneCoordinate) + " m per coordinate");
  // Zero only when every component is: a direction of length 1e-30 is still a direction (the
  // upload normalises it without underflow).
  require(light.kind == LightKind::point || light.direction != glm::vec3(0.0f),
          name + " has a zero direction");
  require(glm::all(glm::greaterThanEqual(light.color, glm::vec3(0.0f))) && light.intensity >= 0.0f,
          name + " has a negative color or intensity");
  const float brightest = light.intensity * std::max({light.color.r, light.color.g, light.color.b});
  require(brightest <= kMaxLightIntensity, name + " intensity times color is " + number(brightest) +
                                               ", above " + number(kMaxLightIntensity) +
                                               (positioned ? " W/sr" : " W/m^2"));
  require(finite(light.range) && (light.range == 0.0f ||
                                  (light.range >= kMinLightRange && light.range <= kMaxLightRange)),
          name + " range is " + number(light.range) + " m; it must be 0 (no fade) or within [" +
              number(kMinLightRange) + ", " + number(kMaxLightRange) + "] m");
  require(finite(light.attenuation) && light.attenuation.x >= 0.0f && light.attenuation.y >= 0.0f &&
              light.attenuation.z >= 0.0f && light.attenuation != glm::vec3(0.0f),
          name + " needs attenuation Kc, Kl, Kq >= 0 and not all zero");
  require(glm::all(glm::lessThanEqual(light.attenuation, glm::vec3(kMaxAttenuation))),
          name + " attenuation Kc, Kl, Kq must each be at most " + number(kMaxAttenuation));
  require(finite(light.inner_angle) && finite(light.outer_angle) && light.inner_angle >= 0.0f &&
              light.inner_angle <= light.outer_angle && light.outer_angle < 1.5707963f,
          name + " needs spot angles with 0 <= inner <= outer < pi/2");
}

}  // namespace

ObjectNumbering number_objects(const Scene& scene) {
  ObjectNumbering n;
  for (uint32_t o = 0; o < scene.objects.size(); ++o) {
    if (scene.meshes[scene.objects[o].mesh].triangle_count() > 0) n.objects.push_back(o);
  }
  std::stable_sort(n.objects.begin(), n.objects.end(), [&](uint32_t a, uint32_t b) {
    return content_less(scene.objects[a], scene.objects[b]);
  });
  for (uint32_t o : n.objects) {
    n.first_triangle.push_back(n.triangle_count);
    n.triangle_count += scene.meshes[scene.objects[o].mesh].triangle_count();
  }
  return n;
}

glm::vec3 id_colour(uint32_t id) {
  uint32_t h = id * 747796405u + 2891336453u;
  h = ((h >> ((h >> 28u) + 4u)) ^ h) * 277803737u;
  h = (h >> 22u) ^ h;
  return glm::vec3(h & 0xFFu, (h >> 8) & 0xFFu, (h >> 16) & 0xFFu) / 255.0f;
}

void validate_camera(const Camera& c) {
  require(finite(c.position) && finite(c.target) && finite(c.up),
          "the camera has a NaN or infinite coordinate");
  require(
      within_scene_coordinates(c.position),
      "the camera's position is outside +-" + number(kMaxSceneCoordinate) + " m per coordinate");
  require(glm::length(c.target - c.position) > 0.0f, "the camera's target equals its position");
  require(glm::length(glm::cross(c.target - c.position, c.up)) > 0.0f,
          "the camera's up vector is zero or parallel to its view direction");
  // Up to 179 degrees, as scene files allow (docs/scene-format.md), with room for the rounding
  // of their degrees to radians in float: 3.1242 rad is 179.004 degrees.
  require(finite(c.vertical_fov) && c.vertical_fov > 0.0f && c.vertical_fov < 3.1242f,
          "the camera's vertical field of view must be in (0, 179] degrees");
  require(finite(c.near_plane) && c.near_plane > 0.0f, "the camera's near plane must be > 0");
}

namespace {

// Each mesh's box in object space, for the checks of placed objects (empty meshes are skipped).
std::vector<MeshBox> mesh_boxes(const Scene& scene) {
  std::vector<MeshBox> boxes;
  for (const Mesh& mesh : scene.meshes) boxes.push_back(mesh_box(mesh));
  return boxes;
}

}  // namespace

void validate_scene(const Scene& scene) {
  validate_camera(scene.camera);
  require(finite(scene.background) && finite(scene.ambient),
          "the background or ambient colour has a NaN or infinite component");

  for (size_t m = 0; m < scene.meshes.size(); ++m) validate_mesh(scene.meshes[m], m);
  for (size_t m = 0; m < scene.materials.size(); ++m) {
    const Material& mat = scene.materials[m];
    const std::string name = "material " + std::to_string(m);
    require(finite(mat.base_color) && finite(mat.emissive), name + " has a NaN or infinite colour");
    require(glm::all(glm::greaterThanEqual(mat.emissive, glm::vec3(0.0f))),
            name + " has a negative emissive colour");
    for (const MaterialScalar& p : kMaterialScalars) {
      const float v = mat.*p.field;
      require(finite(v), name + " has a NaN or infinite " + p.name);
      require(v >= p.min && v <= p.max, name + " has " + p.name + " outside [" + number(p.min) +
                                            ", " + number(p.max) + "]: " + number(v));
    }
    const std::pair<const char*, uint32_t> maps[] = {
        {"base colour", mat.base_color_map},
        {"metallic-roughness", mat.metallic_roughness_map},
        {"normal", mat.normal_map},
        {"occlusion", mat.occlusion_map},
        {"emissive", mat.emissive_map}};
    for (const auto& [what, index] : maps) {
      require(index == kNoTexture || index < scene.textures.size(),
              name + " uses texture " + std::to_string(index) + " as its " + what + " map, of " +
                  std::to_string(scene.textures.size()));
    }
    constexpr uint32_t kMaps = TS_MAP_BASE_COLOR | TS_MAP_METALLIC_ROUGHNESS | TS_MAP_NORMAL |
                               TS_MAP_OCCLUSION | TS_MAP_EMISSIVE;
    require((mat.uv1_maps & ~kMaps) == 0u, name + " has uv1_maps " + std::to_string(mat.uv1_maps) +
                                               ", bits other than the five maps' TS_MAP_*");
  }
  for (size_t t = 0; t < scene.textures.size(); ++t) {
    const Texture& tex = scene.textures[t];
    require(tex.width > 0 && tex.height > 0 && tex.width <= kMaxTextureSide &&
                tex.height <= kMaxTextureSide,
            "texture " + std::to_string(t) + " is " + std::to_string(tex.width) + "x" +
                std::to_string(tex.height) + ", outside 1.." + std::to_string(kMaxTextureSide) +
                " per side");
    require(tex.texels.size() == size_t(tex.width) * tex.height,
            "texture " + std::to_string(t) + " has " + std::to_string(tex.texels.size()) +
                " texels for " + std::to_string(tex.width) + "x" + std::to_string(tex.height));
  }
  if (scene.environment) {
    try {
      validate_environment(*scene.environment);
    } catch (const Error& e) {
      throw Error(std::string("invalid scene: ") + e.what());
    }
  }
  const std::vector<MeshBox> boxes = mesh_boxes(scene);
  // Every set_scene checks every object (the viewer's too, after each edit): the messages are
  // made only for the object that fails, not formatted for each of 90,000 that pass.
  for (size_t o = 0; o < scene.objects.size(); ++o) {
    const Object& obj = scene.objects[o];
    const auto name = [o] { return "object " + std::to_string(o); };
    if (obj.mesh >= scene.meshes.size())
      fail(name() + " uses mesh " + std::to_string(obj.mesh) + " of " +
           std::to_string(scene.meshes.size()));
    if (obj.material >= scene.materials.size())
      fail(name() + " uses material " + std::to_string(obj.material) + " of " +
           std::to_string(scene.materials.size()));
    if (!finite(obj.transform)) fail(name() + " has a NaN or infinite transform");
    if (scene.materials[obj.material].uv1_maps != 0u && scene.meshes[obj.mesh].uvs1.empty())
      fail(name() + ": material " + std::to_string(obj.material) + " reads uv set 1, which mesh " +
           std::to_string(obj.mesh) + " does not have");
    // The world-space box of the mesh's box contains every vertex.
    if (scene.meshes[obj.mesh].positions.empty()) continue;
    const auto [lo, hi] = boxes[obj.mesh];
    for (int corner = 0; corner < 8; ++corner) {
      const glm::vec3 p((corner & 1) ? hi.x : lo.x, (corner & 2) ? hi.y : lo.y,
                        (corner & 4) ? hi.z : lo.z);
      if (!within_scene_coordinates(glm::vec3(obj.transform * glm::vec4(p, 1.0f))))
        fail(name() + " reaches outside +-" + number(kMaxSceneCoordinate) +
             " m per coordinate in world space");
    }
  }
  for (size_t l = 0; l < scene.lights.size(); ++l) validate_light(scene.lights[l], l);
}

CoarsePositions coarse_positions(const Scene& scene) {
  const std::vector<MeshBox> boxes = mesh_boxes(scene);
  CoarsePositions coarse;
  for (size_t o = 0; o < scene.objects.size(); ++o) {
    const Object& obj = scene.objects[o];
    if (obj.mesh >= scene.meshes.size() || scene.meshes[obj.mesh].positions.empty()) continue;
    const auto [lo, hi] = boxes[obj.mesh];
    glm::dvec3 world_lo(std::numeric_limits<double>::max()), world_hi(-world_lo);
    for (int corner = 0; corner < 8; ++corner) {
      const glm::dvec4 p((corner & 1) ? hi.x : lo.x, (corner & 2) ? hi.y : lo.y,
                         (corner & 4) ? hi.z : lo.z, 1.0);
      const glm::dvec3 w(glm::dmat4(obj.transform) * p);
      world_lo = glm::min(world_lo, w);
      world_hi = glm::max(world_hi, w);
    }
    const glm::dvec3 side = world_hi - world_lo;
    const double size = std::max({side.x, side.y, side.z});
    const glm::dvec3 reach = glm::max(glm::abs(world_lo), glm::abs(world_hi));
    const double distance = std::max({reach.x, reach.y, reach.z});
    // The spacing of floats at `distance`: 2^(exponent - 23) for a 24-bit significand.
    const float far = float(distance);
    const double spacing =
        double(std::nextafter(far, std::numeric_limits<float>::infinity())) - far;
    // An object of no size (its vertices at one point) draws nothing to see a grain in.
    if (size <= 0.0 || !(spacing > size / 1024.0)) continue;
    if (coarse.count++ == 0) {
      coarse.first = o;
      coarse.distance = distance;
      coarse.spacing = spacing;
      coarse.size = size;
    }
  }
  return coarse;
}

bool has_light(const Scene& scene) {
  const auto positive = [](glm::vec3 c) { return glm::any(glm::greaterThan(c, glm::vec3(0.0f))); };
  if (!scene.lights.empty() || positive(scene.ambient) || scene.environment) return true;
  // A material emits only on the objects drawn with it.
  for (const Object& o : scene.objects)
    if (o.material < scene.materials.size() && positive(scene.materials[o.material].emissive))
      return true;
  return false;
}

bool is_mirroring(const glm::mat4& transform) {
  // In double, so that the sign is that of the determinant of the float matrix except within
  // rounding of singular (degenerate) transforms, whose triangles have no area anyway.
  return glm::determinant(glm::dmat3(glm::mat3(transform))) < 0.0;
}

glm::mat4 view_matrix(const Camera& camera) {
  return glm::lookAtRH(camera.position, camera.target, camera.up);
}

glm::mat4 projection_matrix(const Camera& camera, float aspect) {
  TESSERA_CHECK(aspect > 0.0f);
  // Any far plane works: clip.z is not used. One far enough not to cost precision in the
  // inverse used for camera rays.
  glm::mat4 p = glm::perspectiveRH_ZO(camera.vertical_fov, aspect, camera.near_plane,
                                      camera.near_plane * 1000.0f);
  p[1][1] = -p[1][1];  // Vulkan's NDC has y pointing down
  return p;
}

}  // namespace tessera
