#include "core/scene_file_write.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "core/check.h"
#include "core/environment.h"
#include "core/image.h"
#include "core/mesh.h"

namespace tessera {
namespace {

using Json = nlohmann::json;

// The shortest decimal that reads back as `f` (std::to_chars), held as the double it parses
// to, so that the JSON text is that short decimal and the reader's double -> float rounding
// gives f again.
Json num(float f) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof(text), f).ptr;
  *end = '\0';
  return std::strtod(text, nullptr);
}

Json vec(glm::vec3 v) {
  return Json::array({num(v.x), num(v.y), num(v.z)});
}

// Degrees that the reader's glm::radians (single precision) turns into `radians`: the plain
// conversion, or the first float within 16 ulps of it that converts exactly; the plain one if
// none does.
float degrees_for(float radians) {
  const float guess = float(double(radians) * 180.0 / 3.14159265358979323846);
  float up = guess, down = guess;
  for (int k = 0; k <= 16; ++k) {
    if (glm::radians(up) == radians) return up;
    if (glm::radians(down) == radians) return down;
    up = std::nextafter(up, INFINITY);
    down = std::nextafter(down, -INFINITY);
  }
  return guess;
}

[[noreturn]] void unwritable(const std::string& what) {
  throw Error("cannot save the scene: " + what);
}

void require_range(float v, float lo, float hi, const std::string& field) {
  if (!(v >= lo && v <= hi))
    unwritable(field + " = " + std::to_string(v) + " is outside the file format's [" +
               std::to_string(lo) + ", " + std::to_string(hi) + "]");
}

// The built-in shape equal to `mesh`, as its JSON declaration, or null.
Json builtin_shape(const Mesh& mesh) {
  const MeshShape shape = shape_of(mesh);
  switch (shape.kind) {
    case MeshShape::Kind::cube:
      return {{"type", "cube"}};
    case MeshShape::Kind::icosphere:
      return {{"type", "icosphere"}, {"level", shape.a}};
    case MeshShape::Kind::uv_sphere:
      return {{"type", "sphere"}, {"segments", shape.a}, {"rings", shape.b}};
    case MeshShape::Kind::plane:
      return {{"type", "plane"}, {"nx", shape.a}, {"ny", shape.b}};
    case MeshShape::Kind::none:
      break;
  }
  return nullptr;
}

Json mesh_json(const Mesh& mesh, const std::string& name) {
  Json j = builtin_shape(mesh);
  if (j.is_null()) {
    j = {{"type", "triangles"}};
    Json p = Json::array(), n = Json::array(), uv = Json::array(), t = Json::array();
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
      const glm::vec3 normal = mesh.normals[i];
      for (int k = 0; k < 3; ++k) {
        p.push_back(num(mesh.positions[i][k]));
        n.push_back(num(normal[k]));
      }
      const glm::vec2 texcoord = mesh.uvs.empty() ? glm::vec2(0.0f) : mesh.uvs[i];  // none: zero
      uv.push_back(num(texcoord.x));
      uv.push_back(num(texcoord.y));
    }
    for (const glm::vec4& tangent : mesh.tangents)
      for (int k = 0; k < 4; ++k) t.push_back(num(tangent[k]));
    j["positions"] = std::move(p);
    j["normals"] = std::move(n);
    j["uvs"] = std::move(uv);
    j["indices"] = mesh.indices;
    if (!mesh.tangents.empty()) j["tangents"] = std::move(t);
    if (!mesh.uvs1.empty()) {
      Json uv1 = Json::array();
      for (const glm::vec2& v : mesh.uvs1) {
        uv1.push_back(num(v.x));
        uv1.push_back(num(v.y));
      }
      j["uvs1"] = std::move(uv1);
    }
  }
  j["name"] = name;
  return j;
}

// The scene format's name of a wrap mode (docs/scene-format.md, textures).
const char* wrap_name(TextureWrap mode) {
  switch (mode) {
    case TextureWrap::clamp_to_edge:
      return "clamp_to_edge";
    case TextureWrap::mirrored_repeat:
      return "mirrored_repeat";
    case TextureWrap::repeat:
      break;
  }
  return "repeat";
}

