#pragma once
// Importers of model files (glTF 2.0, OBJ/MTL) into Tessera's scene model.
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>
#include "core/scene.h"
namespace tessera {
struct ImportOptions {
  bool strict = false;  // warnings become errors
  uint64_t max_file_bytes =
      2ull << 30;  // files (and each buffer/image they reference) above this are refused
  uint32_t max_texture_side = kMaxTextureSide;
};
/// Where the parts of an imported scene come from in their file, for the checks that only the
/// scene a model is placed in can make (validate_scene's limits on positions, light intensities
/// and ranges): a scene file names the model file and these places beside its own (glTF JSON
/// paths; empty for OBJ, whose vertex lines obj_vertex_line finds).
struct ImportedPlaces {
  std::vector<std::string> objects;  // per scene.objects: the node that places it ("nodes[1]")
  std::vector<std::string> meshes;   // per scene.meshes: its primitive ("meshes[0].primitives[0]")
  /// Per scene.meshes: vertex i is element i of the primitive's POSITION accessor (false where
  /// flat normals were generated, which gives each triangle its own vertices).
  std::vector<bool> vertices_are_elements;
  /// Per scene.lights: the node that places it, and the light ("extensions.KHR_lights_punctual.
  /// lights[0]"), whose intensity and range the scene's limits apply to.
  std::vector<std::pair<std::string, std::string>> lights;
  std::vector<std::pair<std::string, std::string>> cameras;  // per camera: node, "cameras[0]"
};

struct ImportedModel {
  Scene scene;  // meshes, materials, textures, objects (world transforms), lights; scene.camera
                // unused
  std::vector<Camera> cameras;        // the file's cameras in file order (glTF), empty for OBJ
  std::vector<std::string> warnings;  // each names the file and place
  ImportedPlaces places;
};
/// Each throws tessera::Error naming the file, the place and what is wrong.
ImportedModel import_gltf(const std::string& path, const ImportOptions& options = {});
ImportedModel import_obj(const std::string& path, const ImportOptions& options = {});

/// The line of the first `v` statement of the OBJ file `path` whose position (x y z, as the
/// importer reads them) `pick` accepts, or 0 where none does or the file cannot be read: for
/// messages about a vertex that a scene file places out of range.
size_t obj_vertex_line(const std::string& path, const std::function<bool(glm::vec3)>& pick);

/// The same for a file held in memory (a .gltf's text or a whole .glb; an OBJ's text): `name`
/// stands for the file in messages, and the files it names (buffers, images, material
/// libraries) are found relative to the folder `base_dir`. `bytes` and `text` are only read
/// during the call; options.max_file_bytes applies to them as to a file.
ImportedModel import_gltf_bytes(const std::vector<unsigned char>& bytes, const std::string& name,
                                const std::string& base_dir, const ImportOptions& options = {});
ImportedModel import_obj_text(const std::string& text, const std::string& name,
                              const std::string& base_dir, const ImportOptions& options = {});

/// The extension of `path` in lower case (".GLB" as ".glb": files from Windows tools often
/// carry upper-case ones), which is how the importers above are chosen: ".gltf" and ".glb" for
/// import_gltf, ".obj" for import_obj.
inline std::string model_extension(const std::string& path) {
  const size_t dot = path.find_last_of("./");
  std::string ext = dot == std::string::npos || path[dot] == '/' ? "" : path.substr(dot);
  for (char& c : ext) c = char(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  return ext;
}
}  // namespace tessera
