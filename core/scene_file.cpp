#include "core/scene_file.h"

#include <algorithm>
#include <cctype>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <random>
#include <sstream>
#include <tuple>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>

#include "core/check.h"
#include "core/closest_name.h"
#include "core/json_places.h"
#include "core/mapped_file.h"
#include "core/materials.h"
#include "core/mesh.h"
#include "core/model_import.h"
#include "core/model_place.h"
#include "core/parallel.h"
#include "core/procedural_textures.h"

namespace tessera {
namespace {

// ordered_json keeps members in file order, so warnings come in the order a person reads.
using Json = nlohmann::ordered_json;

constexpr double kUnbounded = DBL_MAX;

// A value of the document with where it is: its JSON pointer (for the place index) and the
// path shown to people ("materials.gold.roughness").
struct Node {
  const Json* json;
  std::string pointer;
  std::string path;
};

// `v` normalized, or as it is when it is unit length already to within float rounding (as
// every normalized float vector is), so that the normals and directions save_scene_file writes
// read back bit for bit: normalizing again could move them by an ulp.
glm::vec3 unit_vector(glm::vec3 v) {
  const double length2 = glm::dot(glm::dvec3(v), glm::dvec3(v));
  return std::fabs(length2 - 1.0) <= 1e-6 ? v : glm::normalize(v);
}

std::string format_number(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.9g", v);
  return buffer;
}

const char* type_name(const Json& j) {
  switch (j.type()) {
    case Json::value_t::null:
      return "null";
    case Json::value_t::object:
      return "an object";
    case Json::value_t::array:
      return "an array";
    case Json::value_t::string:
      return "a string";
    case Json::value_t::boolean:
      return "a boolean";
    case Json::value_t::number_integer:
    case Json::value_t::number_unsigned:
      return "an integer";
    case Json::value_t::number_float:
      return "a number";
    default:
      return "something else";
  }
}

// A texture as declared; file textures are loaded once the materials say how they are used.
struct TextureDecl {
  Node node;
  std::string file;  // "" for procedural textures (already made)
  std::optional<bool> srgb;
  TextureWrap wrap_u = TextureWrap::repeat, wrap_v = TextureWrap::repeat;
};

// A model file's content, placed as a unit by each object that names it.
struct Model {
  std::vector<Object> objects;         // mesh and material indices already offset into the scene
  std::vector<Camera> cameras;         // the file's (glTF), in the model's frame
  size_t first_light = 0, lights = 0;  // its lights in out.scene.lights, in the model's frame
  std::string name;
  std::string where;                         // its place in the file, for messages
  std::optional<glm::mat4> first_placement;  // of its first instance, once an object places it
  // The model file as its messages name it, whether it is OBJ, where its meshes start in the
  // scene, and where its parts come from in it: validate_scene's limits are the scene's, so a
  // model breaks them only once placed, and the scene's message adds the model's place.
  std::string file;
  bool obj = false;
  uint32_t first_mesh = 0;
  ImportedPlaces places;
};

struct Reader {
  std::string file;  // as named in messages
  std::string base_dir;
  const SceneFileOptions& options;
  JsonPlaces places;
  SceneFile& out;
  std::map<std::string, uint32_t> texture_names, material_names, mesh_names, model_names;
  std::vector<TextureDecl> texture_decls;
  std::vector<Model> models;
  // Each "objects" entry's first object in out.scene.objects and its place, so that
  // validate_scene's "object K" can be traced to the entry that made it.
  std::vector<std::pair<size_t, std::string>> object_sources;
  // Each model instance's first object in out.scene.objects and its model.
  std::vector<std::pair<size_t, uint32_t>> model_instances;
  // The same for each "lights" entry's light and each model's lights (the model's place: its
  // file says how bright they are, its first object where they go), and the camera's place:
  // validate_scene names "light K" and "the camera".
  std::vector<std::pair<size_t, std::string>> light_sources;
  std::string camera_source;

  // The unknown-key warnings (also in out.warnings): an error thrown later carries them, as
  // such a key is often its cause.
  std::vector<std::string> unknown_keys;

  // Set for load_model_scene, whose scene text no one wrote: a place in it would mislead, and
  // the messages of a model's parts name the model file and their place in it already.
  bool model_only = false;

  std::string where(const Node& n, bool at_key = false) const {
    if (model_only) return "";
    const auto& index = at_key ? places.keys : places.values;
    const auto it = index.find(n.pointer);
    std::string s = file;
    if (it != index.end())
      s.append(":")
          .append(std::to_string(it->second.line))
          .append(":")
          .append(std::to_string(it->second.column));
    s.append(": ").append(n.path.empty() ? std::string_view("(top level)") : n.path).append(": ");
    return s;
  }
  [[noreturn]] void fail(const Node& n, const std::string& what) const {
    throw Error(where(n) + what);
  }

  Node child(const Node& n, const std::string& key) const {
    return {&(*n.json)[key], n.pointer + "/" + json_pointer_token(key),
            n.path.empty() ? key : n.path + "." + key};
  }
  // Array elements with a name are shown by it ("materials.gold"), others by index.
  Node element(const Node& n, size_t i) const {
    const Json& e = (*n.json)[i];
    std::string shown = n.path + "[" + std::to_string(i) + "]";
    if (e.is_object() && e.contains("name") && e["name"].is_string())
      shown = n.path + "." + e["name"].get<std::string>();
    return {&e, n.pointer + "/" + std::to_string(i), shown};
  }
  bool has(const Node& n, const char* key) const { return n.json->contains(key); }
  // The node at RFC 6901 JSON `pointer` below `n`, which holds it ("/objects/0/translation/1").
  Node node_at(Node n, const std::string& pointer) const {
    for (size_t at = 1; at <= pointer.size();) {
      const size_t end = std::min(pointer.find('/', at), pointer.size());
      std::string token;
      for (size_t i = at; i < end; ++i) {
        const bool escaped = pointer[i] == '~' && i + 1 < end;
        token += !escaped ? pointer[i] : pointer[++i] == '1' ? '/' : '~';
      }
      n = n.json->is_array() ? element(n, std::stoul(token)) : child(n, token);
      at = end + 1;
    }
    return n;
  }

  void expect(const Node& n, bool ok, const char* what) const {
    if (ok) return;
    // An array's length, which is what is wrong when the types are right ([0, 2] for [x, y, z]).
    const std::string found = n.json->is_array()
                                  ? "an array of " + std::to_string(n.json->size()) +
                                        (n.json->size() == 1 ? " element" : " elements")
                                  : type_name(*n.json);
    fail(n, std::string("must be ") + what + ", found " + found);
  }
  // Checks that `n` is an object and reports members not in `known` (warning; error if strict).
  void object(const Node& n, std::initializer_list<const char*> known) {
    expect(n, n.json->is_object(), "an object");
    for (const auto& [key, value] : n.json->items()) {
      bool found = false;
      for (const char* k : known) found = found || key == k;
      if (found) continue;
      const Node c = child(n, key);
      const std::string near = closest_name(key, known);
      const std::string message = where(c, true) + "unknown key '" + key + "'" +
                                  (near.empty() ? "" : ", did you mean '" + near + "'?");
      if (options.strict) throw Error(message + " (an error with --strict)");
      out.warnings.push_back(message + " (ignored)");
      unknown_keys.push_back(out.warnings.back());
    }
  }
  std::vector<Node> array(const Node& n) const {
    expect(n, n.json->is_array(), "an array");
    std::vector<Node> v;
    for (size_t i = 0; i < n.json->size(); ++i) v.push_back(element(n, i));
    return v;
  }

