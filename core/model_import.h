#pragma once
// Importers of model files (glTF 2.0, OBJ/MTL) into Tessera's scene model.
#include <cstdint>
#include <string>
#include <vector>
#include "core/scene.h"
namespace tessera {
struct ImportOptions {
  bool strict = false;                       // warnings become errors
  uint64_t max_file_bytes = 2ull << 30;      // files (and each buffer/image they reference) above this are refused
  uint32_t max_texture_side = kMaxTextureSide;
};
struct ImportedModel {
  Scene scene;                      // meshes, materials, textures, objects (world transforms), lights; scene.camera unused
  std::vector<Camera> cameras;      // the file's cameras in file order (glTF), empty for OBJ
  std::vector<std::string> warnings;  // each names the file and place
};
/// Each throws tessera::Error naming the file, the place and what is wrong.
ImportedModel import_gltf(const std::string& path, const ImportOptions& options = {});
ImportedModel import_obj(const std::string& path, const ImportOptions& options = {});
}  // namespace tessera
