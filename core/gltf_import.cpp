// glTF 2.0 import: reading the file, the node hierarchy, cameras and KHR_lights_punctual.
// TinyGLTF parses the document and loads buffers; everything it hands over is checked again
// here and in gltf_accessors.cpp before use.

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <numbers>
#include <span>

#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "core/check.h"
#include "core/gltf_detail.h"
#include "core/mapped_file.h"

namespace tessera::gltf {

using nlohmann::json;

void Context::fail(const std::string& where, const std::string& what) const {
  throw Error(file + ": " + (where.empty() ? "" : where + ": ") + what);
}

void Context::warn(const std::string& where, const std::string& what) const {
  if (options.strict) fail(where, what + " (an error in strict import)");
  const std::string message = file + ": " + (where.empty() ? "" : where + ": ") + what;
  // A sampler or texture shared by many materials warns once.
  if (std::find(warnings.begin(), warnings.end(), message) == warnings.end()) {
    warnings.push_back(message);
  }
}

std::string at(const char* array, size_t i) {
  return std::string(array) + "[" + std::to_string(i) + "]";
}

const json& member(const json& o, const char* key) {
  static const json empty = json::array();
  const auto it = o.find(key);
  return it == o.end() ? empty : *it;
}

const json& member_object(const json& o, const char* key) {
  static const json empty = json::object();
  const auto it = o.find(key);
  return it == o.end() ? empty : *it;
}

void check_index(const Context& ctx, const std::string& where, int64_t index, size_t count,
                 const char* array) {
  if (index < 0 || uint64_t(index) >= count) {
    ctx.fail(where, "refers to " + at(array, size_t(std::max<int64_t>(index, 0))) +
                        (index < 0 ? " (negative)" : "") + ", but the file has " +
                        std::to_string(count) + " " + array);
  }
}

std::string float_fault(const json& v, double lo, double hi) {
  const auto text = [](double x) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.9g", x);
    return std::string(buffer);
  };
  const double d = v.get<double>();
  if (d < lo || d > hi) {
    return "is " + v.dump() +
           (hi == HUGE_VAL ? ", must be >= " + text(lo)
                           : ", outside [" + text(lo) + ", " + text(hi) + "]");
  }
  if (std::fabs(d) > FLT_MAX) {
    return "is " + v.dump() + ", which does not fit a 32-bit float (at most " + text(FLT_MAX) + ")";
  }
  return {};
}

float float_number(const Context& ctx, const json& v, const std::string& where, double lo,
                   double hi) {
  if (std::string fault = float_fault(v, lo, hi); !fault.empty()) ctx.fail(where, fault);
  return float(v.get<double>());
}

