#include "host/bench_content.h"

#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "core/bench_scenes.h"
#include "core/check.h"
#include "core/model_place.h"
#include "host/scene_source.h"

namespace tessera {
namespace {

// Where a model's parts are in a scene made of it alone, or of its lights alone.
ModelInScene whole_model(const BenchContent& c, const Scene& scene) {
  return {c.file, c.obj, &c.places, 0, scene.objects.size(), 0, 0, scene.lights.size()};
}

// validate_scene's `message` about `scene` (the content's or its lights'), after the file and,
// for a model, the place in it.
std::string placed(const BenchContent& c, const Scene& scene, const std::string& message) {
  if (c.model)
    if (std::string s = model_part_message(scene, whole_model(c, scene), message); !s.empty())
      return s;
  return c.file + ": " + message;
}

std::string number(float v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// What placing the copies by `k` did to the value validate_scene's `message` about `light` names.
std::string scaled(const std::string& message, const Light& light, float k) {
  if (message.find(" intensity times color is ") != std::string::npos &&
      light.falloff == Falloff::inverse_square && light.kind != LightKind::directional)
    return "scaled it by " + number(k * k) + " (" + number(k) + " squared)";
  if (message.find(" range is ") != std::string::npos) return "scaled it by " + number(k);
  if (message.find(" position is ") != std::string::npos)
    return "moved it " + number(k) + " times as far from the centre of the file's objects";
  if (message.find(" attenuation ") != std::string::npos)
    return "scaled its Kl by 1/" + number(k) + " and its Kq by 1/" + number(k * k);
  return "scaled its position (from the centre of the file's objects) and range by " + number(k) +
         " and an inverse-square intensity by " + number(k * k);
}

}  // namespace

BenchContent load_bench_content(const std::string& path, bool strict, bool quiet) {
  BenchContent c;
  c.file = path;
  if (!is_model_path(path)) {
    SceneFile file = load_scene_argument(path, strict, quiet);
    c.scene = std::move(file.scene);
    c.light_places = std::move(file.light_places);
    return c;
  }
  ImportOptions options;
  options.strict = strict;
  c.model = true;
  c.obj = model_extension(path) == ".obj";
  ImportedModel model = c.obj ? import_obj(path, options) : import_gltf(path, options);
  if (!quiet)
    for (const std::string& w : model.warnings)
      std::fprintf(stderr, "tessera: warning: %s\n", w.c_str());
  c.scene = std::move(model.scene);
  c.places = std::move(model.places);
  // The scene's limits, on the model as the file gives it: as render holds a scene file that
  // places it unmoved, and before the bench's placement scales it (a vertex at 2e15 m would
  // reach the grid only as float rounding).
  try {
    validate_scene(c.scene);
  } catch (const Error& e) {
    throw Error(placed(c, c.scene, e.what()));
  }
  return c;
}

void check_bench_lights(const BenchContent& content, uint32_t copies, float aspect) {
  if (content.scene.lights.empty()) return;  // the copies get the grid family's four
  const InstancedLights moved = instanced_bench_lights(content.scene, copies, aspect);
  Scene lights;
  lights.lights = moved.lights;
  try {
    validate_scene(lights);
  } catch (const Error& e) {
    const std::string message = e.what(), prefix = "invalid scene: light ";
    size_t k = 0;
    if (message.rfind(prefix, 0) == 0)
      k = std::strtoull(message.c_str() + prefix.size(), nullptr, 10);
    const Light& light = content.scene.lights[k < content.scene.lights.size() ? k : 0];
    // A scene file's light is named by its entry's line, as load_scene_file names it.
    const std::string where = !content.model && k < content.light_places.size()
                                  ? content.light_places[k] + message
                                  : placed(content, lights, message);
    throw Error("--objects " + std::to_string(copies) + ": " + where +
                "; the file's value is within the limits, but the bench " +
                scaled(message, light, moved.length) + ": it moves the file's lights with its " +
                std::to_string(copies) + " cop" + (copies == 1 ? "y" : "ies") +
                " on the grid, so that they light each copy as they lit the file's objects");
  }
}

}  // namespace tessera
