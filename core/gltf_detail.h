#pragma once
// Internals of the glTF 2.0 importer (core/gltf_*.cpp), not a public interface.

#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include <tiny_gltf.h>
#include <nlohmann/json.hpp>

#include "core/mapped_file.h"
#include "core/model_import.h"

namespace tessera::gltf {

/// The file being imported, for messages, and where warnings go.
struct Context {
  std::string file;      // the path as the caller gave it
  std::string base_dir;  // folder that relative uris are resolved against
  const ImportOptions& options;
  std::vector<std::string>& warnings;
  /// buffers[0]'s bytes where they are read in place from the .glb's BIN chunk, which TinyGLTF
  /// was not given (its model then holds one byte of that buffer); empty otherwise.
  std::span<const unsigned char> glb_buffer;
  /// Where set (a .glb mapped, its buffer read in place), the byte ranges that reading accessors
  /// covers are collected in `reads`, for the node walk to hand to read_pages once a primitive
  /// is converted (its conversion reads some of them in place until it ends).
  ReadPages* read_pages = nullptr;
  mutable std::vector<std::pair<const unsigned char*, size_t>> reads;
  /// The file lists KHR_mesh_quantization (in extensionsUsed or extensionsRequired), which
  /// allows integer POSITION, NORMAL and TANGENT components (convert_primitive).
  bool mesh_quantization = false;