namespace {

void check_file_size(const Context& ctx, uintmax_t size) {
  if (size > ctx.options.max_file_bytes) {
    ctx.fail("", "is " + std::to_string(size) + " bytes, over the limit of " +
                     std::to_string(ctx.options.max_file_bytes));
  }
  if (size > UINT32_MAX) ctx.fail("", "is over 4 GiB, more than glTF files may be");
}

// The file's bytes, mapped (map_file): the size is checked first, so that the messages for a
// missing or oversized file are the same as for bytes handed over (import_gltf_bytes).
MappedFile read_file(const Context& ctx, const std::string& path) {
  require_regular_file(path);  // file_size's error for a directory or a FIFO says "not supported"
  std::error_code error;
  const uintmax_t size = std::filesystem::file_size(path, error);
  if (error) ctx.fail("", "cannot read the file: " + error.message());
  check_file_size(ctx, size);
  MappedFile bytes = map_file(path, ctx.options.max_file_bytes);
  check_file_size(ctx, bytes.size());  // a file that grew since
  return bytes;
}

uint32_t load_u32(const unsigned char* p) {
  uint32_t v;
  std::memcpy(&v, p, 4);
  return v;  // glTF is little-endian, as is every host Tessera runs on
}

// The JSON chunk of a binary glTF (specification 4.4), after checking the header's lengths: a
// view into `bytes`, not a copy.
std::string_view glb_json(const Context& ctx, std::span<const unsigned char> bytes) {
  if (bytes.size() < 20) ctx.fail("", "is truncated: a .glb needs a 20-byte header");
  if (load_u32(&bytes[4]) != 2) {
    ctx.fail("", "is a binary glTF of version " + std::to_string(load_u32(&bytes[4])) + ", not 2");
  }
  if (load_u32(&bytes[8]) != bytes.size()) {
    ctx.fail("", "is truncated or padded: its header says " + std::to_string(load_u32(&bytes[8])) +
                     " bytes, the file has " + std::to_string(bytes.size()));
  }
  const uint64_t length = load_u32(&bytes[12]);
  if (load_u32(&bytes[16]) != 0x4E4F534Au) ctx.fail("", "its first chunk is not JSON");
  // Chunks end on 4-byte boundaries (specification 4.4.3.1); a length that does not is wrong,
  // and TinyGLTF would then look for the BIN chunk in the wrong place and complain of that.
  if (length % 4 != 0) {
    ctx.fail("", "its JSON chunk's length, " + std::to_string(length) +
                     " bytes, is not a multiple of 4 as glTF 2.0 requires (4.4.3.1): the length "
                     "is wrong or the file is damaged");
  }
  if (20 + length > bytes.size()) {
    ctx.fail("", "is truncated: its JSON chunk of " + std::to_string(length) +
                     " bytes runs past the end of the file");
  }
  return std::string_view(reinterpret_cast<const char*>(bytes.data()) + 20, length);
}

// The payload of a binary glTF's BIN chunk (specification 4.4.3.3), which follows the JSON
// chunk of `json_length` bytes; empty when the file has none or its chunk header is not what
// TinyGLTF accepts (TinyGLTF, given the whole file, then names the fault).
std::span<const unsigned char> glb_bin(std::span<const unsigned char> bytes, size_t json_length) {
  const size_t start = 20 + json_length;
  if (start % 4 != 0 || bytes.size() < start + 12) return {};
  const uint32_t length = load_u32(&bytes[start]);
  if (length < 4 || length % 4 != 0 || length > bytes.size() - start - 8) return {};
  if (load_u32(&bytes[start + 4]) != 0x004E4942u) return {};  // "BIN\0"
  return bytes.subspan(start + 8, length);
}

// A .glb for TinyGLTF that leaves buffers[0] in `bytes`: the same header and JSON chunk, with
// the text of buffers[0].byteLength (`length_text`, a view into `json`) rewritten to 1 and
// padded with spaces, so that every later place in the text keeps its line and column, and a
// BIN chunk of 4 zero bytes. TinyGLTF copies a GLB-stored buffer out of the file into fresh
// pages; from this one it copies one byte, and buffer_view_bytes reads the buffer where it lies
// instead (Context::glb_buffer).
std::vector<unsigned char> glb_without_buffer(std::span<const unsigned char> bytes,
                                              std::string_view json, std::string_view length_text) {
  const uint32_t total = uint32_t(20 + json.size() + 12);
  std::vector<unsigned char> out(bytes.begin(), bytes.begin() + 20 + json.size());
  std::memcpy(&out[8], &total, 4);
  const size_t at = size_t(length_text.data() - json.data()) + 20;
  out[at] = '1';
  std::fill(out.begin() + at + 1, out.begin() + at + length_text.size(), ' ');
  const uint32_t bin[3] = {4, 0x004E4942u, 0};  // length, "BIN\0", the one buffer byte and padding
  out.insert(out.end(), reinterpret_cast<const unsigned char*>(bin),
             reinterpret_cast<const unsigned char*>(bin) + sizeof bin);
  return out;
}

// The deepest nesting of arrays and objects in JSON `text` (brackets inside strings left out),
// counted without recursion.
size_t nesting_depth(std::string_view text) {
  size_t depth = 0, deepest = 0;
  bool in_string = false, escaped = false;
  for (const char c : text) {
    if (in_string) {
      if (escaped)
        escaped = false;
      else if (c == '\\')
        escaped = true;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return deepest;
}

// Whether an image of the checked document `doc` reads a buffer view: TinyGLTF then indexes
// the view's buffer at the view's offset, which must stay inside the buffer it holds.
bool images_in_buffer_views(const json& doc) {
  for (const json& image : member(doc, "images")) {
    if (image.contains("bufferView")) return true;
  }
  return false;
}

// Keeps an image's encoded bytes (a file's or a data uri's); material_index decodes them, after
// its own size checks. Images in buffer views are left alone: TinyGLTF has not range-checked
// their view, so their bytes are read only after buffer_view_bytes has.
bool keep_encoded_image(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                        const unsigned char* bytes, int size, void*) {
  if (image->bufferView < 0) image->image.assign(bytes, bytes + size);
  return true;
}

// Whether every element of `m` is at most `largest` in magnitude (by default: finite).
bool within(const glm::dmat4& m, double largest = DBL_MAX) {
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) {
      if (!(std::fabs(m[c][r]) <= largest)) return false;  // NaN too
    }
  }
  return true;
}

// What the importer reads of a node; an empty vector or std::nullopt where the node lacks the
// property.
struct NodeInfo {
  std::vector<double> matrix, translation, rotation, scale;
  std::vector<int> children;
  std::optional<int> mesh, camera;
  bool skin = false;
  bool light_extension = false;  // has extensions.KHR_lights_punctual
  std::optional<int> light;      // ... and its light
};

// nodes[index] of a document that check_document has checked.
NodeInfo node_info(const json& node) {
  NodeInfo n;
  for (auto [key, out] : {std::pair{"matrix", &n.matrix},
                          {"translation", &n.translation},
                          {"rotation", &n.rotation},
                          {"scale", &n.scale}}) {
    if (node.contains(key)) *out = node[key].get<std::vector<double>>();
  }
  if (node.contains("children")) n.children = node["children"].get<std::vector<int>>();
  if (node.contains("mesh")) n.mesh = node["mesh"].get<int>();
  if (node.contains("camera")) n.camera = node["camera"].get<int>();
  n.skin = node.contains("skin");
  if (node.contains("extensions") && node["extensions"].contains("KHR_lights_punctual")) {
    n.light_extension = true;
    const json& ext = node["extensions"]["KHR_lights_punctual"];
    if (ext.contains("light")) n.light = ext["light"].get<int>();
  }
  return n;
}

// The same from TinyGLTF's reading of a node, which holds all of it when scan_document vouched
// for the document (no index over 2^31 - 1, skin an index, no matrix beside TRS properties).
NodeInfo node_info(const tinygltf::Node& node) {
  NodeInfo n{node.matrix, node.translation, node.rotation, node.scale, node.children};
  if (node.mesh >= 0) n.mesh = node.mesh;
  if (node.camera >= 0) n.camera = node.camera;
  n.skin = node.skin >= 0;
  if (auto it = node.extensions.find("KHR_lights_punctual"); it != node.extensions.end()) {
    n.light_extension = true;
    if (it->second.Has("light")) n.light = it->second.Get("light").GetNumberAsInt();
  }
  return n;
}

// glTF allows a transform that flattens what it places (a scale of 0: specification 3.5.3,
// whose notes expect lighting artifacts on one axis and let a scale of 0 on all three hide the
// node), where Tessera's scene files refuse one with the same words as here. The file is
// imported as written, with a warning (an error in strict import, as in a scene file): both
// renderers shade a flattened triangle with its face normal, its normals' transform (the
// inverse transpose) being singular, and one flattened to a line or a point covers no pixel.
constexpr const char* kFlattened =
    "imported as written, as glTF 2.0 allows (3.5.3): drawn flat, or not at all where every "
    "axis is 0";

// A node's local transform: its matrix, or translation * rotation * scale.
glm::dmat4 local_transform(const Context& ctx, const NodeInfo& node, const std::string& where) {
  // First, each number must fit a float (float_fault), as the object transform that holds it
  // does: 1e39, finite as a double, became an infinite float that the scene's checks refused as
  // "a NaN or infinite transform" of a scene object, naming neither the file nor the node. The
  // path is built only for the number refused (the walk reads every node).
  for (auto [key, values] : {std::pair{"matrix", &node.matrix},
                             {"translation", &node.translation},
                             {"rotation", &node.rotation},
                             {"scale", &node.scale}}) {
    for (size_t k = 0; k < values->size(); ++k) {
      if (std::string fault = float_fault(json((*values)[k])); !fault.empty()) {
        ctx.fail(where + "." + key + "[" + std::to_string(k) + "]", fault);
      }
    }
  }
  glm::dmat4 m(1.0);
  if (!node.matrix.empty()) {
    m = glm::make_mat4(node.matrix.data());  // column-major, as glTF stores it
    // The specification (3.5.3) requires a matrix that decomposes into TRS; a
    // projective last row (a row-major matrix, say) would smear the mesh.
    if (m[0][3] != 0.0 || m[1][3] != 0.0 || m[2][3] != 0.0 || m[3][3] != 1.0) {
      ctx.fail(where + ".matrix", "is not affine: its last row is (" + std::to_string(m[0][3]) +
                                      ", " + std::to_string(m[1][3]) + ", " +
                                      std::to_string(m[2][3]) + ", " + std::to_string(m[3][3]) +
                                      "), not (0, 0, 0, 1), so it is no translation, rotation " +
                                      "and scale (glTF 2.0, 3.5.3)");
    }
    if (!node.translation.empty() || !node.rotation.empty() || !node.scale.empty()) {
      ctx.warn(where, "has both a matrix and TRS properties; the matrix is used");
    }
    // As a scale of 0 (below), in double, as scene files test a matrix.
    if (glm::determinant(glm::dmat3(m)) == 0.0) {
      ctx.warn(
          where + ".matrix",
          std::string("flattens the object (its upper 3x3 part has determinant 0); ") + kFlattened);
    }
  } else {
    auto or_default = [](const std::vector<double>& v, std::vector<double> fallback) {
      return v.empty() ? fallback : v;
    };
    const auto t = or_default(node.translation, {0, 0, 0});
    const auto r = or_default(node.rotation, {0, 0, 0, 1});
    const auto s = or_default(node.scale, {1, 1, 1});
    if (s[0] == 0.0 || s[1] == 0.0 || s[2] == 0.0) {
      ctx.warn(where + ".scale", std::string("a scale of 0 flattens the object; ") + kFlattened);
    }
    glm::dquat q(r[3], r[0], r[1], r[2]);
    const double length = glm::length(q);
    if (!(length > 0.0) || !std::isfinite(length)) {
      ctx.fail(where + ".rotation",
               "is not a unit quaternion (its length is " + std::to_string(length) + ")");
    }
    // Writers round a unit quaternion's floats; a length further from 1 is the file's error.
    if (std::abs(length - 1.0) > 1e-3) {
      ctx.warn(where + ".rotation", "is not a unit quaternion (its length is " +
                                        std::to_string(length) + "); it is normalized");
    }
    q /= length;
    m = glm::translate(glm::dmat4(1.0), glm::dvec3(t[0], t[1], t[2])) * glm::mat4_cast(q) *
        glm::scale(glm::dmat4(1.0), glm::dvec3(s[0], s[1], s[2]));
  }
  if (!within(m)) ctx.fail(where, "its transform has a NaN or infinite element");
  return m;
}

// Camera at a node: glTF cameras look down their local -z with +y up.
Camera place_camera(const glm::dmat4& world) {
  Camera c;
  const glm::dvec3 position(world * glm::dvec4(0, 0, 0, 1));
  const glm::dvec3 forward = glm::normalize(glm::dvec3(world * glm::dvec4(0, 0, -1, 0)));
  c.position = glm::vec3(position);
  c.target = glm::vec3(position + forward);
  c.up = glm::vec3(glm::normalize(glm::dvec3(world * glm::dvec4(0, 1, 0, 0))));
  return c;
}

// Luminous efficacy of 555 nm light, lm/W: the conversion KHR_lights_punctual's photometric
// units need to become Tessera's radiometric ones. It treats every light as if it emitted at
// 555 nm, which is how the extension's reference viewers read "color" too (a relative tint).
constexpr double kLumensPerWatt = 683.0;

// KHR_lights_punctual light `index` placed by a node's world transform. Point and spot
// intensity is luminous intensity in candela (lm/sr) -> radiant intensity W/sr = cd / 683;
// directional intensity is illuminance in lux (lm/m^2) -> irradiance W/m^2 = lx / 683.
Light make_light(const Context& ctx, const json& lights, int index, const glm::dmat4& world) {
  const json& l = lights[index];
  const std::string where = "extensions.KHR_lights_punctual." + at("lights", index);
  Light light;
  const std::string type = l.value("type", "");
  if (type == "point") {
    light.kind = LightKind::point;
  } else if (type == "spot") {
    light.kind = LightKind::spot;
  } else if (type == "directional") {
    light.kind = LightKind::directional;
  } else {
    ctx.fail(where + ".type", "is '" + type + "', not point, spot or directional");
  }
  const auto color = l.value("color", std::vector<double>{1, 1, 1});
  for (double c : color) {
    if (!(c >= 0.0 && c <= 1.0)) ctx.fail(where + ".color", "has a component outside [0, 1]");
  }
  light.color = glm::vec3(color[0], color[1], color[2]);
  const double intensity = l.value("intensity", 1.0);
  if (!(intensity >= 0.0) || !std::isfinite(intensity)) {
    ctx.fail(where + ".intensity", "must be a finite number >= 0");
  }
  // Held to a float as written, as a scene file's intensity is (1e39 / 683 would fit one, but
  // 1e42 / 683 would not).
  if (l.contains("intensity")) float_number(ctx, l["intensity"], where + ".intensity");
  light.intensity = float(intensity / kLumensPerWatt);
  if (l.contains("range")) {
    const double range = l["range"].get<double>();
    if (!(range > 0.0) || !std::isfinite(range)) ctx.fail(where + ".range", "must be > 0");
    // The extension recommends the same window as Tessera's inverse_square falloff.
    light.range = float_number(ctx, l["range"], where + ".range");
  }
  light.falloff = Falloff::inverse_square;
  light.position = glm::vec3(world * glm::dvec4(0, 0, 0, 1));
  light.direction = glm::vec3(glm::normalize(glm::dvec3(world * glm::dvec4(0, 0, -1, 0))));
  if (light.kind == LightKind::spot) {
    const json& spot = member_object(l, "spot");
    double inner = spot.value("innerConeAngle", 0.0);
    double outer = spot.value("outerConeAngle", std::numbers::pi / 4);
    if (!(inner >= 0.0 && inner < outer && outer <= std::numbers::pi / 2)) {
      ctx.fail(where + ".spot", "needs 0 <= innerConeAngle < outerConeAngle <= pi/2");
    }
    // Tessera needs outer < pi/2 (its cone test divides by cos(outer)).
    constexpr double kLargestOuter = std::numbers::pi / 2 - 1e-4;
    if (outer > kLargestOuter) {
      ctx.warn(where + ".spot.outerConeAngle", "is pi/2; narrowed to pi/2 - 1e-4");
      outer = kLargestOuter;
      inner = std::min(inner, outer);
    }
    light.inner_angle = float(inner);
    light.outer_angle = float(outer);
  }
  if (!std::isfinite(light.direction.x) || !std::isfinite(light.position.x)) {
    ctx.fail(where, "is placed by a degenerate node transform");
  }
  return light;
}

// The cameras in file order, each placed by the first node that uses it (at the origin if none).
std::vector<Camera> make_cameras(
    const Context& ctx, const json& doc,
    const std::map<int, std::pair<glm::dmat4, std::string>>& placements, ImportedPlaces& places) {
  std::vector<Camera> cameras;
  const json& list = member(doc, "cameras");
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string where = at("cameras", i);
    auto placed = placements.find(int(i));
    Camera c = place_camera(placed == placements.end() ? glm::dmat4(1.0) : placed->second.first);
    places.cameras.emplace_back(placed == placements.end() ? "" : placed->second.second, where);
    const std::string type = list[i].value("type", "");
    if (type == "perspective") {
      const json& p = member_object(list[i], "perspective");
      const double yfov = p.value("yfov", 0.0), znear = p.value("znear", 0.0);
      if (!(yfov > 0.0 && yfov < 3.1)) {
        ctx.fail(where + ".perspective.yfov", "must be in (0, 3.1) radians");
      }
      if (!(znear > 0.0) || !std::isfinite(znear)) {
        ctx.fail(where + ".perspective.znear", "must be > 0");
      }
      c.vertical_fov = float(yfov);
      c.near_plane = float_number(ctx, p["znear"], where + ".perspective.znear");
    } else if (type == "orthographic") {
      ctx.warn(where,
               "is orthographic, which Tessera does not render; given as a perspective "
               "camera with a 45 degree field of view");
    } else {
      ctx.fail(where + ".type", "is '" + type + "', not perspective or orthographic");
    }
    cameras.push_back(c);
  }
  return cameras;
}

