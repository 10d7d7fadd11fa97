#pragma once
// Importers of model files (glTF 2.0, OBJ/MTL) into Tessera's scene model.
#include <cstdint>
#include <string>
#include <vector>
#include "core/scene.h"
namespace tessera {
struct ImportOptions {
  bool strict = false;  // warnings become errors
  uint64_t max_file_bytes =
      2ull << 30;  // files (and each buffer/image they reference) above this are refused
  uint32_t max_texture_side = kMaxTextureSide;
};
struct ImportedModel {
  Scene scene;  // meshes, materials, textures, objects (world transforms), lights; scene.camera
                // unused
  std::vector<Camera> cameras;        // the file's cameras in file order (glTF), empty for OBJ
  std::vector<std::string> warnings;  // each names the file and place
};
/// Each throws tessera::Error naming the file, the place and what is wrong.
ImportedModel import_gltf(const std::string& path, const ImportOptions& options = {});
ImportedModel import_obj(const std::string& path, const ImportOptions& options = {});

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
