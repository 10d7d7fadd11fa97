#pragma once
// What `tessera bench --scene FILE` places N times on the grid family's layout: a scene file's
// scene or a model file's, with what its messages need to name the file and the place in it.

#include <cstdint>
#include <string>

#include "core/model_import.h"
#include "core/scene.h"

namespace tessera {

struct BenchContent {
  Scene scene;            // has passed validate_scene
  std::string file;       // as given
  bool model = false;     // a model file (else a scene file)
  bool obj = false;       // an OBJ model
  ImportedPlaces places;  // a model's, for messages
  // A scene file's: where each light is given, "FILE:LINE:COLUMN: PATH: " (SceneFile).
  std::vector<std::string> light_places;
};

/// The scene of a scene file (load_scene_argument) or of a model file (import_gltf,
/// import_obj, by extension). Warnings are printed to stderr unless `quiet`; with `strict` they
/// are errors. A model is held to the scene's limits (validate_scene) as a scene file that
/// places it once, unmoved, would hold it: Error "FILE: PLACE: invalid scene: ..." names the
/// model file and the place in it, as a scene file's message does after its own place. Throws
/// what the loaders throw.
BenchContent load_bench_content(const std::string& path, bool strict, bool quiet);

/// Throws Error "--objects N: FILE: PLACE: invalid scene: light K ...; ..." when the lights of
/// `copies` copies (instanced_bench_lights, core/bench_scenes.h) are past validate_scene's
/// limits, which the content's own are not: the message says by how much placing the copies
/// scaled the value it names.
void check_bench_lights(const BenchContent& content, uint32_t copies, float aspect);

}  // namespace tessera
