#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include <unistd.h>

#include <GLFW/glfw3.h>

#include "core/check.h"
#include "core/materials.h"
#include "core/pick.h"
#include "core/scene_file_write.h"
#include "host/scene_source.h"
#include "host/viewer.h"

namespace tessera {
namespace {

// A scripted fly key moves the camera as if held this long.
constexpr float kScriptedFlySeconds = 0.1f;

void log(const Viewer& v, const std::string& what) {
  std::printf("frame %" PRIu64 ": %s\n", v.frame_number, what.c_str());
}

Viewport viewport_of(const Viewer& v) {
  int w = 0, h = 0;
  glfwGetWindowSize(v.window->handle, &w, &h);
  return {uint32_t(std::max(w, 1)), uint32_t(std::max(h, 1))};
}

// The renderer takes the camera with the scene (set_scene uploads only what changed). A move
// that leaves the camera where it was (a drag of no length, wheel 0, an orbit at the pole) is
// no change: nothing to upload, log or redraw. The orbit `before` is compared, not the scene's
// camera, which until the first move is the scene file's and may differ from to_camera of its
// orbit by a rounding.
void camera_moved(Viewer& v, const OrbitCamera& before) {
  const Camera moved = to_camera(v.orbit);
  if (moved == to_camera(before)) return;
  v.scene.camera = moved;
  mark_changed(v, "camera");
  const Camera& c = v.scene.camera;
  std::printf("frame %" PRIu64 ": camera position %.9g %.9g %.9g target %.9g %.9g %.9g\n",
              v.frame_number, c.position.x, c.position.y, c.position.z, c.target.x, c.target.y,
              c.target.z);
}

// From /proc/self/statm: its second number is the resident set in pages.
void print_resident_memory(Viewer& v) {
  unsigned long long pages_total = 0, pages_resident = 0;
  FILE* statm = std::fopen("/proc/self/statm", "r");
  const bool read = statm && std::fscanf(statm, "%llu %llu", &pages_total, &pages_resident) == 2;
  if (statm) std::fclose(statm);
  if (!read) return refuse(v, "resident memory unknown: /proc/self/statm cannot be read");
  log(v, "resident memory " +
             std::to_string(pages_resident * (unsigned long long)sysconf(_SC_PAGESIZE) / 1024) +
             " KiB");
}

// The framebuffer pixel under window position `at`, if inside the last frame.
bool pixel_under(const Viewer& v, glm::vec2 at, uint32_t& x, uint32_t& y) {
  const Viewport window = viewport_of(v);
  if (v.chain.extent.width == 0 || at.x < 0.0f || at.y < 0.0f) return false;
  x = uint32_t(at.x * float(v.chain.extent.width) / float(window.width));
  y = uint32_t(at.y * float(v.chain.extent.height) / float(window.height));
  return x < v.chain.extent.width && y < v.chain.extent.height;
}

// A scripted click can be given anywhere; one outside the window (as it is now: a resize
// may have shrunk it) picks nothing and is a script command that cannot be carried out.
bool inside_window(Viewer& v, const InputEvent& e) {
  const Viewport window = viewport_of(v);
  if (e.from.x >= 0.0f && e.from.y >= 0.0f && e.from.x < float(window.width) &&
      e.from.y < float(window.height))
    return true;
  char text[128];
  std::snprintf(text, sizeof(text), "click at %g %g: outside the %ux%u window", e.from.x, e.from.y,
                window.width, window.height);
  refuse(v, text);
  return false;
}

void pick(Viewer& v, glm::vec2 at) {
  uint32_t x = 0, y = 0;
  v.selected = -1;
  if (pixel_under(v, at, x, y)) {
    if (auto triangle = triangle_of_key(v.renderer->read_visibility_at(x, y)))
      v.selected = int(v.renderer->object_of_triangle(*triangle));
  }
  char text[96];
  if (v.selected < 0) {
    std::snprintf(text, sizeof(text), "click at %g %g: nothing under the cursor", at.x, at.y);
  } else {
    std::snprintf(text, sizeof(text), "click at %g %g: selected object %d", at.x, at.y, v.selected);
  }
  log(v, text);
}

// The world point the pixel under `at` shows: from the visibility key's depth (near / w, see
// shaders/setup_common.glsl), or at the target's depth where no triangle covers it.
glm::vec3 point_under(const Viewer& v, glm::vec2 at) {
  const Camera& c = v.scene.camera;
  const glm::vec3 forward = glm::normalize(c.target - c.position);
  float w = glm::dot(c.target - c.position, forward);
  uint32_t x = 0, y = 0;
  if (!pixel_under(v, at, x, y)) return c.target;
  const uint64_t key = v.renderer->read_visibility_at(x, y);
  if (key != kEmptyVisibilityKey) {
    const uint32_t bits = ~uint32_t(key >> 32);
    float depth = 0.0f;
    std::memcpy(&depth, &bits, sizeof(depth));
    w = c.near_plane / depth;
  }
  const glm::vec3 right = glm::normalize(glm::cross(forward, c.up));
  const glm::vec3 up = glm::cross(right, forward);
  const float t = std::tan(c.vertical_fov * 0.5f);
  const float aspect = float(v.chain.extent.width) / float(v.chain.extent.height);
  const float ndc_x = (float(x) + 0.5f) / float(v.chain.extent.width) * 2.0f - 1.0f;
  const float ndc_y = (float(y) + 0.5f) / float(v.chain.extent.height) * 2.0f - 1.0f;
  // Vulkan's y points down the image; the view's up points up.
  return c.position + w * (forward + ndc_x * t * aspect * right - ndc_y * t * up);
}

// Applies `edit` through the history (validated, undoable) and shows it next frame; false if
// it was refused. The render options as they are now belong to the state it makes.
bool edit(Viewer& v, const Edit& e) {
  try {
    v.history.apply(v.scene, e);
  } catch (const Error& error) {
    refuse(v, std::string("edit refused: ") + error.what());
    return false;
  }
  v.options_at[v.history.state()] = render_options_of(v.frame);
  mark_changed(v, e.label);
  return true;
}

// Render options as an edit of no scene operations, so that they share the undo history and
// the unsaved mark with the scene's edits. With `continuing` (a panel drag going on) and the
// last edit being the drag's, the options of that edit's state change instead: one undo step
// per drag.
void set_options(Viewer& v, const RenderOptions& options, const std::string& label,
                 bool continuing) {
  if (options == render_options_of(v.frame)) return;
  if (continuing && v.options_drag_state == v.history.state()) {
    set_render_options(v.frame, options);
    v.options_at[v.history.state()] = options;
    mark_changed(v, label);
    return;
  }
  const RenderOptions before = render_options_of(v.frame);
  set_render_options(v.frame, options);
  if (!edit(v, Edit{label, {}})) {
    set_render_options(v.frame, before);
    return;
  }
  v.options_drag_state = v.history.state();
  log(v, label);
}

// A scripted render option, as the panel sets it.
void edit_option(Viewer& v, const InputEvent& e) {
  RenderOptions o = render_options_of(v.frame);
  const char* brdfs[] = {"classic", "filament", "blinn-phong"};
  const char* tonemaps[] = {"aces", "reinhard", "clamp"};
  const char* views[] = {"shaded", "normal", "uv", "triangle", "object"};
  std::string label;
  if (e.field == "brdf") {
    o.brdf = Brdf(e.index);
    label = std::string("BRDF ") + brdfs[e.index];
  } else if (e.field == "tonemap") {
    o.tonemap = ToneMap(e.index);
    label = std::string("tone map ") + tonemaps[e.index];
  } else if (e.field == "view") {
    o.view = View(e.index);
    label = std::string("view ") + views[e.index];
  } else if (e.field == "energy_compensation") {
    o.energy_compensation = e.index != 0;
    label = e.index ? "energy compensation on" : "energy compensation off";
  } else {
    o.exposure_ev = e.value.x;
    char text[48];
    std::snprintf(text, sizeof(text), "exposure %g EV", e.value.x);
    label = text;
  }
  if (o == render_options_of(v.frame)) return log(v, label + ": already so, nothing to undo");
  set_options(v, o, label, false);
}

bool has_selection(Viewer& v, const char* action) {
  if (v.selected >= 0) return true;
  refuse(v, std::string("no object selected to ") + action);
  return false;
}

void set_selected_material(Viewer& v, const Material& m) {
  if (!has_selection(v, "change the material of")) return;
  // The same material again is no edit (no undo step, no unsaved mark).
  if (v.scene.materials[v.scene.objects[size_t(v.selected)].material] == m) return;
  edit(v, set_object_material(v.scene, uint32_t(v.selected), m));
}

// A scripted material edit, as the panel's editor would make it.
void edit_material(Viewer& v, const InputEvent& e) {
  if (!has_selection(v, "change the material of")) return;
  Material m = v.scene.materials[v.scene.objects[size_t(v.selected)].material];
  if (e.field == "preset") {
    m = metal_material(e.path, m.roughness);
  } else if (e.field == "base_color") {
    m.base_color = e.value;
  } else if (e.field == "emissive") {
    m.emissive = e.value;
  } else if (e.field == "metallic") {
    m.metallic = e.value.x;
  } else if (e.field == "roughness") {
    m.roughness = e.value.x;
  }
  set_selected_material(v, m);
}

// A scripted light edit, as the panel's light list makes it.
void edit_light(Viewer& v, const InputEvent& e) {
  PanelChanges c;
  if (e.field == "add") {
    c.add_light = true;
  } else if (e.index >= v.scene.lights.size()) {
    refuse(v, "no light " + std::to_string(e.index) + " (the scene has " +
                  std::to_string(v.scene.lights.size()) + ")");
    return;
  } else if (e.field == "delete") {
    c.delete_light = true;
    c.light_index = e.index;
  } else {
    Light light = v.scene.lights[e.index];
    if (e.field == "position") light.position = e.value;
    if (e.field == "color") light.color = e.value;
    if (e.field == "intensity") light.intensity = e.value.x;
    c.light = light;
    c.light_index = e.index;
  }
  apply_panel_changes(v, c);
}

// The selected object's transform with its origin moved to `point`.
glm::mat4 placed_at(const Viewer& v, uint32_t object, glm::vec3 point) {
  glm::mat4 transform = v.scene.objects[object].transform;
  transform[3] = glm::vec4(point, 1.0f);
  return transform;
}

void undo_or_redo(Viewer& v, bool redo) {
  const std::string label = redo ? v.history.redo_label() : v.history.undo_label();
  if (!(redo ? v.history.redo(v.scene) : v.history.undo(v.scene))) {
    refuse(v, redo ? "nothing to redo" : "nothing to undo");
    return;
  }
  // Indices may have shifted: an undone add or redone delete removes an object.
  if (v.selected >= int(v.scene.objects.size())) v.selected = -1;
  // Every state reached through the history has its render options.
  if (auto it = v.options_at.find(v.history.state()); it != v.options_at.end())
    set_render_options(v.frame, it->second);
  v.options_drag_state = ~0ull;
  mark_changed(v, (redo ? "redo " : "undo ") + label);
}

// The scene file's "render" block with the render options as they are now: each option the
// file gave, or that differs from the tool's default.
RenderDefaults render_block(const Viewer& v) {
  RenderDefaults r = v.render_defaults;
  const FrameSettings defaults;
  auto keep = [](auto& field, auto value, auto default_value) {
    if (field || value != default_value) field = value;
  };
  keep(r.exposure_ev, v.frame.exposure_ev, defaults.exposure_ev);
  keep(r.tonemap, v.frame.tonemap, defaults.tonemap);
  keep(r.brdf, v.frame.brdf, defaults.brdf);
  keep(r.energy_compensation, v.frame.energy_compensation, defaults.energy_compensation);
  keep(r.view, v.frame.view, defaults.view);
  return r;
}

void write_scene(const Viewer& v, const std::string& path) {
  const RenderDefaults render = render_block(v);
  save_scene_file(v.scene, path, &render, v.description);
}

// Ctrl+S or a script's `save` (`to_own_file`: the session's scene file), or a script's
// `save PATH`, after which PATH is the session's scene file.
void save(Viewer& v, std::string path, bool to_own_file) {
  if (to_own_file && !v.history.dirty()) {
    // Saving rewrites the file in the generated form: never without a reason.
    // A built-in scene or a model has no file of the session's name until its first save.
    log(v, "nothing to save: no edits since the scene was loaded or saved (" + path +
               (std::filesystem::exists(path) ? " left as it is)" : " not written)"));
    return;
  }
  // A built-in scene not saved yet: NAME.json in the working folder, unless a file of that
  // name is there already, which is not this session's to overwrite.
  std::string instead;
  if (to_own_file && v.scene_file.empty()) {
    if (const std::string free = free_path(path); free != path) {
      instead = " (" + path + " was there already and is not this session's file: left as it is)";
      path = free;
    }
  }
  try {
    write_scene(v, path);
  } catch (const Error& error) {
    refuse(v, std::string("not saved: ") + error.what());
    return;
  }
  v.scene_file = path;
  v.history.mark_saved();
  log(v, "saved " + path + instead);
}

// A scripted click or drag that starts where the panel was drawn is the panel's, as a person's
// press there is; a script edits through the panel's own lines (material, light, brdf, ...).
bool scripted_on_panel(const Viewer& v, const InputEvent& e) {
  if (!e.scripted || !on_panel(*v.window, e.from)) return false;
  char text[160];
  std::snprintf(text, sizeof(text),
                "%s at %g %g: on the panel, which takes it (F1 or --overlay off hides the panel)",
                e.kind == EventKind::click ? "click" : "drag", e.from.x, e.from.y);
  log(v, text);
  return true;
}

float aspect_of(const Viewer& v) {
  const Viewport viewport = viewport_of(v);
  return float(viewport.width) / float(viewport.height);
}

void handle_key(Viewer& v, const InputEvent& e) {
  const uint32_t selected = uint32_t(v.selected);
  const OrbitCamera before = v.orbit;
  FlyKeys fly_keys;
  switch (e.key) {
    case GLFW_KEY_W:
    case GLFW_KEY_A:
    case GLFW_KEY_S:
    case GLFW_KEY_D:
    case GLFW_KEY_Q:
    case GLFW_KEY_E:
      if (e.key == GLFW_KEY_S && e.ctrl) {
        save(v, save_path(v), true);
      } else if (e.scripted) {  // held keys of a person are polled each frame instead
        fly_keys = {e.key == GLFW_KEY_W, e.key == GLFW_KEY_S, e.key == GLFW_KEY_A,
                    e.key == GLFW_KEY_D, e.key == GLFW_KEY_Q, e.key == GLFW_KEY_E};
        fly(v.orbit, fly_keys, kScriptedFlySeconds);
        camera_moved(v, before);
      }
      break;
    case GLFW_KEY_F:
      if (!e.shift) {
        if (frame_scene(v.orbit, v.scene, aspect_of(v), v.home_camera.near_plane)) {
          camera_moved(v, before);
        } else {
          refuse(v, "nothing to frame: the scene has no vertices");
        }
      } else if (has_selection(v, "frame")) {
        if (frame_sphere(v.orbit, object_bounds(v.scene, selected), aspect_of(v),
                         v.home_camera.near_plane)) {
          camera_moved(v, before);
        } else {
          refuse(v, "nothing to frame: the selected object's mesh has no vertices");
        }
      }
      break;
    case GLFW_KEY_HOME:
      v.orbit = from_camera(v.home_camera);
      camera_moved(v, before);
      break;
    case GLFW_KEY_Z:
      if (e.ctrl) undo_or_redo(v, e.shift);
      break;
    case GLFW_KEY_Y:
      if (e.ctrl) undo_or_redo(v, true);
      break;
    case GLFW_KEY_DELETE:
    case GLFW_KEY_X:
      if (has_selection(v, "delete")) {
        edit(v, delete_object(v.scene, selected));
        v.selected = -1;
      }
      break;
    case GLFW_KEY_C:
      if (has_selection(v, "copy"))
        edit(v,
             add_object_copy(v.scene, selected, placed_at(v, selected, point_under(v, v.pointer))));
      break;
    case GLFW_KEY_M:
      if (has_selection(v, "move"))
        edit(v, move_object(v.scene, selected, placed_at(v, selected, point_under(v, v.pointer))));
      break;
    case GLFW_KEY_N: {
      // A sphere a twentieth of the view's distance across, in the selected object's material.
      const Material m =
          v.selected >= 0 ? v.scene.materials[v.scene.objects[selected].material] : Material{};
      edit(v, add_sphere(v.scene, point_under(v, v.pointer), 0.05f * v.orbit.distance, m));
      break;
    }
    case GLFW_KEY_L: {
      // A point light at the eye, bright enough for irradiance 1 W/m^2 at the target.
      Light light;
      light.position = v.scene.camera.position;
      light.intensity = v.orbit.distance * v.orbit.distance;
      edit(v, add_light(v.scene, light));
      break;
    }
    case GLFW_KEY_P:
      v.screenshots.push_back(
          {"tessera_view_" + std::to_string(v.frame_number) + ".png", e.scripted});
      break;
    case GLFW_KEY_ESCAPE:
      v.selected = -1;
      break;
    case GLFW_KEY_F1:
      v.overlay_visible = !v.overlay_visible;
      break;
    default:
      break;
  }
}

}  // namespace

void Viewer::release() {
  if (!ctx) return;
  vkDeviceWaitIdle(ctx->device);
  destroy_overlay(*ctx, overlay);
  destroy_presenter(*ctx, presenter);
  destroy_swapchain(*ctx, chain);
  if (chain.surface) vkDestroySurfaceKHR(ctx->instance, chain.surface, nullptr);
  chain.surface = VK_NULL_HANDLE;
  renderer.reset();
}

void mark_changed(Viewer& v, const std::string& what) {
  if (!v.scene_changed) {
    v.changed_at = std::chrono::steady_clock::now();
    v.change = what;
  } else if (v.change.find(what) == std::string::npos) {
    v.change.append(", ").append(what);
  }
  v.scene_changed = true;
  if (what != "camera") v.scene_edited = true;
}

namespace {

FlyKeys held_fly_keys(const Viewer& v) {
  auto held = [&](int key) { return glfwGetKey(v.window->handle, key) == GLFW_PRESS; };
  if (v.window->panel_has_keyboard || held(GLFW_KEY_LEFT_CONTROL)) return {};
  return {held(GLFW_KEY_W), held(GLFW_KEY_S), held(GLFW_KEY_A),
          held(GLFW_KEY_D), held(GLFW_KEY_Q), held(GLFW_KEY_E)};
}

}  // namespace

bool fly_keys_held(const Viewer& v) {
  const FlyKeys k = held_fly_keys(v);
  return k.forward || k.back || k.left || k.right || k.down || k.up;
}

void fly_held_keys(Viewer& v, float seconds) {
  if (!fly_keys_held(v)) return;
  const OrbitCamera before = v.orbit;
  fly(v.orbit, held_fly_keys(v), seconds);
  camera_moved(v, before);
}

namespace {

void handle_event_kind(Viewer& v, const InputEvent& e) {
  const OrbitCamera before = v.orbit;
  switch (e.kind) {
    case EventKind::key:
      handle_key(v, e);
      break;
    case EventKind::drag: {
      // A right drag does nothing (scripts cannot ask for one).
      if (e.button == MouseButton::right || scripted_on_panel(v, e)) break;
      const glm::vec2 d = e.to - e.from;
      if (e.button == MouseButton::middle || e.shift) {
        pan(v.orbit, d.x, d.y, viewport_of(v));
      } else {
        orbit(v.orbit, d.x, d.y, viewport_of(v));
      }
      v.pointer = e.to;
      camera_moved(v, before);
      break;
    }
    case EventKind::click:
      if (scripted_on_panel(v, e) || !inside_window(v, e)) break;
      v.pointer = e.from;
      pick(v, e.from);
      break;
    case EventKind::wheel:
      zoom(v.orbit, e.wheel);
      camera_moved(v, before);
      break;
    case EventKind::resize:
      set_window_size(*v.window, e.width, e.height);
      break;
    case EventKind::minimise:
      v.minimised = true;
      break;
    case EventKind::restore:
      v.minimised = false;
      break;
    case EventKind::screenshot:
      v.screenshots.push_back({e.path, e.scripted});
      if (v.minimised || window_iconified(*v.window)) {
        log(v, "screenshot " + e.path +
                   " waits: the window is minimised; it is written from the first frame after "
                   "the restore");
      } else if (v.refused_size != std::pair<uint32_t, uint32_t>{}) {
        log(v, "screenshot " + e.path +
                   " waits: the window is too large to draw (said above); it is written from "
                   "the first frame drawn after it is made smaller");
      }
      break;
    case EventKind::save:
      save(v, e.path.empty() ? save_path(v) : e.path, e.path.empty());
      break;
    case EventKind::exit:
      v.exit = true;
      break;
    case EventKind::memory:
      print_resident_memory(v);
      break;
    case EventKind::material:
      edit_material(v, e);
      break;
    case EventKind::light:
      edit_light(v, e);
      break;
    case EventKind::option:
      edit_option(v, e);
      break;
  }
}

}  // namespace

void refuse(Viewer& v, const std::string& why) {
  log(v, why);
  v.event_failed = true;
}

void handle_event(Viewer& v, const InputEvent& e) {
  v.event_failed = false;
  handle_event_kind(v, e);
  if (e.scripted && v.event_failed) v.script_failures++;
}

void apply_panel_changes(Viewer& v, const PanelChanges& c) {
  if (c.material) set_selected_material(v, *c.material);
  if (c.light && *c.light != v.scene.lights[c.light_index])
    edit(v, set_light(v.scene, c.light_index, *c.light));
  if (c.delete_light) edit(v, delete_light(v.scene, c.light_index));
  if (c.add_light) handle_key(v, InputEvent{.kind = EventKind::key, .key = GLFW_KEY_L});
  if (c.toggle_environment)
    edit(v, set_environment(v.scene, v.scene.environment ? nullptr : v.environment));
  if (c.options) set_options(v, *c.options, c.options_label, c.continuing);
}

std::string save_path(const Viewer& v) {
  return !v.scene_file.empty() ? v.scene_file : v.args.scene + ".json";
}

std::string autosave_path(const Viewer& v) {
  // A scene file's autosaves end in ".autosave.json" or ".autosave-N.json", a built-in's in
  // ".builtin-autosave.json" or ".builtin-autosave-N.json", which no file's can: a NAME.json
  // saved beside a built-in NAME (its autosave NAME.autosave.json) never takes the built-in's
  // autosaves for its own, nor the built-in the file's.
  if (v.scene_file.empty()) return v.args.scene + ".builtin-autosave.json";
  std::filesystem::path path = v.scene_file;
  return path.replace_extension(".autosave.json").string();
}

std::string free_path(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return path;
  const std::filesystem::path p(path);
  for (int n = 2;; ++n) {
    std::filesystem::path next = p;
    next.replace_filename(p.stem().string() + "-" + std::to_string(n) + p.extension().string());
    if (!std::filesystem::exists(next, ec)) return next.string();
  }
}

std::vector<std::string> earlier_autosaves(const Viewer& v) {
  namespace fs = std::filesystem;
  const fs::path first = autosave_path(v);
  const std::string stem = first.stem().string();  // FILE.autosave, NAME.builtin-autosave
  const fs::path folder = first.parent_path().empty() ? fs::path(".") : first.parent_path();
  std::vector<std::string> found;
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() < stem.size() + 5 || name.compare(0, stem.size(), stem) != 0 ||
        name.compare(name.size() - 5, 5, ".json") != 0)
      continue;
    // STEM.json, or STEM-N.json.
    const std::string middle = name.substr(stem.size(), name.size() - stem.size() - 5);
    if (!middle.empty() && (middle.size() < 2 || middle[0] != '-' ||
                            middle.find_first_not_of("0123456789", 1) != std::string::npos))
      continue;
    found.push_back((first.parent_path() / name).string());
  }
  std::sort(found.begin(), found.end());
  return found;
}

bool autosave_if_unsaved(Viewer& v) {
  if (!v.history.dirty()) return true;
  // Never over an earlier session's autosave: that holds edits this session does not have.
  const std::string first = autosave_path(v), path = free_path(first);
  try {
    write_scene(v, path);
    if (path == first) {
      std::fprintf(stderr, "tessera: note: unsaved edits written to %s\n", path.c_str());
    } else {
      std::fprintf(stderr,
                   "tessera: note: unsaved edits written to %s (%s, of an earlier session, left "
                   "as it is)\n",
                   path.c_str(), first.c_str());
    }
    return true;
  } catch (const Error& error) {
    std::fprintf(stderr, "tessera: error: unsaved edits lost: %s\n", error.what());
    return false;
  }
}

}  // namespace tessera