Json material_json(const Material& m, const std::string& name,
                   const std::vector<std::string>& texture_names) {
  for (float c : {m.base_color.r, m.base_color.g, m.base_color.b})
    require_range(c, 0.0f, FLT_MAX, name + ".base_color");
  for (float c : {m.emissive.r, m.emissive.g, m.emissive.b})
    require_range(c, 0.0f, FLT_MAX, name + ".emissive");
  require_range(m.metallic, 0.0f, 1.0f, name + ".metallic");
  require_range(m.roughness, 0.0f, 1.0f, name + ".roughness");
  Json j = {{"name", name},
            {"base_color", vec(m.base_color)},
            {"metallic", num(m.metallic)},
            {"roughness", num(m.roughness)},
            {"emissive", vec(m.emissive)},
            {"occlusion", num(m.occlusion)},
            {"normal_scale", num(m.normal_scale)},
            {"double_sided", m.double_sided}};
  const std::tuple<const char*, uint32_t, uint32_t> maps[] = {
      {"base_color_map", m.base_color_map, TS_MAP_BASE_COLOR},
      {"metallic_roughness_map", m.metallic_roughness_map, TS_MAP_METALLIC_ROUGHNESS},
      {"normal_map", m.normal_map, TS_MAP_NORMAL},
      {"occlusion_map", m.occlusion_map, TS_MAP_OCCLUSION},
      {"emissive_map", m.emissive_map, TS_MAP_EMISSIVE}};
  for (const auto& [key, map, bit] : maps) {
    if (map != kNoTexture) j[key] = texture_names[map];
    if (m.uv1_maps & bit) j[std::string(key) + "_uv_set"] = 1;
  }
  return j;
}

Json light_json(const Light& l, size_t index) {
  const std::string name = "lights[" + std::to_string(index) + "]";
  const char* kinds[] = {"point", "spot", "directional"};
  const char* type = l.kind == LightKind::point  ? kinds[0]
                     : l.kind == LightKind::spot ? kinds[1]
                                                 : kinds[2];
  Json j = {{"type", type},
            {"position", vec(l.position)},
            {"color", vec(l.color)},
            {"intensity", num(l.intensity)},
            {"falloff", l.falloff == Falloff::classic ? "classic" : "inverse_square"},
            {"range", num(l.range)}};
  if (l.direction != glm::vec3(0.0f)) j["direction"] = vec(l.direction);
  if (l.attenuation != glm::vec3(0.0f)) j["attenuation"] = vec(l.attenuation);
  const float inner = degrees_for(l.inner_angle), outer = degrees_for(l.outer_angle);
  require_range(inner, 0.0f, 89.9f, name + ".inner_angle_degrees");
  require_range(outer, 0.0f, 89.9f, name + ".outer_angle_degrees");
  j["inner_angle_degrees"] = num(inner);
  j["outer_angle_degrees"] = num(outer);
  return j;
}

// The environment as "sky", "uniform" or a PFM file written at `pfm_path` (named in the file
// by `pfm_name`).
Json environment_json(const Environment& e, const std::string& pfm_path,
                      const std::string& pfm_name) {
  const ImageF& r = e.radiance;
  if (r.width >= 4 && r.width <= kMaxTextureSide && r.height == r.width / 2 &&
      make_sky_environment(r.width).radiance.pixels == r.pixels)
    return r.width == 512 ? Json("sky") : Json{{"type", "sky"}, {"width", r.width}};
  if (!r.pixels.empty()) {
    const Environment uniform = make_uniform_environment(glm::vec3(r.pixels[0]));
    if (uniform.radiance.width == r.width && uniform.radiance.height == r.height &&
        uniform.radiance.pixels == r.pixels)
      return {{"type", "uniform"}, {"radiance", vec(glm::vec3(r.pixels[0]))}};
  }
  write_hdr_image(pfm_path, r);
  return {{"type", "file"}, {"file", pfm_name}};
}

Json render_json(const RenderDefaults& r) {
  Json j = Json::object();
  if (r.width) j["width"] = *r.width;
  if (r.height) j["height"] = *r.height;
  if (r.exposure_ev) j["exposure_ev"] = num(*r.exposure_ev);
  if (r.tonemap) {
    const char* names[] = {"aces", "reinhard", "clamp"};
    j["tonemap"] = names[int(*r.tonemap)];
  }
  if (r.brdf) {
    j["brdf"] = *r.brdf == Brdf::classic    ? "classic"
                : *r.brdf == Brdf::filament ? "filament"
                                            : "blinn_phong";
  }
  if (r.energy_compensation) j["energy_compensation"] = *r.energy_compensation;
  if (r.view) {
    const char* names[] = {"shaded", "normal", "uv", "triangle", "object"};
    j["view"] = names[int(*r.view)];
  }
  return j;
}

}  // namespace