// The scene's node trees, depth first with an explicit stack (no recursion limit on deep
// hierarchies), placing mesh instances, lights and cameras by their world transforms. Nodes are
// read from `doc` when it has them, else (scan_document's partial document) from `model`.
void instantiate_nodes(const Context& ctx, const json& doc, const tinygltf::Model& model,
                       ImportedModel& out) {
  const json& scenes = member(doc, "scenes");
  if (scenes.empty()) ctx.fail("scenes", "the file has no scene to render");
  const int scene_index = doc.value("scene", 0);
  check_index(ctx, "scene", scene_index, scenes.size(), "scenes");
  const json* json_nodes = doc.contains("nodes") ? &doc["nodes"] : nullptr;
  const size_t node_count = json_nodes ? json_nodes->size() : model.nodes.size();
  const json& lights =
      member(member_object(member_object(doc, "extensions"), "KHR_lights_punctual"), "lights");

  MaterialTable table;
  decode_images(ctx, model, table);
  std::map<std::pair<int, int>, uint32_t> meshes;                       // (mesh, primitive)
  std::map<int, std::pair<glm::dmat4, std::string>> camera_placements;  // world, node
  std::vector<bool> on_path(node_count, false);
  struct Visit {
    int node;
    glm::dmat4 parent;
    bool leave;
    std::string from;  // where the reference to this node is, for messages
  };
  std::vector<Visit> stack;
  const json& roots = member(scenes[scene_index], "nodes");
  for (size_t i = roots.size(); i-- > 0;) {
    stack.push_back({roots[i].get<int>(), glm::dmat4(1.0), false,
                     at("scenes", scene_index) + ".nodes[" + std::to_string(i) + "]"});
  }
  while (!stack.empty()) {
    Visit v = std::move(stack.back());
    stack.pop_back();
    if (v.leave) {
      on_path[v.node] = false;
      continue;
    }
    check_index(ctx, v.from, v.node, node_count, "nodes");
    const std::string where = at("nodes", v.node);
    if (on_path[v.node]) {
      ctx.fail(v.from, "refers to node " + std::to_string(v.node) +
                           ", its own ancestor: the node graph has a cycle");
    }
    on_path[v.node] = true;
    const NodeInfo node =
        json_nodes ? node_info((*json_nodes)[v.node]) : node_info(model.nodes[v.node]);
    const glm::dmat4 world = v.parent * local_transform(ctx, node, where);
    // Numbers that each fit a float can multiply, down the hierarchy, to one that does not.
    if (!within(world, FLT_MAX)) {
      ctx.fail(where,
               "its world transform (its ancestors' transforms times its own) overflows a 32-bit "
               "float");
    }
    stack.push_back({v.node, {}, true, {}});
    for (size_t c = node.children.size(); c-- > 0;) {
      stack.push_back(
          {node.children[c], world, false, where + ".children[" + std::to_string(c) + "]"});
    }

    if (node.mesh) {
      const int mesh = *node.mesh;
      check_index(ctx, where + ".mesh", mesh, model.meshes.size(), "meshes");
      // A mirroring transform turns counter-clockwise triangles clockwise (specification
      // 3.7.4); the renderers handle it per object (is_mirroring), so the mesh is shared.
      for (size_t p = 0; p < model.meshes[mesh].primitives.size(); ++p) {
        const int material = model.meshes[mesh].primitives[p].material;
        if (material >= 0) {
          check_index(ctx, at("meshes", mesh) + ".primitives[" + std::to_string(p) + "].material",
                      material, member(doc, "materials").size(), "materials");
        }
        Object object;
        object.material = material_index(ctx, doc, model, material, table, out.scene);
        object.transform = glm::mat4(world);
        const auto key = std::make_pair(mesh, int(p));
        if (auto it = meshes.find(key); it != meshes.end()) {
          object.mesh = it->second;
        } else {
          out.scene.meshes.push_back(
              convert_primitive(ctx, model, mesh, int(p), table.uv_options[material]));
          out.places.meshes.push_back(at("meshes", mesh) + ".primitives[" + std::to_string(p) +
                                      "]");
          // Without NORMAL, make_flat gave each triangle its own vertices.
          out.places.vertices_are_elements.push_back(
              model.meshes[mesh].primitives[p].attributes.count("NORMAL") > 0);
          if (ctx.read_pages) {
            for (const auto& [begin, size] : ctx.reads) ctx.read_pages->mark_read(begin, size);
            ctx.reads.clear();
          }
          object.mesh = meshes[key] = uint32_t(out.scene.meshes.size() - 1);
        }
        out.scene.objects.push_back(object);
        out.places.objects.push_back(where);
      }
    }
    if (node.camera) {
      const int camera = *node.camera;
      check_index(ctx, where + ".camera", camera, member(doc, "cameras").size(), "cameras");
      camera_placements.try_emplace(camera, world, where);
    }
    if (node.light_extension) {
      if (!node.light) ctx.fail(where + ".extensions.KHR_lights_punctual", "has no light");
      const int light = *node.light;
      check_index(ctx, where + ".extensions.KHR_lights_punctual.light", light, lights.size(),
                  "KHR_lights_punctual lights");
      out.scene.lights.push_back(make_light(ctx, lights, light, world));
      out.places.lights.emplace_back(where,
                                     "extensions.KHR_lights_punctual." + at("lights", light));
    }
    if (node.skin) ctx.warn(where + ".skin", "skins are ignored (bind pose)");
  }
  // Valid glTF, but a model is placed to be drawn: an empty image was otherwise unexplained,
  // where a scene file's model that no object places is warned about.
  // A file of lights or cameras alone is a use of its own.
  if (out.scene.objects.empty() && out.scene.lights.empty() && camera_placements.empty()) {
    ctx.warn(at("scenes", scene_index),
             roots.empty() ? "has no nodes, so the model places nothing and draws nothing"
                           : "places no meshes, lights or cameras (none of its nodes has one), "
                             "so the model draws nothing");
  }
  out.cameras = make_cameras(ctx, doc, camera_placements, out.places);
}

}  // namespace
}  // namespace tessera::gltf