  double number(const Node& n, double lo, double hi, bool open_lo = false) const {
    expect(n, n.json->is_number(), "a number");
    const double d = n.json->get<double>();
    const bool below = open_lo ? !(d > lo) : !(d >= lo);
    if (below || d > hi) {
      const std::string v = format_number(d);
      if (hi == kUnbounded) fail(n, v + " must be " + (open_lo ? "> " : ">= ") + format_number(lo));
      fail(n, v + " is outside " + (open_lo ? "(" : "[") + format_number(lo) + ", " +
                  format_number(hi) + "]");
    }
    if (std::fabs(d) > FLT_MAX) fail(n, format_number(d) + " does not fit a 32-bit float");
    return d;
  }
  float real(const Node& n, double lo = -kUnbounded, double hi = kUnbounded,
             bool open_lo = false) const {
    return float(number(n, lo, hi, open_lo));
  }
  float real_or(const Node& n, const char* key, float fallback, double lo = -kUnbounded,
                double hi = kUnbounded, bool open_lo = false) const {
    return has(n, key) ? real(child(n, key), lo, hi, open_lo) : fallback;
  }
  uint64_t integer(const Node& n, uint64_t lo, uint64_t hi) const {
    expect(n, n.json->is_number(), "an integer");
    const double d = n.json->get<double>();
    if (!n.json->is_number_integer() && d != std::floor(d))
      fail(n, format_number(d) + " must be a whole number");
    if (n.json->is_number_unsigned() && n.json->get<uint64_t>() >= lo &&
        n.json->get<uint64_t>() <= hi)
      return n.json->get<uint64_t>();
    if (n.json->is_number_float() && d >= double(lo) && d <= double(hi)) return uint64_t(d);
    fail(n, (n.json->is_number_float() ? format_number(d) : n.json->dump()) + " is outside [" +
                std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
  uint32_t integer_or(const Node& n, const char* key, uint32_t fallback, uint32_t lo,
                      uint32_t hi) const {
    return has(n, key) ? uint32_t(integer(child(n, key), lo, hi)) : fallback;
  }
  std::string string(const Node& n) const {
    expect(n, n.json->is_string(), "a string");
    return n.json->get<std::string>();
  }
  bool boolean(const Node& n) const {
    expect(n, n.json->is_boolean(), "true or false");
    return n.json->get<bool>();
  }
  template <size_t N>
  glm::vec<N, float> vector(const Node& n, double lo = -kUnbounded, double hi = kUnbounded) const {
    expect(n, n.json->is_array() && n.json->size() == N,
           N == 2   ? "an array of 2 numbers"
           : N == 3 ? "an array of 3 numbers"
                    : "an array");
    glm::vec<N, float> v;
    for (size_t i = 0; i < N; ++i) v[i] = real(element(n, i), lo, hi);
    return v;
  }
  glm::vec3 vec3_or(const Node& n, const char* key, glm::vec3 fallback,
                    double lo = -kUnbounded) const {
    return has(n, key) ? vector<3>(child(n, key), lo) : fallback;
  }
  template <class E>
  E choice(const Node& n, std::initializer_list<std::pair<const char*, E>> options) const {
    // Names are spelt with '_' here and with '-' on the command line (blinn_phong,
    // --brdf blinn-phong); either is taken in both places.
    std::string s = string(n);
    std::replace(s.begin(), s.end(), '-', '_');
    std::string known;
    for (const auto& [name, value] : options) {
      if (s == name) return value;
      known += (known.empty() ? "" : ", ") + std::string(name);
    }
    fail(n, "'" + s + "' is not one of " + known);
  }
  // Registers `n`'s "name" in `names` with `index`; names are unique within their kind.
  std::string declare(const Node& n, std::map<std::string, uint32_t>& names, uint32_t index,
                      const char* kind) const {
    if (!has(n, "name")) fail(n, std::string("a ") + kind + " needs a \"name\"");
    const Node name_node = child(n, "name");
    const std::string name = string(name_node);
    if (name.empty()) fail(name_node, "the name is empty");
    if (!names.emplace(name, index).second)
      fail(name_node, std::string("a ") + kind + " named '" + name + "' is already declared");
    return name;
  }
  uint32_t lookup(const Node& n, const std::map<std::string, uint32_t>& names,
                  const char* kind) const {
    const std::string name = string(n);
    const auto it = names.find(name);
    if (it != names.end()) return it->second;
    std::string known;
    for (const auto& [k, v] : names) known += (known.empty() ? "" : ", ") + k;
    fail(n, std::string("no ") + kind + " named '" + name + "'" +
                (known.empty() ? std::string(" (none declared)") : " (declared: " + known + ")"));
  }
  // A file named by the scene: relative to the scene's folder, existing, within the size limit.
  std::string resolve(const Node& n) const {
    const std::string name = string(n);
    std::filesystem::path p(name);
    if (p.is_relative() && !base_dir.empty()) p = std::filesystem::path(base_dir) / p;
    try {
      require_regular_file(p.string());
    } catch (const Error& e) {
      fail(n, e.what());
    }
    std::error_code ec;
    const uint64_t bytes = std::filesystem::file_size(p, ec);
    if (ec) fail(n, "cannot read '" + p.string() + "': " + ec.message());
    if (bytes > options.max_model_bytes)
      fail(n, "'" + p.string() + "' is " + std::to_string(bytes) + " bytes, over the limit of " +
                  std::to_string(options.max_model_bytes));
    return p.string();
  }
  // Runs a loader of a file the scene names, giving its Error the place in the scene file.
  template <class F>
  auto loading(const Node& n, F&& load) const {
    try {
      return load();
    } catch (const Error& e) {
      fail(n, e.what());
    }
  }

  void add_objects(const Node& n, uint64_t count) const {
    if (count > options.max_objects || out.scene.objects.size() + count > options.max_objects)
      fail(n, "makes " + std::to_string(out.scene.objects.size() + count) +
                  " objects, over the limit of " + std::to_string(options.max_objects));
  }

  void read_camera(const Node& n);
  void read_light(const Node& n);
  void read_texture(const Node& n);
  std::pair<TextureWrap, TextureWrap> wrap_modes(const Node& n) const;
  void load_textures();
  void read_material(const Node& n);
  void read_mesh(const Node& n);
  void read_model(const Node& n);
  std::string model_camera_place(const Model& m, size_t camera) const;
  std::string in_model(const std::string& message) const;
  glm::mat4 read_transform(const Node& n) const;
  void read_objects(const Node& n);
  void read_environment(const Node& n);
  void read_render(const Node& n);
  void read(const Node& root);
};

void Reader::read_camera(const Node& n) {
  camera_source = where(n);
  object(n, {"position", "target", "up", "vertical_fov_degrees", "near"});
  Camera& c = out.scene.camera;
  c.position = vec3_or(n, "position", c.position);
  c.target = vec3_or(n, "target", c.target);
  c.up = vec3_or(n, "up", c.up);
  if (has(n, "vertical_fov_degrees"))
    c.vertical_fov = glm::radians(real(child(n, "vertical_fov_degrees"), 0.0, 179.0, true));
  c.near_plane = real_or(n, "near", c.near_plane, 0.0, kUnbounded, true);
  if (c.position == c.target) fail(n, "the camera's position and target are the same point");
  if (glm::length(glm::cross(c.target - c.position, c.up)) == 0.0f)
    fail(n, "the camera's up vector is zero or along its view direction");
}

void Reader::read_light(const Node& n) {
  light_sources.emplace_back(out.scene.lights.size(), where(n));
  object(n, {"name", "type", "position", "direction", "color", "intensity", "falloff", "range",
             "attenuation", "inner_angle_degrees", "outer_angle_degrees"});
  Light l;
  if (!has(n, "type")) fail(n, "a light needs a \"type\": point, spot or directional");
  l.kind = choice(child(n, "type"), {std::pair{"point", LightKind::point},
                                     {"spot", LightKind::spot},
                                     {"directional", LightKind::directional}});
  l.position = vec3_or(n, "position", l.position);
  if (has(n, "direction")) {
    const Node d = child(n, "direction");
    const glm::vec3 v = vector<3>(d);
    if (glm::dot(v, v) == 0.0f || !std::isfinite(glm::dot(v, v)))
      fail(d, "a direction must be non-zero (and not so long that its length overflows)");
    l.direction = unit_vector(v);
  }
  l.color = vec3_or(n, "color", l.color, 0.0);
  l.intensity = real_or(n, "intensity", l.intensity, 0.0);
  if (has(n, "falloff"))
    l.falloff = choice(child(n, "falloff"), {std::pair{"inverse_square", Falloff::inverse_square},
                                             {"classic", Falloff::classic}});
  l.range = real_or(n, "range", l.range, 0.0);
  if (has(n, "attenuation")) {
    const Node a = child(n, "attenuation");
    l.attenuation = vector<3>(a, 0.0);
    if (l.attenuation == glm::vec3(0.0f)) fail(a, "Kc, Kl and Kq are all 0");
  }
  // In degrees as the file gives them (the defaults' for those it does not), for the message.
  double inner_degrees = std::round(glm::degrees(double(l.inner_angle)) * 1e4) / 1e4;
  double outer_degrees = std::round(glm::degrees(double(l.outer_angle)) * 1e4) / 1e4;
  if (has(n, "inner_angle_degrees")) {
    inner_degrees = real(child(n, "inner_angle_degrees"), 0.0, 89.9);
    l.inner_angle = glm::radians(float(inner_degrees));
  }
  if (has(n, "outer_angle_degrees")) {
    outer_degrees = real(child(n, "outer_angle_degrees"), 0.0, 89.9);
    l.outer_angle = glm::radians(float(outer_degrees));
  }
  if (l.inner_angle > l.outer_angle) {
    // Placed at the angle the file gives (the inner one if both).
    fail(child(n, has(n, "inner_angle_degrees") ? "inner_angle_degrees" : "outer_angle_degrees"),
         "the inner angle (" + format_number(inner_degrees) +
             " degrees) is larger than the outer angle (" + format_number(outer_degrees) +
             " degrees)");
  }
  out.scene.lights.push_back(l);
}

// "wrap": one mode for both axes, or [u, v].
std::pair<TextureWrap, TextureWrap> Reader::wrap_modes(const Node& n) const {
  if (!has(n, "wrap")) return {TextureWrap::repeat, TextureWrap::repeat};
  const Node w = child(n, "wrap");
  auto mode = [&](const Node& m) {
    return choice(m, {std::pair{"repeat", TextureWrap::repeat},
                      {"clamp_to_edge", TextureWrap::clamp_to_edge},
                      {"mirrored_repeat", TextureWrap::mirrored_repeat}});
  };
  if (w.json->is_string()) return {mode(w), mode(w)};
  expect(w, w.json->is_array() && w.json->size() == 2, "a wrap mode or an array of 2 (u, v)");
  return {mode(element(w, 0)), mode(element(w, 1))};
}

void Reader::read_texture(const Node& n) {
  object(n, {"name", "type", "file", "srgb", "size", "cells", "color_a", "color_b", "tiles",
             "color", "strength", "wrap"});
  const auto [wrap_u, wrap_v] = wrap_modes(n);
  const size_t first_new = out.scene.textures.size();
  const uint32_t index = uint32_t(out.scene.textures.size());
  const std::string name = declare(n, texture_names, index, "texture");
  if (!has(n, "type")) fail(n, "a texture needs a \"type\": file, checker or tiles");
  const Node type = child(n, "type");
  const int kind = choice(type, {std::pair{"file", 0}, {"checker", 1}, {"tiles", 2}});
  const uint32_t side = options.max_texture_side;
  if (kind == 0) {
    if (!has(n, "file")) fail(n, "a file texture needs a \"file\"");
    TextureDecl d{n, resolve(child(n, "file")), std::nullopt, wrap_u, wrap_v};
    if (has(n, "srgb")) d.srgb = boolean(child(n, "srgb"));
    texture_decls.push_back(d);
    out.scene.textures.emplace_back();  // loaded by load_textures
  } else if (kind == 1) {
    const uint32_t size = integer_or(n, "size", 256, 1, side);
    const uint32_t cells = integer_or(n, "cells", 8, 1, size);
    out.scene.textures.push_back(make_checker_texture(
        size, cells, vec3_or(n, "color_a", {1, 1, 1}, 0.0), vec3_or(n, "color_b", {0, 0, 0}, 0.0)));
    texture_decls.push_back({n, "", true});
  } else {
    // make_tile_maps' smallest side: refused here, at its place, rather than by it, unplaced.
    const uint32_t size = integer_or(n, "size", 512, 4, side);
    TileMaps maps = make_tile_maps(size, integer_or(n, "tiles", 8, 1, size),
                                   vec3_or(n, "color", {0.75f, 0.45f, 0.3f}, 0.0),
                                   real_or(n, "strength", 1.0f, 0.0, 100.0));
    // One declaration, four maps: NAME.base_color, .metallic_roughness, .normal, .occlusion.
    texture_names.erase(name);
    const char* suffixes[] = {".base_color", ".metallic_roughness", ".normal", ".occlusion"};
    Texture* textures[] = {&maps.base_color, &maps.metallic_roughness, &maps.normal,
                           &maps.occlusion};
    for (int i = 0; i < 4; ++i) {
      texture_names[name + suffixes[i]] = uint32_t(out.scene.textures.size());
      out.scene.textures.push_back(std::move(*textures[i]));
      texture_decls.push_back({n, "", std::nullopt});
    }
  }
  for (size_t i = first_new; i < out.scene.textures.size(); ++i) {
    out.scene.textures[i].wrap_u = wrap_u;
    out.scene.textures[i].wrap_v = wrap_v;
  }
}

// File textures are sRGB where a material uses them as colour (base colour or emission),
// linear (data) otherwise,
// unless the file says "srgb".
void Reader::load_textures() {
  std::vector<bool> colour(out.scene.textures.size(), false);
  for (const Material& m : out.scene.materials)
    for (uint32_t map : {m.base_color_map, m.emissive_map})
      if (map != kNoTexture) colour[map] = true;
  // Decoded in parallel on every core; the first failure in file order is the one reported.
  std::vector<std::exception_ptr> failed(texture_decls.size());
  std::vector<Texture> decoded(texture_decls.size());
  parallel_for(texture_decls.size(), [&](size_t i) {
    const TextureDecl& d = texture_decls[i];
    if (d.file.empty()) return;
    try {
      decoded[i] = load_texture(d.file, d.srgb.value_or(colour[i]));
    } catch (const Error&) {
      failed[i] = std::current_exception();
    }
  });
  for (size_t i = 0; i < texture_decls.size(); ++i) {
    const TextureDecl& d = texture_decls[i];
    if (d.file.empty()) continue;
    out.scene.textures[i] = loading(child(d.node, "file"), [&] {
      if (failed[i]) std::rethrow_exception(failed[i]);
      Texture t = std::move(decoded[i]);
      t.wrap_u = d.wrap_u;
      t.wrap_v = d.wrap_v;
      if (t.width > options.max_texture_side || t.height > options.max_texture_side)
        throw Error(d.file + " is " + std::to_string(t.width) + "x" + std::to_string(t.height) +
                    ", over the largest side of " + std::to_string(options.max_texture_side));
      return t;
    });
  }
}

void Reader::read_material(const Node& n) {
  object(n,
         {"name", "preset", "base_color", "metallic", "roughness", "emissive", "occlusion",
          "normal_scale", "base_color_map", "metallic_roughness_map", "normal_map", "occlusion_map",
          "emissive_map", "base_color_map_uv_set", "metallic_roughness_map_uv_set",
          "normal_map_uv_set", "occlusion_map_uv_set", "emissive_map_uv_set", "double_sided"});
  declare(n, material_names, uint32_t(out.scene.materials.size()), "material");
  Material m;
  if (has(n, "preset")) {
    const Node p = child(n, "preset");
    const MetalPreset* preset = find_metal_preset(string(p));
    if (!preset) {
      std::string known;
      for (const MetalPreset& k : metal_presets())
        known += (known.empty() ? "" : ", ") + std::string(k.name);
      fail(p, "no metal preset named '" + string(p) + "' (presets: " + known + ")");
    }
    if (has(n, "base_color")) fail(p, "give either a preset or a base_color, not both");
    m.base_color = preset->f0;
    m.metallic = 1.0f;
  }
  m.base_color = vec3_or(n, "base_color", m.base_color, 0.0);
  m.metallic = real_or(n, "metallic", m.metallic, 0.0, 1.0);
  m.roughness = real_or(n, "roughness", m.roughness, 0.0, 1.0);
  m.emissive = vec3_or(n, "emissive", m.emissive, 0.0);
  m.occlusion = real_or(n, "occlusion", m.occlusion, 0.0, 1.0);
  m.normal_scale = real_or(n, "normal_scale", m.normal_scale);
  const std::tuple<const char*, uint32_t*, uint32_t> maps[] = {
      {"base_color_map", &m.base_color_map, TS_MAP_BASE_COLOR},
      {"metallic_roughness_map", &m.metallic_roughness_map, TS_MAP_METALLIC_ROUGHNESS},
      {"normal_map", &m.normal_map, TS_MAP_NORMAL},
      {"occlusion_map", &m.occlusion_map, TS_MAP_OCCLUSION},
      {"emissive_map", &m.emissive_map, TS_MAP_EMISSIVE}};
  for (const auto& [key, slot, bit] : maps) {
    if (has(n, key)) *slot = lookup(child(n, key), texture_names, "texture");
    // The uv set the map reads: 0 (the mesh's "uvs") or 1 ("uvs1").
    const std::string set_key = std::string(key) + "_uv_set";
    if (integer_or(n, set_key.c_str(), 0, 0, 1) == 1) m.uv1_maps |= bit;
  }
  if (has(n, "double_sided")) m.double_sided = boolean(child(n, "double_sided"));
  out.scene.materials.push_back(m);
}

void Reader::read_mesh(const Node& n) {
  object(n, {"name", "type", "segments", "rings", "level", "nx", "ny", "positions", "normals",
             "uvs", "uvs1", "indices", "tangents"});
  declare(n, mesh_names, uint32_t(out.scene.meshes.size()), "mesh");
  if (!has(n, "type"))
    fail(n, "a mesh needs a \"type\": sphere, icosphere, cube, plane or triangles");
  const int kind = choice(
      child(n, "type"),
      {std::pair{"sphere", 0}, {"icosphere", 1}, {"cube", 2}, {"plane", 3}, {"triangles", 4}});
  const uint64_t max_vertices = options.max_mesh_vertices;
  auto check_vertices = [&](uint64_t vertices) {
    if (vertices > max_vertices)
      fail(n, "would have " + std::to_string(vertices) + " vertices, over the limit of " +
                  std::to_string(max_vertices));
  };
  Mesh mesh;
  if (kind == 0) {
    const uint32_t segments = integer_or(n, "segments", 64, 3, 1u << 20);
    const uint32_t rings = integer_or(n, "rings", std::max(2u, segments / 2), 2, 1u << 20);
    check_vertices(uint64_t(segments + 1) * (rings + 1));
    mesh = make_uv_sphere(segments, rings);
  } else if (kind == 1) {
    mesh = make_icosphere(integer_or(n, "level", 3, 0, 8));
  } else if (kind == 2) {
    mesh = make_cube();
  } else if (kind == 3) {
    const uint32_t nx = integer_or(n, "nx", 1, 1, 1u << 20),
                   ny = integer_or(n, "ny", 1, 1, 1u << 20);
    check_vertices(uint64_t(nx + 1) * (ny + 1));
    mesh = make_plane(nx, ny);
  } else {
    for (const char* key : {"positions", "normals", "uvs", "indices"})
      if (!has(n, key)) fail(n, std::string("a triangles mesh needs \"") + key + "\"");
    auto flat = [&](const char* key, size_t width) {
      const Node a = child(n, key);
      expect(a, a.json->is_array(), "an array of numbers");
      if (a.json->size() % width != 0)
        fail(a, std::to_string(a.json->size()) + " numbers are not a multiple of " +
                    std::to_string(width));
      check_vertices(a.json->size() / width);
      return a;
    };
    const Node p = flat("positions", 3), nn = flat("normals", 3), uv = flat("uvs", 2);
    const size_t vertices = p.json->size() / 3;
    if (nn.json->size() / 3 != vertices || uv.json->size() / 2 != vertices)
      fail(n, "positions, normals and uvs must give the same number of vertices (" +
                  std::to_string(vertices) + ", " + std::to_string(nn.json->size() / 3) + ", " +
                  std::to_string(uv.json->size() / 2) + ")");
    for (size_t i = 0; i < vertices; ++i) {
      glm::vec3 pos, nor;
      for (int k = 0; k < 3; ++k) {
        pos[k] = real(element(p, 3 * i + k));
        nor[k] = real(element(nn, 3 * i + k));
      }
      if (glm::dot(nor, nor) == 0.0f)
        fail(element(nn, 3 * i), "normal " + std::to_string(i) + " is zero");
      mesh.positions.push_back(pos);
      mesh.normals.push_back(unit_vector(nor));
      mesh.uvs.push_back({real(element(uv, 2 * i)), real(element(uv, 2 * i + 1))});
    }
    if (has(n, "uvs1")) {
      const Node uv1 = flat("uvs1", 2);
      if (uv1.json->size() / 2 != vertices)
        fail(uv1, "uvs1 gives " + std::to_string(uv1.json->size() / 2) + " vertices, positions " +
                      std::to_string(vertices));
      for (size_t i = 0; i < vertices; ++i)
        mesh.uvs1.push_back({real(element(uv1, 2 * i)), real(element(uv1, 2 * i + 1))});
    }
    const Node ix = child(n, "indices");
    expect(ix, ix.json->is_array(), "an array of integers");
    if (ix.json->size() % 3 != 0)
      fail(ix, std::to_string(ix.json->size()) + " indices are not a multiple of 3");
    for (size_t i = 0; i < ix.json->size(); ++i) {
      const Node e = element(ix, i);
      if (vertices == 0) fail(e, "an index, but the mesh has no vertices");
      mesh.indices.push_back(uint32_t(integer(e, 0, vertices - 1)));
    }
    if (has(n, "tangents")) {
      // Taken as written (saved meshes keep their imported or generated frames exactly);
      // validate_scene checks them.
      const Node t = flat("tangents", 4);
      if (t.json->size() / 4 != vertices)
        fail(t, std::to_string(t.json->size() / 4) + " tangents for " + std::to_string(vertices) +
                    " vertices");
      for (size_t i = 0; i < vertices; ++i) {
        glm::vec4 v;
        for (int k = 0; k < 4; ++k) v[k] = real(element(t, 4 * i + k));
        mesh.tangents.push_back(v);
      }
    }
  }
  out.scene.meshes.push_back(std::move(mesh));
}

void Reader::read_model(const Node& n) {
  object(n, {"name", "file"});
  declare(n, model_names, uint32_t(models.size()), "model");
  if (!has(n, "file")) fail(n, "a model needs a \"file\" (.gltf, .glb or .obj)");
  const Node f = child(n, "file");
  const std::string path = resolve(f);
  const std::string ext = model_extension(path);
  ImportOptions io;
  io.strict = options.strict;
  io.max_file_bytes = options.max_model_bytes;
  io.max_texture_side = options.max_texture_side;
  ImportedModel model = loading(f, [&] {
    if (ext == ".gltf" || ext == ".glb") return import_gltf(path, io);
    if (ext == ".obj") return import_obj(path, io);
    throw Error(path + ": unknown model format '" +
                std::filesystem::path(path).extension().string() +
                "' (.gltf, .glb or .obj, in either case)");
  });
  for (const std::string& w : model.warnings) out.warnings.push_back(where(f) + w);
  Scene& s = out.scene;
  const uint32_t meshes = uint32_t(s.meshes.size()), materials = uint32_t(s.materials.size()),
                 textures = uint32_t(s.textures.size());
  for (Material m : model.scene.materials) {
    for (uint32_t* map : {&m.base_color_map, &m.metallic_roughness_map, &m.normal_map,
                          &m.occlusion_map, &m.emissive_map})
      if (*map != kNoTexture) *map += textures;
    s.materials.push_back(m);
  }
  for (Mesh& m : model.scene.meshes) s.meshes.push_back(std::move(m));
  for (Texture& t : model.scene.textures) s.textures.push_back(std::move(t));
  Model placed;
  placed.first_light = s.lights.size();
  placed.lights = model.scene.lights.size();
  if (placed.lights > 0) light_sources.emplace_back(placed.first_light, where(n));
  for (const Light& l : model.scene.lights) s.lights.push_back(l);
  placed.cameras = model.cameras;
  placed.name = string(child(n, "name"));
  placed.where = where(n);
  placed.file = path;
  placed.obj = ext == ".obj";
  placed.first_mesh = meshes;
  placed.places = std::move(model.places);
  for (Object o : model.scene.objects) {
    o.mesh += meshes;
    o.material += materials;
    placed.objects.push_back(o);
  }
  models.push_back(std::move(placed));
}

std::string Reader::model_camera_place(const Model& m, size_t camera) const {
  if (camera >= m.places.cameras.size()) return "";
  const auto& [node, path] = m.places.cameras[camera];
  return model_file_place(m.file, m.obj, node.empty() ? path : node + " (" + path + ")");
}

// validate_scene's `message` about an object or light that a model brought, with the model
// file's place of it (model_part_message), after the scene file's place, which the caller adds;
// "" for the scene file's own.
std::string Reader::in_model(const std::string& message) const {
  const auto in = [&](const Model& m, size_t first_object, size_t objects) {
    return ModelInScene{m.file,  m.obj,        &m.places,     first_object,
                        objects, m.first_mesh, m.first_light, m.lights};
  };
  const std::string prefix = "invalid scene: object ";
  if (message.rfind(prefix, 0) == 0) {
    // The model instance that made object K.
    const size_t k = std::strtoull(message.c_str() + prefix.size(), nullptr, 10);
    const auto it = std::upper_bound(
        model_instances.begin(), model_instances.end(), k,
        [](size_t v, const std::pair<size_t, uint32_t>& i) { return v < i.first; });
    if (it == model_instances.begin()) return "";
    const auto [first, model] = *std::prev(it);
    return model_part_message(out.scene, in(models[model], first, models[model].objects.size()),
                              message);
  }
  for (const Model& m : models)
    if (std::string s = model_part_message(out.scene, in(m, 0, 0), message); !s.empty()) return s;
  return "";
}

// translation, rotation (axis-angle in degrees, or a list applied left to right), scale
// (number or per axis, negative mirrors), composed T * R * S; or a column-major "matrix".
glm::mat4 Reader::read_transform(const Node& n) const {
  if (has(n, "matrix")) {
    const Node m = child(n, "matrix");
    for (const char* key : {"translation", "rotation", "scale"})
      if (has(n, key)) fail(m, std::string("give either a matrix or ") + key + ", not both");
    expect(m, m.json->is_array() && m.json->size() == 16, "an array of 16 numbers (column-major)");
    glm::mat4 t;
    for (int i = 0; i < 16; ++i) glm::value_ptr(t)[i] = real(element(m, i));
    // glm's t[column][row]: the last row is each column's fourth number.
    if (t[0][3] != 0.0f || t[1][3] != 0.0f || t[2][3] != 0.0f || t[3][3] != 1.0f) {
      fail(m, "is not affine: its last row is (" + std::to_string(t[0][3]) + ", " +
                  std::to_string(t[1][3]) + ", " + std::to_string(t[2][3]) + ", " +
                  std::to_string(t[3][3]) +
                  "), not (0, 0, 0, 1) (the 16 numbers go column by column: is it row-major?)");
    }
    // As a scale of 0 (below), in double: a float determinant of a tiny scale underflows.
    if (glm::determinant(glm::dmat3(glm::mat3(t))) == 0.0)
      fail(m, "flattens the object (its upper 3x3 part has determinant 0)");
    return t;
  }
  glm::mat4 t(1.0f);
  if (has(n, "translation")) t = glm::translate(t, vector<3>(child(n, "translation")));
  if (has(n, "rotation")) {
    const Node r = child(n, "rotation");
    std::vector<Node> rotations = r.json->is_array() ? array(r) : std::vector<Node>{r};
    for (const Node& one : rotations) {
      expect(one, one.json->is_object(), "an object {\"axis\": [x, y, z], \"degrees\": a}");
      for (const char* key : {"axis", "degrees"})
        if (!one.json->contains(key)) fail(one, std::string("a rotation needs \"") + key + "\"");
      const glm::vec3 axis = vector<3>(child(one, "axis"));
      if (glm::dot(axis, axis) == 0.0f) fail(child(one, "axis"), "the rotation axis is zero");
      t = glm::rotate(t, glm::radians(real(child(one, "degrees"))), axis);
    }
  }
  if (has(n, "scale")) {
    const Node s = child(n, "scale");
    const glm::vec3 v = s.json->is_number() ? glm::vec3(real(s)) : vector<3>(s);
    if (v.x == 0.0f || v.y == 0.0f || v.z == 0.0f) fail(s, "a scale of 0 flattens the object");
    t = glm::scale(t, v);
  }
  return t;
}

void Reader::read_objects(const Node& list) {
  for (const Node& n : array(list)) {
    object_sources.emplace_back(out.scene.objects.size(), where(n));
    object(n, {"name", "mesh", "model", "material", "materials", "tile_columns", "translation",
               "rotation", "scale", "matrix", "grid", "random"});
    const bool is_model = has(n, "model");
    if (is_model && has(n, "mesh")) fail(n, "give either a \"mesh\" or a \"model\", not both");
    if (!is_model && !has(n, "mesh")) fail(n, "an object needs either a \"mesh\" or a \"model\"");
    // Said before any material is looked up: a model's object names none.
    if (is_model && (has(n, "material") || has(n, "materials")))
      fail(child(n, has(n, "material") ? "material" : "materials"),
           "a model brings its own materials");
    uint32_t mesh = 0, model = 0;
    if (is_model)
      model = lookup(child(n, "model"), model_names, "model");
    else
      mesh = lookup(child(n, "mesh"), mesh_names, "mesh");
    std::vector<uint32_t> materials;
    if (has(n, "material")) {
      if (has(n, "materials")) fail(child(n, "materials"), "give either material or materials");
      materials.push_back(lookup(child(n, "material"), material_names, "material"));
    } else if (has(n, "materials")) {
      for (const Node& m : array(child(n, "materials")))
        materials.push_back(lookup(m, material_names, "material"));
      if (materials.empty()) fail(child(n, "materials"), "the list is empty");
      if (materials.size() > 1 && !has(n, "grid") && !has(n, "random") && !has(n, "tile_columns"))
        fail(child(n, "materials"), "lists " + std::to_string(materials.size()) +
                                        " materials for a generator's instances, and this "
                                        "object has no \"grid\" or \"random\"");
    }
    if (!is_model && materials.empty())
      fail(n, "an object with a mesh needs a \"material\" (or \"materials\" for a generator)");
    if (is_model && !materials.empty())
      fail(child(n, has(n, "material") ? "material" : "materials"),
           "a model brings its own materials");
    const glm::mat4 placement = read_transform(n);
    const bool moved =
        has(n, "translation") || has(n, "rotation") || has(n, "scale") || has(n, "matrix");

    // Adds one instance at `local` (inside the entry's placement) with palette entry `pick`.
    auto add = [&](const glm::mat4& local, uint32_t pick) {
      const glm::mat4 world = moved ? placement * local : local;
      if (is_model) {
        if (!models[model].first_placement) models[model].first_placement = world;
        model_instances.emplace_back(out.scene.objects.size(), model);
        for (Object o : models[model].objects) {
          o.transform = world * o.transform;
          out.scene.objects.push_back(o);
        }
      } else {
        out.scene.objects.push_back({mesh, materials[pick % materials.size()], world});
      }
    };
    const uint64_t per_instance = is_model ? std::max<size_t>(1, models[model].objects.size()) : 1;
    if (has(n, "grid") && has(n, "random")) fail(n, "give either grid or random, not both");
    if (has(n, "tile_columns") && (is_model || !has(n, "grid")))
      fail(child(n, "tile_columns"),
           is_model ? "lays out a grid's materials, and a model brings its own"
                    : "lays out a grid's materials, and this object has no \"grid\"");
    if (has(n, "grid")) {
      const Node g = child(n, "grid");
      object(g, {"count", "spacing", "limit", "instance_scale"});
      if (!has(g, "count")) fail(g, "a grid needs a \"count\": [nx, ny, nz]");
      const Node c = child(g, "count");
      expect(c, c.json->is_array() && c.json->size() == 3, "an array of 3 integers");
      uint64_t count[3];
      uint64_t cells = 1;
      for (size_t i = 0; i < 3; ++i) {
        count[i] = integer(element(c, i), 1, UINT32_MAX);
        if (__builtin_mul_overflow(cells, count[i], &cells))
          fail(c, "the cell count overflows 64 bits");
      }
      uint64_t total = cells;
      if (has(g, "limit")) {
        const Node l = child(g, "limit");
        total = integer(l, 1, UINT64_MAX);
        if (total > cells)
          fail(l, "keeps the first " + std::to_string(total) + " cells, more than the grid's " +
                      std::to_string(cells));
      }
      uint64_t objects = 0;
      if (__builtin_mul_overflow(total, per_instance, &objects))
        fail(c, "the object count overflows 64 bits");
      add_objects(c, objects);
      glm::vec3 spacing(1.0f);
      if (has(g, "spacing")) {
        const Node s = child(g, "spacing");
        spacing = s.json->is_number() ? glm::vec3(real(s)) : vector<3>(s);
      }
      const bool scaled = has(g, "instance_scale");
      const float instance_scale = real_or(g, "instance_scale", 1.0f, 0.0, kUnbounded, true);
      uint32_t tile = 0;
      if (has(n, "tile_columns")) {
        const Node t = child(n, "tile_columns");
        tile = uint32_t(integer(t, 1, materials.size()));
        if (materials.size() % tile != 0)
          fail(t, std::to_string(materials.size()) + " materials do not make rows of " +
                      std::to_string(tile));
      }
      for (uint64_t i = 0; i < total; ++i) {
        const uint64_t ix = i % count[0], iy = i / count[0] % count[1],
                       iz = i / (count[0] * count[1]);
        // The centred layout of the benchmark grid (core/bench_scenes.cpp), in its float
        // arithmetic, so that a file reproduces it bit for bit.
        const glm::vec3 p((float(ix) - float(count[0] - 1) / 2.0f) * spacing.x,
                          (float(iy) - float(count[1] - 1) / 2.0f) * spacing.y,
                          (float(iz) - float(count[2] - 1) / 2.0f) * spacing.z);
        glm::mat4 local = glm::translate(glm::mat4(1.0f), p);
        if (scaled) local = glm::scale(local, glm::vec3(instance_scale));
        const uint64_t rows = tile ? materials.size() / tile : 1;
        // A model's instances take no palette entry (it brings its own materials).
        if (materials.empty())
          add(local, 0);
        else
          add(local, uint32_t(tile ? (iy % rows) * tile + ix % tile : i % materials.size()));
      }
    } else if (has(n, "random")) {
      const Node r = child(n, "random");
      object(r, {"count", "seed", "min", "max", "scale"});
      for (const char* key : {"count", "min", "max"})
        if (!has(r, key)) fail(r, std::string("a random generator needs \"") + key + "\"");
      const Node c = child(r, "count");
      const uint64_t count = integer(c, 1, UINT64_MAX);
      uint64_t objects = 0;
      if (__builtin_mul_overflow(count, per_instance, &objects))
        fail(c, "the object count overflows 64 bits");
      add_objects(c, objects);
      std::mt19937 rng(uint32_t(has(r, "seed") ? integer(child(r, "seed"), 0, UINT32_MAX) : 0));
      const glm::vec3 lo = vector<3>(child(r, "min")), hi = vector<3>(child(r, "max"));
      for (int k = 0; k < 3; ++k) {
        if (lo[k] > hi[k]) {
          fail(child(r, "max"), std::string("is below \"min\" on ") + "xyz"[k] + " (min " +
                                    format_number(lo[k]) + ", max " + format_number(hi[k]) + ")");
        }
      }
      glm::vec2 scale(1.0f);
      bool scaled = false;
      if (has(r, "scale")) {
        const Node s = child(r, "scale");
        scale = s.json->is_number() ? glm::vec2(real(s, 0.0, kUnbounded, true)) : vector<2>(s, 0.0);
        if (!(scale.x > 0.0f) || scale.x > scale.y) fail(s, "needs 0 < low <= high");
        scaled = true;
      }
      for (uint64_t i = 0; i < count; ++i) {
        glm::vec3 p;
        for (int k = 0; k < 3; ++k) p[k] = lo[k] + (hi[k] - lo[k]) * uniform_float(rng());
        glm::mat4 local = glm::translate(glm::mat4(1.0f), p);
        if (scaled)
          local =
              glm::scale(local, glm::vec3(scale.x + (scale.y - scale.x) * uniform_float(rng())));
        add(local, materials.size() > 1 ? uint32_t(rng() % materials.size()) : 0);
      }
    } else {
      add_objects(n, per_instance);
      add(glm::mat4(1.0f), 0);
    }
  }
}

void Reader::read_environment(const Node& n) {
  if (n.json->is_string()) {
    if (string(n) != "sky") fail(n, "'" + string(n) + "' is not \"sky\" (or give an object)");
    out.scene.environment = std::make_shared<const Environment>(make_sky_environment());
    return;
  }
  object(n, {"type", "width", "file", "radiance"});
  if (!has(n, "type")) fail(n, "an environment needs a \"type\": sky, file or uniform");
  const int kind = choice(child(n, "type"), {std::pair{"sky", 0}, {"file", 1}, {"uniform", 2}});
  Environment e;
  if (kind == 0) {
    e = make_sky_environment(integer_or(n, "width", 512, 4, options.max_texture_side));
  } else if (kind == 1) {
    if (!has(n, "file")) fail(n, "a file environment needs a \"file\" (.hdr or .pfm)");
    const Node f = child(n, "file");
    const std::string path = resolve(f);
    e = loading(f, [&] { return load_environment(path); });
  } else {
    e = make_uniform_environment(vec3_or(n, "radiance", glm::vec3(1.0f), 0.0));
  }
  out.scene.environment = std::make_shared<const Environment>(std::move(e));
}

void Reader::read_render(const Node& n) {
  object(n, {"width", "height", "exposure_ev", "tonemap", "brdf", "energy_compensation", "view"});
  RenderDefaults& r = out.render;
  if (has(n, "width")) r.width = uint32_t(integer(child(n, "width"), 1, 16384));
  if (has(n, "height")) r.height = uint32_t(integer(child(n, "height"), 1, 16384));
  if (r.width || r.height) r.size_place = where(n);
  if (has(n, "exposure_ev")) r.exposure_ev = real(child(n, "exposure_ev"), -64.0, 64.0);
  if (has(n, "tonemap"))
    r.tonemap = choice(child(n, "tonemap"), {std::pair{"aces", ToneMap::aces},
                                             {"reinhard", ToneMap::reinhard},
                                             {"clamp", ToneMap::clamp}});
  if (has(n, "brdf"))
    r.brdf = choice(child(n, "brdf"), {std::pair{"classic", Brdf::classic},
                                       {"filament", Brdf::filament},
                                       {"blinn_phong", Brdf::blinn_phong}});
  if (has(n, "energy_compensation"))
    r.energy_compensation = boolean(child(n, "energy_compensation"));
  if (has(n, "view"))
    r.view = choice(child(n, "view"), {std::pair{"shaded", View::shaded},
                                       {"normal", View::normal},
                                       {"uv", View::uv},
                                       {"triangle", View::triangle},
                                       {"object", View::object}});
}

void Reader::read(const Node& root) {
  object(root, {"version", "description", "camera", "lights", "textures", "materials", "meshes",
                "models", "objects", "environment", "background", "ambient", "render"});
  if (has(root, "version")) {
    // "2 is outside [1, 1]" read oddly for the one format there is.
    const Node version = child(root, "version");
    if (version.json->is_number() && version.json->get<double>() != 1.0)
      fail(version, "format version " + version.json->dump() +
                        " is not one this Tessera reads (version 1 only)");
    integer(version, 1, 1);
  }
  if (has(root, "description")) out.description = string(child(root, "description"));
  // Declarations before uses: textures, materials, meshes, models, then objects.
  if (has(root, "textures"))
    for (const Node& t : array(child(root, "textures"))) read_texture(t);
  if (has(root, "materials"))
    for (const Node& m : array(child(root, "materials"))) read_material(m);
  load_textures();
  if (has(root, "meshes"))
    for (const Node& m : array(child(root, "meshes"))) read_mesh(m);
  if (has(root, "models"))
    for (const Node& m : array(child(root, "models"))) read_model(m);
  if (has(root, "objects")) read_objects(child(root, "objects"));
  // A model's lights and cameras go where its first instance puts the model (a model placed
  // many times still brings them once).
  for (const Model& m : models) {
    // A model no object places adds its lights and cameras only: said, since its meshes are
    // what a file usually declares it for (a fresh user's trial got an empty image).
    if (!m.first_placement && !m.objects.empty()) {
      const std::string message =
          m.where + "no object places model '" + m.name + "', so its meshes are not drawn";
      if (options.strict) throw Error(message + " (an error with --strict)");
      out.warnings.push_back(message);
    }
    const glm::mat4 world = m.first_placement.value_or(glm::mat4(1.0f));
    for (size_t i = m.first_light; i < m.first_light + m.lights; ++i) {
      Light& l = out.scene.lights[i];
      l.position = glm::vec3(world * glm::vec4(l.position, 1.0f));
      l.direction = glm::normalize(glm::mat3(world) * l.direction);
    }
    for (size_t i = 0; i < m.cameras.size(); ++i) {
      Camera c = m.cameras[i];
      c.position = glm::vec3(world * glm::vec4(c.position, 1.0f));
      c.target = glm::vec3(world * glm::vec4(c.target, 1.0f));
      c.up = glm::normalize(glm::mat3(world) * c.up);
      // Checked here, where the model is, rather than by the renderer once --camera picks it
      // (whose message named neither file nor camera): an object can place it out of range.
      try {
        validate_camera(c);
      } catch (const Error& e) {
        throw Error(m.where + "camera " + std::to_string(i) + ": " + model_camera_place(m, i) +
                    e.what());
      }
      out.model_cameras.push_back(c);
      out.model_camera_names.push_back("model '" + m.name + "' camera " + std::to_string(i));
    }
  }
  if (has(root, "lights"))
    for (const Node& l : array(child(root, "lights"))) read_light(l);
  if (has(root, "camera")) read_camera(child(root, "camera"));
  if (has(root, "environment")) read_environment(child(root, "environment"));
  out.scene.background = vec3_or(root, "background", out.scene.background, 0.0);
  out.scene.ambient = vec3_or(root, "ambient", out.scene.ambient, 0.0);
  if (has(root, "render")) read_render(child(root, "render"));
}

// The place of the entry that made item `k` (an object or light): the last of `sources` (in
// item order) that starts at or before it; null if none does.
const std::string* source_of(const std::vector<std::pair<size_t, std::string>>& sources, size_t k) {
  const auto it = std::upper_bound(sources.begin(), sources.end(), k,
                                   [](size_t v, const auto& s) { return v < s.first; });
  return it == sources.begin() ? nullptr : &std::prev(it)->second;
}

// validate_scene of what `reader` read, its message placed at the entry that made the object,
// light or camera it names.
void validate_read(const Reader& reader, const std::string& name) {
  try {
    validate_scene(reader.out.scene);
  } catch (const Error& e) {
    // "invalid scene: object K: ..." is placed at the objects entry that made object K, "light
    // K" at the lights entry, "the camera" at the camera.
    const std::string message = e.what();
    const auto placed = [&](const std::string& prefix,
                            const std::vector<std::pair<size_t, std::string>>& sources) {
      if (message.rfind(prefix, 0) != 0) return;
      const std::string* source =
          source_of(sources, std::strtoull(message.c_str() + prefix.size(), nullptr, 10));
      if (!source) return;
      const std::string in_model = reader.in_model(message);
      throw Error(*source + (in_model.empty() ? message : in_model));
    };
    placed("invalid scene: object ", reader.object_sources);
    placed("invalid scene: light ", reader.light_sources);
    if (message.rfind("invalid scene: the camera", 0) == 0 && !reader.camera_source.empty())
      throw Error(reader.camera_source + message);
    throw Error(name + ": " + message);
  }
}

}  // namespace

float uniform_float(uint32_t x) {
  const float u = float(x) * 0x1p-32f;
  return u < 1.0f ? u : 0x1.fffffep-1f;  // float(x) rounds up to 2^32 for x near 2^32
}

SceneFile load_scene_text(const std::string& text, const std::string& name,
                          const std::string& base_dir, const SceneFileOptions& options) {
  if (text.size() > options.max_file_bytes)
    throw Error(name + ": is " + std::to_string(text.size()) + " bytes, over the limit of " +
                std::to_string(options.max_file_bytes) + " bytes for a scene file");
  Json root;
  try {
    root = Json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    // "[json.exception.parse_error.101] parse error at line 3, column 5: syntax error ...":
    // the parser stops at the end of the token it could not take; point at the token's start.
    const std::string what = e.what();
    const size_t at = what.find(": ", what.find("column "));
    const std::string reason = at == std::string::npos ? what : what.substr(at + 2);
    size_t end = e.byte == 0 ? 0 : std::min<size_t>(e.byte - 1, text.size());
    if (end < text.size() && text[end] == '"') {
      while (end > 0 && !(text[end - 1] == '"' && (end < 2 || text[end - 2] != '\\'))) --end;
      if (end > 0) --end;
    } else {
      while (end > 0 && end < text.size() &&
             std::isalnum(static_cast<unsigned char>(text[end - 1])))
        --end;
    }
    const JsonPlace p = place_of_offset(text, end);
    throw Error(name + ":" + std::to_string(p.line) + ":" + std::to_string(p.column) +
                ": JSON syntax error: " + reason);
  } catch (const nlohmann::json::out_of_range&) {
    // A number beyond double's range (1e999): the place index below finds and names it.
  }
  SceneFile out;
  Reader reader{name, base_dir, options, {}, out};
  try {
    reader.places = index_json_places(text);
  } catch (const JsonNumberOverflow& e) {
    // nlohmann-json stopped at this number and left no document to name the value's path by
    // (objects[0].translation[1]), as other errors name it: the text is parsed again with the
    // number written as 0, which changes no other value and no place. If the rest of the file
    // does not parse either (another such number, a syntax error), the place alone is given.
    std::string patched = text;
    patched.replace(e.offset, e.length, "0" + std::string(e.length - 1, ' '));
    const Json whole = Json::parse(patched, nullptr, false);
    if (whole.is_discarded()) throw Error(name + ":" + e.what());
    reader.places.values[e.pointer] = e.place;
    throw Error(reader.where(reader.node_at({&whole, "", ""}, e.pointer)) + e.reason);
  } catch (const JsonDuplicateKey& e) {
    // Named by its path, as other errors are (nlohmann-json keeps the last value of the key),
    // unless the text held no document (a number out of range besides).
    if (root.is_null()) throw Error(name + ":" + e.what());
    const Node key = reader.child(reader.node_at({&root, "", ""}, e.object), e.key);
    reader.places.keys[key.pointer] = e.place;
    throw Error(reader.where(key, true) + "key '" + e.key + "' is given twice");
  } catch (const Error& e) {
    throw Error(name + ":" + e.what());
  }
  TESSERA_CHECK(!root.is_discarded());
  try {
    reader.read({&root, "", ""});
    validate_read(reader, name);
  } catch (const Error& e) {
    // An unknown key read before the error may be its cause ("materal" for "materials", whose
    // absence the error is about): its warning, with the "did you mean", would otherwise be
    // lost with the scene that held it.
    std::string message = e.what();
    for (const std::string& w : reader.unknown_keys) message += "\n  " + w;
    throw Error(message);
  }
  for (size_t k = 0; k < out.scene.lights.size(); ++k) {
    const std::string* source = source_of(reader.light_sources, k);
    out.light_places.push_back(source ? *source : name + ": ");
  }
  return out;
}

SceneFile load_model_scene(const std::string& path, const SceneFileOptions& options) {
  const std::string name = std::filesystem::path(path).filename().string();
  const Json root = {{"models", Json::array({Json::object({{"name", name}, {"file", path}})})},
                     {"objects", Json::array({Json::object({{"model", name}})})}};
  SceneFile out;
  Reader reader{path, "", options, {}, out};
  reader.model_only = true;
  try {
    reader.read({&root, "", ""});
    validate_read(reader, path);
  } catch (const Error& e) {
    // The messages that name no place (an object count over the limit) name the file.
    const std::string message = e.what();
    if (message.find(path) == std::string::npos) throw Error(path + ": " + message);
    throw;
  }
  return out;
}

std::string read_scene_description(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const Json j = Json::parse(in, nullptr, false);
  if (j.is_object() && j.contains("description") && j["description"].is_string())
    return j["description"].get<std::string>();
  return "";
}

SceneFile load_scene_file(const std::string& path, const SceneFileOptions& options) {
  require_regular_file(path);
  std::error_code ec;
  const uint64_t bytes = std::filesystem::file_size(path, ec);
  if (ec) throw Error(path + ": cannot read the scene file: " + ec.message());
  if (bytes > options.max_file_bytes)
    throw Error(path + ": is " + std::to_string(bytes) + " bytes, over the limit of " +
                std::to_string(options.max_file_bytes) + " bytes for a scene file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open the scene file");
  std::ostringstream text;
  text << in.rdbuf();
  return load_scene_text(text.str(), path, std::filesystem::path(path).parent_path().string(),
                         options);
}

}  // namespace tessera