  /// Throws Error "FILE: WHERE: WHAT"; `where` is a glTF JSON path such as
  /// meshes[2].primitives[0].mode (empty for the file as a whole).
  [[noreturn]] void fail(const std::string& where, const std::string& what) const;
  /// Records a warning, or fails with it when options.strict.
  void warn(const std::string& where, const std::string& what) const;
};

/// "name[i]", the JSON path of element i of a top-level array.
std::string at(const char* array, size_t i);

/// o[key] when `o` has it, else an empty array (`member`) or object (`member_object`), by
/// reference: json::value(key, default) returns a copy, which for the top-level arrays cost a
/// seventh of the import when taken per material or texture.
const nlohmann::json& member(const nlohmann::json& o, const char* key);
const nlohmann::json& member_object(const nlohmann::json& o, const char* key);

/// Fails unless 0 <= index < count: `where` holds an index into the file's `array`.
void check_index(const Context& ctx, const std::string& where, int64_t index, size_t count,
                 const char* array);

/// What keeps the number `v` from being read as a float, quoting it as written: outside
/// [lo, hi] ("is -1, must be >= 0" where hi is HUGE_VAL, else "is 2, outside [0, 1]"), or beyond
/// a float's range ("is 1e+39, which does not fit a 32-bit float (at most 3.40282347e+38)"):
/// a double such as 1e39 became an infinite float, which the renderer then refused without
/// saying where it came from, or not at all. Empty where it can be read (no allocation), so
/// that a caller checking many numbers builds their glTF paths only for the one it refuses.
std::string float_fault(const nlohmann::json& v, double lo = -HUGE_VAL, double hi = HUGE_VAL);

/// The number `v` at `where` as a float, after float_fault, failing at `where` with its words.
/// Every number the importer holds in a float (materials, nodes, cameras, lights) goes
/// through these two, with the limits the scene files set for the same parameter
/// (docs/scene-format.md).
float float_number(const Context& ctx, const nlohmann::json& v, const std::string& where,
                   double lo = -HUGE_VAL, double hi = HUGE_VAL);

/// The JSON document of `text` with only the members that the importer reads from it (asset,
/// extensionsUsed, extensionsRequired, scene, scenes, nodes, cameras, materials, textures,
/// samplers, images, buffers, extensions), after a scan of the whole text that checks its syntax
/// and check_document's property types without building the rest (accessors, bufferViews and
/// meshes, the bulk of a large file, are read from TinyGLTF's model). Empty when the text has an
/// error or anything the scan does not vouch for: the caller then parses the whole text with
/// nlohmann::json and check_document, which name the error. Given a document, check_document
/// gives the same result on it as on the whole text's. With a document, *glb_buffer_length
/// (when given) is set to the text of buffers[0].byteLength's value, a view into `text`, where
/// buffers[0] has one byteLength and no uri (the buffer of a .glb's BIN chunk), else to empty.
std::optional<nlohmann::json> scan_document(std::string_view text,
                                            std::string_view* glb_buffer_length = nullptr);

/// Checks the JSON document before TinyGLTF reads it (TinyGLTF ignores properties of the wrong
/// type): the type of every property Tessera reads, extensionsRequired, and that each external
/// buffer and image file exists, is within options.max_file_bytes and, for buffers, holds
/// byteLength bytes. Warns for extensions used but ignored.
void check_document(const Context& ctx, const nlohmann::json& doc);

/// After TinyGLTF has refused `text`: fails with the glTF path of what TinyGLTF most likely
/// refused, where it finds one of the faults TinyGLTF checks before Tessera can (an index past
/// the accessors, a camera or spot light without its block, a byteStride or componentType glTF
/// does not allow, a data uri that is not base64); returns where it finds none, and the caller
/// passes TinyGLTF's own message on.
void explain_tinygltf_failure(const Context& ctx, std::string_view text);

/// An accessor's elements, count * components values, in one of three arrays. Float
/// accessors and unsigned integer ones that are not normalized, without sparse values, keep
/// their stored type (floats, uints; copied, not converted, which was a fifth of the import of a
/// large mesh); every other accessor is read as doubles (exact for every component type),
/// normalized integers mapped to [0, 1] or [-1, 1], sparse substitution applied. Each value
/// converts to the same double whichever array holds it, so a computation in double does not
/// depend on which one it reads (visit).
struct AccessorValues {
  size_t count = 0;
  int components = 0;
  std::vector<double> values;
  std::vector<float> floats;
  std::vector<uint32_t> uints;
  // Tightly packed float values left in the model's buffer, which outlives this, and read in
  // place (PackedFloats) instead of being copied into `floats`; null for the others.
  const unsigned char* packed = nullptr;
};

/// Element i of tightly packed floats in a buffer: the float at byte 4 i, loaded with memcpy
/// (the buffer holds bytes, not float objects).
struct PackedFloats {
  const unsigned char* bytes;
  float operator[](size_t i) const {
    float v;
    std::memcpy(&v, bytes + 4 * i, sizeof v);
    return v;
  }
};

/// f(values) with `values` indexable as the flat array of `v`'s values: PackedFloats, or a
/// const float*, const uint32_t* or const double* to the array of `v` that holds them.
template <typename F>
decltype(auto) visit(const AccessorValues& v, F&& f) {
  if (v.packed) return f(PackedFloats{v.packed});
  if (!v.floats.empty()) return f(v.floats.data());
  if (!v.uints.empty()) return f(v.uints.data());
  return f(v.values.data());
}

/// accessors[index], referenced from `where`, after the checks read_accessor makes before it
/// reads a byte: the index, that its type is one of `types` (TINYGLTF_TYPE_*), that its
/// componentType is one glTF defines, and that only byte and short components are normalized.
/// A caller that allows fewer component types (indices, vertex attributes) checks them between
/// this and read_accessor, so that a type it refuses is named as such, and not as 4-byte reads
/// running past a view sized for the type the file should have had.
const tinygltf::Accessor& checked_accessor(const Context& ctx, const tinygltf::Model& model,
                                           int index, const std::string& where,
                                           std::initializer_list<int> types);

/// Reads accessors[index], referenced from `where`, after checked_accessor, checking the buffer
/// view and buffer ranges, stride, size arithmetic and sparse indices; `types` lists the
/// allowed accessor types (TINYGLTF_TYPE_*).
AccessorValues read_accessor(const Context& ctx, const tinygltf::Model& model, int index,
                             const std::string& where, std::initializer_list<int> types);

/// Bytes of bufferViews[index], referenced from `where`, after checking its range in its buffer.
std::pair<const unsigned char*, size_t> buffer_view_bytes(const Context& ctx,
                                                          const tinygltf::Model& model, int index,
                                                          const std::string& where);

/// How one primitive becomes a Tessera mesh.
struct PrimitiveOptions {
  bool uv1 = false;  // TEXCOORD_1 read as Mesh::uvs1 (a texture of the material reads set 1)
  glm::mat3 uv_transform[2]{glm::mat3(1), glm::mat3(1)};  // KHR_texture_transform of each set
  // Tangents are generated (when TANGENT is absent) only for a material with a normal map, the
  // one reader of tangents: elsewhere they cost a fifth of the import and change no pixel.
  bool tangents = false;
  int tangent_set = 0;         // the uv set tangents are generated from (the normal map's)
  std::string material_where;  // the material's glTF path, for messages
};

/// Converts meshes[mesh].primitives[primitive] (TRIANGLES, TRIANGLE_STRIP or TRIANGLE_FAN,
/// indexed or not) into a Mesh with unit normals (flat ones generated when NORMAL is absent),
/// uvs (TEXCOORD_0, none where absent; TEXCOORD_1 as uvs1 where options.uv1) and tangents (TANGENT,
/// or generated where options.tangents).
Mesh convert_primitive(const Context& ctx, const tinygltf::Model& model, int mesh, int primitive,
                       const PrimitiveOptions& options);

/// glTF materials and textures turned into Tessera's, created on first use.
struct MaterialTable {
  std::map<int, uint32_t> materials;  // glTF material (-1: the default) -> Scene::materials
  std::map<int, PrimitiveOptions> uv_options;  // glTF material -> its uv set and transform
  std::map<int, Texture> images;               // decoded images (RGBA8, srgb unset)
  // (image, srgb, occlusion strength, wrap modes u | v << 2)
  std::map<std::tuple<int, bool, float, int>, uint32_t> textures;
};

/// Decodes every image that a texture names, in parallel on every core, into table.images. An
/// image that fails is left out (decoded_image, reached through material_index, then fails
/// naming it, where and as it would have without this step).
void decode_images(const Context& ctx, const tinygltf::Model& model, MaterialTable& table);

/// Scene::materials index of glTF material `material` (-1: the glTF default material), adding
/// it and its textures to `scene` on first use; fills table.uv_options for it. `doc` is the
/// checked JSON document (check_document), `model` TinyGLTF's reading of it.
uint32_t material_index(const Context& ctx, const nlohmann::json& doc, const tinygltf::Model& model,
                        int material, MaterialTable& table, Scene& scene);

}  // namespace tessera::gltf
