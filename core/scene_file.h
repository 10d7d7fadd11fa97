#pragma once
// Tessera's own JSON scene format (docs/scene-format.md, docs/scene-format.schema.json): a
// camera, lights, textures, materials, meshes (built-in shapes, inline triangles or model
// files), objects and instancing generators, environment, and optional render defaults.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/scene.h"
#include "core/texture.h"

namespace tessera {

struct SceneFileOptions {
  bool strict = false;                    // unknown keys (and importer warnings) become errors
  uint64_t max_file_bytes = 64u << 20;    // the scene file itself; larger files are refused
  uint64_t max_model_bytes = 2ull << 30;  // each model, texture or environment file it names
  uint64_t max_objects = 1u << 24;        // objects after instancing and model expansion
  uint64_t max_mesh_vertices = 1u << 26;  // per mesh (built-in shapes and inline meshes)
  uint32_t max_texture_side = kMaxTextureSide;
};

/// The "render" block: each member set only if the file gives it.
struct RenderDefaults {
  std::optional<uint32_t> width, height;
  std::optional<float> exposure_ev;
  std::optional<ToneMap> tonemap;
  std::optional<Brdf> brdf;
  std::optional<bool> energy_compensation;
  std::optional<View> view;
  /// "FILE:LINE:COLUMN: render: " where the file gives width or height, "" if it gives
  /// neither: for a command to place a size the device cannot render.
  std::string size_place;
};

struct SceneFile {
  Scene scene;  // has passed validate_scene
  RenderDefaults render;
  std::string description;            // the file's "description", or ""
  std::vector<std::string> warnings;  // each "FILE:LINE:COLUMN: PATH: what"
  /// The cameras the file's models bring (glTF's perspective cameras), in "models" order and
  /// each model's file order, placed as the model's first instance is (as the model file has
  /// them where no object places it); model_camera_names says whose each is ("model 'engine'
  /// camera 0"). scene.camera is the file's "camera" block; commands pick one of these
  /// instead with --camera N.
  std::vector<Camera> model_cameras;
  std::vector<std::string> model_camera_names;
  /// Where each of scene.lights comes from, "FILE:LINE:COLUMN: PATH: " (its "lights" entry, or
  /// the "models" entry of the model that brought it): for a command that moves the lights
  /// (`tessera bench`) to place a message about one. Empty for load_model_scene.
  std::vector<std::string> light_places;
};

/// Reads the scene file at `path`. Files it names (textures, models, environments) are found
/// relative to its folder. Throws tessera::Error "FILE:LINE:COLUMN: PATH: what is wrong" for
/// unreadable, oversized or malformed files, wrong types, values out of range, NaN or
/// infinite numbers, unknown names, counts over the limits, and files it names that fail to
/// load; nothing is returned partially.
SceneFile load_scene_file(const std::string& path, const SceneFileOptions& options = {});

/// The same for a text held in memory; `name` is used in messages and files are found
/// relative to `base_dir`.
SceneFile load_scene_text(const std::string& text, const std::string& name,
                          const std::string& base_dir, const SceneFileOptions& options = {});

/// A model file (.gltf, .glb or .obj, in either case) as a scene: the scene of a scene file
/// whose "models" entry names `path` and whose one object places it as it is, with the model's
/// lights and cameras (SceneFile::model_cameras) and the default camera, background and
/// ambient. Messages name the model file and the place in it, not that scene file, which no
/// one wrote. Throws Error as load_scene_file does.
SceneFile load_model_scene(const std::string& path, const SceneFileOptions& options = {});

/// The "description" of the scene file at `path` without loading the scene ("" if it has
/// none, or if the file cannot be read or parsed: for listings).
std::string read_scene_description(const std::string& path);

/// The random numbers of the "random" generator, reproducible on every platform: the 32-bit
/// outputs x of std::mt19937 (whose sequence the C++ standard fixes), mapped to [0, 1) as
/// float(x) * 2^-32, rounded to nearest, and 1 replaced by the largest float below 1.
float uniform_float(uint32_t x);

}  // namespace tessera
