#include "host/scene_source.h"

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "core/builtin_scenes.h"
#include "core/check.h"
#include "core/closest_name.h"
#include "core/file_extension.h"
#include "core/light_floor.h"
#include "core/model_import.h"
#include "core/orbit_camera.h"
#include "host/cli.h"

namespace tessera {
namespace fs = std::filesystem;

std::string scenes_variable_problem() {
  const char* env = std::getenv("TESSERA_SCENES");
  if (!env || !*env) return "";
  std::error_code ec;
  std::string why;
  if (!fs::exists(env, ec)) {
    why = "does not exist";
  } else if (!fs::is_directory(env, ec)) {
    why = "is not a folder";
  } else {
    fs::directory_iterator(env, ec);
    if (ec) why = "cannot be read (" + ec.message() + ")";
  }
  if (why.empty()) return "";
  return "TESSERA_SCENES is '" + std::string(env) + "', which " + why +
         "; scenes are looked for in the other scene folders";
}

std::vector<std::string> scene_folders() {
  std::vector<std::string> folders;
  if (const char* env = std::getenv("TESSERA_SCENES"); env && *env) {
    // Said once per run: a misspelt folder was passed over without a word, and the scenes of
    // the next folder listed and loaded as if they were the ones asked for.
    static const bool warned = [] {
      if (const std::string problem = scenes_variable_problem(); !problem.empty())
        std::fprintf(stderr, "tessera: warning: %s\n", problem.c_str());
      return true;
    }();
    (void)warned;
    folders.push_back(env);
  }
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) folders.push_back((exe.parent_path().parent_path() / "share/tessera/scenes").string());
  folders.push_back(TESSERA_SOURCE_SCENES_DIR);
  return folders;
}

bool is_scene_path(const std::string& argument) {
  return argument.find('/') != std::string::npos || has_extension(argument, ".json");
}

bool is_named_scene(const std::string& name) {
  for (const std::string& folder : scene_folders())
    if (fs::is_regular_file(fs::path(folder) / (name + ".json"))) return true;
  return false;
}

std::vector<std::string> known_scene_names() {
  std::set<std::string> names;
  for (const auto& s : builtin_scenes()) names.insert(std::string(s.name));
  for (const std::string& folder : scene_folders()) {
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) continue;
    for (const auto& e : fs::directory_iterator(folder, ec)) {
      if (e.path().extension() == ".json") names.insert(e.path().stem().string());
    }
  }
  return {names.begin(), names.end()};
}

namespace {
Error unsupported_format(const std::string& path) {
  return Error("'" + path +
               "' is a file of a format Tessera does not read: give a scene file (.json) or a "
               "model (.gltf, .glb or .obj)");
}
}  // namespace

void check_scene_file_format(const std::string& path) {
  if (has_extension(path, ".json") || is_model_path(path)) return;
  if (fs::path(path).extension().empty()) return;
  std::ifstream in(path, std::ios::binary);
  char c = 0;
  while (in.get(c) && std::isspace(static_cast<unsigned char>(c))) {
  }
  if (!in || c != '{') throw unsupported_format(path);
}

void check_scene_name(const std::string& name) {
  if (is_builtin_scene(name) || is_named_scene(name)) return;
  // A file of a format Tessera does not read ("box.fbx" in the working folder) is not a
  // misspelt scene name: say what it reads.
  std::error_code ec;
  if (fs::is_regular_file(name, ec)) throw unsupported_format(name);
  std::string known;
  const std::vector<std::string> names = known_scene_names();
  for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
  const std::string near = closest_name(name, names);
  throw Error("unknown scene '" + name + "' (known scenes: " + known + "; or a scene file's path)" +
              (near.empty() ? "" : ", did you mean '" + near + "'?"));
}

bool is_model_path(const std::string& argument) {
  const std::string ext = model_extension(argument);
  return ext == ".gltf" || ext == ".glb" || ext == ".obj";
}