void save_scene_file(const Scene& scene, const std::string& path, const RenderDefaults* render,
                     const std::string& description) {
  validate_scene(scene);
  const std::filesystem::path file(path);
  const std::filesystem::path folder = file.parent_path();
  const std::string stem = file.stem().string();
  if (const std::string reason = unwritable_reason(path); !reason.empty())
    throw Error("cannot write the scene file '" + path + "': " + reason);
  const std::string temporary = path + ".tmp";
  if (const std::string reason = unwritable_reason(temporary); !reason.empty()) {
    throw Error("cannot write the scene file '" + path + "': its temporary file '" + temporary +
                "': " + reason);
  }
  // The texture and environment files this save creates, removed again if it fails (files that
  // were there before are overwritten, as a successful save would).
  std::vector<std::string> created;
  auto creates = [&created](const std::string& file) {
    std::error_code ec;
    if (!std::filesystem::exists(file, ec)) created.push_back(file);
    return file;
  };
  try {
    Json root = {{"version", 1}};
    if (!description.empty()) root["description"] = description;
    const Camera& c = scene.camera;
    const float fov = degrees_for(c.vertical_fov);
    require_range(fov, FLT_MIN, 179.0f, "camera.vertical_fov_degrees");
    root["camera"] = {{"position", vec(c.position)},
                      {"target", vec(c.target)},
                      {"up", vec(c.up)},
                      {"vertical_fov_degrees", num(fov)},
                      {"near", num(c.near_plane)}};

    std::vector<std::string> texture_names;
    Json textures = Json::array();
    for (size_t i = 0; i < scene.textures.size(); ++i) {
      const Texture& t = scene.textures[i];
      const std::string name = stem + "-texture-" + std::to_string(i) + ".png";
      write_png(creates((folder / name).string()), Image8{t.width, t.height, t.texels});
      texture_names.push_back("texture" + std::to_string(i));
      Json texture = {
          {"name", texture_names.back()}, {"type", "file"}, {"file", name}, {"srgb", t.srgb}};
      if (t.wrap_u != TextureWrap::repeat || t.wrap_v != TextureWrap::repeat)
        texture["wrap"] = Json::array({wrap_name(t.wrap_u), wrap_name(t.wrap_v)});
      textures.push_back(std::move(texture));
    }
    Json materials = Json::array();
    for (size_t i = 0; i < scene.materials.size(); ++i)
      materials.push_back(
          material_json(scene.materials[i], "material" + std::to_string(i), texture_names));
    Json meshes = Json::array();
    for (size_t i = 0; i < scene.meshes.size(); ++i)
      meshes.push_back(mesh_json(scene.meshes[i], "mesh" + std::to_string(i)));
    Json objects = Json::array();
    for (const Object& o : scene.objects) {
      Json matrix = Json::array();
      for (int k = 0; k < 16; ++k) matrix.push_back(num(o.transform[k / 4][k % 4]));
      objects.push_back({{"mesh", "mesh" + std::to_string(o.mesh)},
                         {"material", "material" + std::to_string(o.material)},
                         {"matrix", std::move(matrix)}});
    }
    Json lights = Json::array();
    for (size_t i = 0; i < scene.lights.size(); ++i)
      lights.push_back(light_json(scene.lights[i], i));
    root["textures"] = std::move(textures);
    root["materials"] = std::move(materials);
    root["meshes"] = std::move(meshes);
    root["objects"] = std::move(objects);
    root["lights"] = std::move(lights);
    if (scene.environment) {
      const std::string name = stem + "-environment.pfm";
      root["environment"] =
          environment_json(*scene.environment, creates((folder / name).string()), name);
    }
    root["background"] = vec(scene.background);
    root["ambient"] = vec(scene.ambient);
    if (render) root["render"] = render_json(*render);

    const std::string text = root.dump(1) + "\n";
    if (text.size() > SceneFileOptions{}.max_file_bytes) {
      unwritable("'" + path + "' would be " + std::to_string(text.size() >> 20) +
                 " MiB, over the " + std::to_string(SceneFileOptions{}.max_file_bytes >> 20) +
                 " MiB a scene file may have (large meshes are written inline)");
    }
    {
      errno = 0;
      std::ofstream out(temporary, std::ios::binary);
      out << text;
      out.close();
      if (!out) {
        const int code = errno;
        std::remove(temporary.c_str());
        throw Error("cannot write the scene file '" + path + "': writing '" + temporary +
                    "' failed: " + (code ? std::strerror(code) : "unknown error"));
      }
    }
    std::error_code error;
    std::filesystem::rename(temporary, path, error);
    if (error) {
      std::remove(temporary.c_str());
      throw Error("cannot write the scene file '" + path + "': " + error.message());
    }
  } catch (...) {
    for (const std::string& file : created) std::remove(file.c_str());
    throw;
  }
}

}  // namespace tessera
