#pragma once
// validate_scene's messages about the parts a model file brought, placed in that file: a
// scene's limits apply to a model only once it is placed (in a scene file, or by the bench), so
// the message names the model file and where in it the object or light comes from.
#include <cstddef>
#include <string>

#include "core/model_import.h"
#include "core/scene.h"

namespace tessera {

/// "FILE: PLACE: " as the model file's importer names a place in it (glTF: a JSON path, left
/// out where `place` is empty; OBJ: 'FILE' line N, or 'FILE' alone for line 0).
std::string model_file_place(const std::string& file, bool obj, const std::string& place,
                             size_t line = 0);

/// Where one placed copy of a model is in a scene.
struct ModelInScene {
  std::string file;  // as messages name it; an OBJ is read again to find a vertex's line
  bool obj = false;
  const ImportedPlaces* places = nullptr;  // the importer's, for `file`
  size_t first_object = 0, objects = 0;    // its objects in scene.objects
  size_t first_mesh = 0;                   // where its meshes start in scene.meshes
  size_t first_light = 0, lights = 0;      // its lights in scene.lights
};

/// validate_scene's `message` ("invalid scene: object K ...", "invalid scene: light K ...")
/// about one of m's objects or lights in `scene`, with the model file's place of it before it
/// (the node and primitive of an object, the light's intensity or range, a light's node) and,
/// for an object, its first vertex out of range after it; "" where the message is about none of
/// m's parts or the place is not known.
std::string model_part_message(const Scene& scene, const ModelInScene& m,
                               const std::string& message);

}  // namespace tessera