void use_model_camera(SceneFile& file, uint32_t index, const std::string& help_command) {
  const size_t count = file.model_cameras.size();
  if (index < count) {
    file.scene.camera = file.model_cameras[index];
    return;
  }
  std::string listed;
  for (size_t i = 0; i < count; ++i)
    listed += (i ? ", " : "") + std::to_string(i) + ": " + file.model_camera_names[i];
  // A bad command line, though found only once the scene is loaded: the scene is as it should
  // be, the number asked for is not one of its cameras.
  throw UsageError(
      "--camera " + std::to_string(index) + ": " +
          (count == 0 ? std::string("the scene's models bring no cameras (glTF files can)")
                      : "the scene's models bring " + std::to_string(count) + " camera" +
                            (count == 1 ? "" : "s") + " (" + listed + ")"),
      help_command);
}

void frame_model_camera(Scene& scene, const std::string& name, bool camera_given, uint32_t width,
                        uint32_t height) {
  if (!is_model_path(name) || camera_given) return;
  scene.camera = framed_camera(scene, float(width) / float(height));
}

std::string light_unlit_model(Scene& scene, const std::string& name) {
  if (!scene.lights.empty()) return "";
  // A directional light, unlike a point light, lights a model of any size alike.
  Light sun;
  sun.kind = LightKind::directional;
  sun.direction = glm::normalize(glm::vec3(-0.5f, -0.8f, -0.6f));
  sun.intensity = 2.5f;
  scene.lights.push_back(sun);
  scene.ambient = glm::max(scene.ambient, glm::vec3(0.08f));
  return "note: " + name +
         " has no lights: lit by the sun of the built-in scene 'textured' (directional, "
         "intensity 2.5, from above, right and front) and its ambient light 0.08";
}

SceneFile load_scene_argument(const std::string& name_or_file, bool strict, bool quiet) {
  SceneFileOptions options;
  options.strict = strict;
  if (is_model_path(name_or_file)) {
    SceneFile file = load_model_scene(name_or_file, options);
    if (!quiet)
      for (const std::string& w : file.warnings)
        std::fprintf(stderr, "tessera: warning: %s\n", w.c_str());
    const std::string note = light_unlit_model(file.scene, name_or_file);
    if (!note.empty() && !quiet) std::fprintf(stderr, "tessera: %s\n", note.c_str());
    return file;
  }
  std::string path = is_scene_path(name_or_file) ? name_or_file : "";
  for (const std::string& folder : scene_folders()) {
    if (!path.empty()) break;
    if (fs::is_regular_file(fs::path(folder) / (name_or_file + ".json")))
      path = (fs::path(folder) / (name_or_file + ".json")).string();
  }
  SceneFile file;
  if (path.empty()) {
    // No scenes folder (a binary moved without share/): the same scene from code.
    check_scene_name(name_or_file);
    file.scene = make_builtin_scene(name_or_file);
    return file;
  }
  file = load_scene_file(path, options);
  if (!quiet)
    for (const std::string& w : file.warnings)
      std::fprintf(stderr, "tessera: warning: %s\n", w.c_str());
  return file;
}

std::string unlit_scene_note(const Scene& scene, const std::string& name, View view,
                             bool env_removed) {
  // Valid (a scene being built, a background alone), so a note; and not "its objects are
  // black", which spoke of objects there are none of.
  if (scene.objects.empty())
    return "note: " + name + " has no objects: the image shows only the background";
  if (view != View::shaded || has_light(scene)) return "";
  if (env_removed)
    return "note: --env none removed the environment that lit " + name +
           ", which has no lights, ambient light or emissive material: its objects are black";
  return "note: " + name +
         " has no lights, ambient light, environment or emissive material: its objects are black";
}

std::string coarse_positions_note(const Scene& scene, const std::string& name) {
  const CoarsePositions c = coarse_positions(scene);
  if (c.count == 0) return "";
  const auto number = [](const char* format, double value) {
    char text[64];
    std::snprintf(text, sizeof text, format, value);
    return std::string(text);
  };
  // Past its size the spacing is a multiple of it, not a fraction ("1/0").
  const std::string share = c.spacing < c.size
                                ? "1/" + number("%.0f", c.size / c.spacing) + " of its size"
                                : number("%.3g", c.spacing / c.size) + " times its size";
  return "note: object " + std::to_string(c.first) + " of " + name + " lies " +
         number("%g", c.distance) + " m from the origin, where 32-bit positions are " +
         number("%g", c.spacing) + " m apart, " + share +
         (c.count > 1 ? ", as " + std::to_string(c.count - 1) + " more objects are" : "") +
         ": the GPU shades it with stripes and a stepped outline, or loses it where that "
         "spacing nears its size (the CPU reference, in double, does not); model the scene "
         "around the origin (docs/scene-format.md)";
}