namespace tessera {

namespace {

// `file`, if given, holds `bytes`. Where TinyGLTF copies the buffers (a .gltf's external or
// data-uri buffers, or a .glb whose buffer TinyGLTF must be given, below) the file is released
// once it has read them, so that the file's pages and the meshes are not held at once; a .glb's
// buffer read in place holds the file to the end.
ImportedModel import_gltf_from(gltf::Context& ctx, ImportedModel& out,
                               std::span<const unsigned char> bytes, MappedFile* file) {
  using namespace gltf;
  const bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
  // Said plainly, rather than as the JSON parser's complaint about the first byte.
  if (bytes.empty()) ctx.fail("", "is empty");
  if (!binary && model_extension(ctx.file) == ".glb") {
    ctx.fail("", "is not a binary glTF: a .glb starts with the bytes 'glTF' (glTF 2.0, 4.4)");
  }
  const std::string_view text =
      binary ? glb_json(ctx, bytes)
             : std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  // The scan's partial document on the common path (building the whole one was a seventh of
  // the import's time), the whole one when the scan finds something for check_document to name.
  std::string_view glb_buffer_length;
  std::optional<json> scanned = scan_document(text, binary ? &glb_buffer_length : nullptr);
  json doc;
  if (scanned) {
    doc = std::move(*scanned);
  } else {
    // The scan gives up past 256 levels; TinyGLTF's parser recurses through `extras` and
    // overflowed its stack at 15,000 (a fresh user's trial), so nothing deeper reaches it.
    if (const size_t depth = nesting_depth(text); depth > 256) {
      ctx.fail("", "its JSON nests arrays and objects " + std::to_string(depth) +
                       " levels deep, more than the 256 Tessera reads");
    }
    try {
      doc = json::parse(text.begin(), text.end());
    } catch (const json::exception& e) {
      ctx.fail("", std::string("is not valid JSON: ") + e.what());
    }
  }
  check_document(ctx, doc);
  for (const char* list : {"extensionsUsed", "extensionsRequired"}) {
    for (const json& name : member(doc, list)) {
      ctx.mesh_quantization |= name == "KHR_mesh_quantization";
    }
  }

  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(keep_encoded_image, nullptr);
  tinygltf::Model model;
  std::string error, warning;
  // buffers[0] is read in place when it is valid as TinyGLTF would check it (in the BIN chunk,
  // 1 to the chunk's size bytes) and no image could index it; otherwise TinyGLTF is given the
  // file and copies it, naming any fault. The scan (glb_buffer_length) is the one reading of
  // the text that knows where the number lies.
  std::vector<unsigned char> stand_in;
  if (!glb_buffer_length.empty() && !images_in_buffer_views(doc)) {
    const std::span<const unsigned char> bin = glb_bin(bytes, text.size());
    const uint64_t length = doc["buffers"][0]["byteLength"].get<uint64_t>();
    if (length >= 1 && length <= bin.size()) {
      stand_in = glb_without_buffer(bytes, text, glb_buffer_length);
      ctx.glb_buffer = bin.first(length);
    }
  }
  const std::span<const unsigned char> glb = stand_in.empty() ? bytes : stand_in;
  const bool ok = binary ? loader.LoadBinaryFromMemory(&model, &error, &warning, glb.data(),
                                                       unsigned(glb.size()), ctx.base_dir)
                         : loader.LoadASCIIFromString(&model, &error, &warning, text.data(),
                                                      unsigned(text.size()), ctx.base_dir);
  if (!ok) {
    explain_tinygltf_failure(ctx, text);
    while (!error.empty() && error.back() == '\n') error.pop_back();
    ctx.fail("", "TinyGLTF cannot read it: " + error);
  }
  stand_in = {};
  // Materials are read from `doc` (material_index): TinyGLTF's copies, 2 KiB each before
  // their strings and maps (160 KiB of a 1.8 MB glb's 34 materials), are dropped at once.
  std::vector<tinygltf::Material>().swap(model.materials);
  // The file is released as the primitives are converted (ReadPages), its header and JSON
  // chunk at once: the document is parsed.
  std::optional<ReadPages> read_pages;
  if (file && file->mapped() && !ctx.glb_buffer.empty()) {
    read_pages.emplace(*file);
    ctx.read_pages = &*read_pages;
    read_pages->mark_read(bytes.data(), size_t(ctx.glb_buffer.data() - bytes.data()));
  }
  if (file && ctx.glb_buffer.empty()) *file = MappedFile();
  instantiate_nodes(ctx, doc, model, out);
  return std::move(out);
}

}  // namespace

ImportedModel import_gltf(const std::string& path, const ImportOptions& options) {
  ImportedModel out;
  gltf::Context ctx{path, std::filesystem::path(path).parent_path().string(), options,
                    out.warnings};
  MappedFile file = gltf::read_file(ctx, path);
  return import_gltf_from(ctx, out, {file.data(), file.size()}, &file);
}

ImportedModel import_gltf_bytes(const std::vector<unsigned char>& bytes, const std::string& name,
                                const std::string& base_dir, const ImportOptions& options) {
  ImportedModel out;
  gltf::Context ctx{name, base_dir, options, out.warnings};
  gltf::check_file_size(ctx, bytes.size());
  return import_gltf_from(ctx, out, bytes, nullptr);
}

}  // namespace tessera