std::string near_lights_note(const Scene& scene, const std::string& name) {
  const NearLights near = lights_within_floor(scene);
  if (near.count == 0) return "";
  char distance[64];
  std::snprintf(distance, sizeof distance, "%g", near.distance);
  const size_t more = near.count - 1;
  return "note: light " + std::to_string(near.light) + " of " + name + " lies " + distance +
         " m from object " + std::to_string(near.object) +
         (near.exact ? "" : " (its bounding box: too many triangles to measure them all)") +
         (more ? ", as " + std::to_string(more) +
                     (more == 1 ? " more light lies" : " more lights lie") +
                     " within 1 cm of an object"
               : "") +
         ": the shading treats distances below 1 cm as 1 cm, so surfaces nearer receive less "
         "than intensity / d^2, and a scene modelled below centimetre scale renders too "
         "dark unless scaled up (lengths by k, intensities by k^2; docs/shading.md)";
}

std::string scene_file_summary(const std::string& path) {
  // Loaded, not only parsed: a file that parses can still fail to load (a missing model, a
  // value out of range), and a listed scene that then fails surprised. Warnings are dropped:
  // loading the scene says them.
  try {
    load_scene_file(path);
  } catch (const Error& e) {
    // The path is the listing's heading; the error after it (line and column, what is wrong).
    std::string message = e.what();
    if (message.starts_with(path + ":"))
      message = fs::path(path).filename().string() + message.substr(path.size());
    return "(cannot be loaded: " + message + ")";
  }
  return read_scene_description(path);
}

std::string scene_listing() {
  // Every folder `--scene NAME` searches, in its order: TESSERA_SCENES listed alone hid the
  // built-in scenes that still load. A name an earlier folder also holds is found there.
  std::string out;
  std::map<std::string, std::string> first_folder;  // scene name -> the folder it loads from
  for (const std::string& folder : scene_folders()) {
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) continue;
    std::set<fs::path> files;
    for (const auto& e : fs::directory_iterator(folder, ec))
      if (e.path().extension() == ".json") files.insert(e.path());
    if (files.empty()) continue;
    out += (out.empty() ? "" : "\n") + std::string("scene files in ") + folder + ":\n";
    for (const fs::path& f : files) {
      char line[512];
      const std::string name = f.stem().string();
      std::snprintf(line, sizeof line, "%-12s ", name.c_str());
      const auto [it, first] = first_folder.emplace(name, folder);
      out += line +
             (first ? scene_file_summary(f.string())
                    : "(not loaded by name: " + it->second + " has '" + name + "' first)") +
             "\n";
    }
  }
  if (!out.empty()) return out;
  for (const auto& s : builtin_scenes()) {
    char line[512];
    std::snprintf(line, sizeof line, "%-12s %s\n", std::string(s.name).c_str(),
                  std::string(s.description).c_str());
    out += line;
  }
  return out;
}

void apply_render_defaults(const RenderDefaults& r, FrameSettings& frame, bool size_given,
                           bool exposure_given, bool tonemap_given, bool brdf_given,
                           bool view_given) {
  if (!size_given) {
    frame.width = r.width.value_or(frame.width);
    frame.height = r.height.value_or(frame.height);
  }
  if (!exposure_given) frame.exposure_ev = r.exposure_ev.value_or(frame.exposure_ev);
  if (!tonemap_given) frame.tonemap = r.tonemap.value_or(frame.tonemap);
  if (!brdf_given) frame.brdf = r.brdf.value_or(frame.brdf);
  if (!view_given) frame.view = r.view.value_or(frame.view);
  frame.energy_compensation = frame.energy_compensation || r.energy_compensation.value_or(false);
}

}  // namespace tessera
