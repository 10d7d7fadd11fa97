#include "host/view_command.h"

#include <chrono>
#include <cinttypes>
#include <cstdio>

#include <unistd.h>

#include <GLFW/glfw3.h>

#include "compute/context.h"
#include "compute/present.h"
#include "compute/renderer.h"
#include "compute/swapchain.h"
#include "compute/vk_check.h"
#include "core/check.h"
#include "core/materials.h"
#include "host/overlay.h"
#include "host/report.h"
#include "host/scene_source.h"
#include "host/view_camera.h"
#include "host/view_panel.h"
#include "host/view_script.h"
#include "host/window.h"
#include "shaders/shared/gpu_types.h"

namespace tessera {
namespace {

struct Viewer {
  ViewArgs args;
  Scene scene;
  FrameSettings frame;
  std::vector<ScriptEvent> script;
  size_t next_script_event = 0;
  uint64_t frame_number = 0;

  std::unique_ptr<Window> window;
  std::unique_ptr<Context> ctx;
  std::unique_ptr<Renderer> renderer;
  Swapchain chain;
  Presenter presenter;
  Overlay overlay;
  bool recreate = true;
  bool overlay_visible = true;
  FrameStats last_stats;
  double frame_ms = 0.0;
  std::chrono::steady_clock::time_point last_present{};
  std::shared_ptr<const Environment> environment;  // the scene's, kept while switched off
  bool unsaved = false;

  int selected = -1;           // index into scene.objects, or -1
  bool scene_changed = false;  // set_scene before the next frame
  std::string change;          // what changed it ("camera", "material", ...), for the log
  std::chrono::steady_clock::time_point changed_at{};
  uint64_t frames_presented = 0;
  std::chrono::steady_clock::time_point first_present{};
  bool minimised = false;  // by the script (a real window reports a 0 x 0 framebuffer)
  bool exit = false;
  std::string screenshot;  // written from the next presented frame

  ~Viewer() { release(); }
  // Destroys the Vulkan objects of the window, the renderer's too, leaving the context.
  void release() {
    if (ctx) {
      vkDeviceWaitIdle(ctx->device);
      destroy_overlay(*ctx, overlay);
      destroy_presenter(*ctx, presenter);
      destroy_swapchain(*ctx, chain);
      if (chain.surface) vkDestroySurfaceKHR(ctx->instance, chain.surface, nullptr);
      renderer.reset();
      chain.surface = VK_NULL_HANDLE;
    }
  }
};

// The scene changed by `what` ("camera", "material", ...); an edit (not a camera move) leaves
// unsaved changes. The renderer takes it with set_scene before the next frame.
void mark_changed(Viewer& v, const std::string& what, bool edit) {
  if (!v.scene_changed) {
    v.changed_at = std::chrono::steady_clock::now();
    v.change = what;
  } else if (v.change.find(what) == std::string::npos) {
    v.change.append("+").append(what);
  }
  v.scene_changed = true;
  v.unsaved |= edit;
}

// The renderer takes the camera with the scene (set_scene uploads only what changed).
void camera_moved(Viewer& v) {
  mark_changed(v, "camera", false);
  const Camera& c = v.scene.camera;
  std::printf("frame %" PRIu64 ": camera position %.9g %.9g %.9g target %.9g %.9g %.9g\n",
              v.frame_number, c.position.x, c.position.y, c.position.z, c.target.x, c.target.y,
              c.target.z);
}

// From /proc/self/statm: its second number is the resident set in pages.
void print_resident_memory(const Viewer& v) {
  unsigned long long pages_total = 0, pages_resident = 0;
  FILE* statm = std::fopen("/proc/self/statm", "r");
  const bool read = statm && std::fscanf(statm, "%llu %llu", &pages_total, &pages_resident) == 2;
  if (statm) std::fclose(statm);
  if (!read) {
    std::printf("frame %" PRIu64 ": resident memory unknown\n", v.frame_number);
    return;
  }
  std::printf("frame %" PRIu64 ": resident memory %llu KiB\n", v.frame_number,
              pages_resident * (unsigned long long)sysconf(_SC_PAGESIZE) / 1024);
}

// The framebuffer pixel under window position `at`, if inside the last frame.
bool pixel_under(const Viewer& v, glm::vec2 at, uint32_t& x, uint32_t& y) {
  int window_w = 0, window_h = 0;
  glfwGetWindowSize(v.window->handle, &window_w, &window_h);
  if (window_w <= 0 || window_h <= 0 || v.chain.extent.width == 0) return false;
  const float sx = float(v.chain.extent.width) / float(window_w);
  const float sy = float(v.chain.extent.height) / float(window_h);
  if (at.x < 0.0f || at.y < 0.0f) return false;
  x = uint32_t(at.x * sx);
  y = uint32_t(at.y * sy);
  return x < v.chain.extent.width && y < v.chain.extent.height;
}

void pick(Viewer& v, glm::vec2 at) {
  uint32_t x = 0, y = 0;
  v.selected = -1;
  if (pixel_under(v, at, x, y)) {
    const uint64_t key = v.renderer->read_visibility_at(x, y);
    // The key's low 32 bits are the triangle-instance id (shaders/raster_common.glsl).
    if (key != TS_VIS_EMPTY) v.selected = int(v.renderer->object_of_triangle(uint32_t(key)));
  }
  std::printf("frame %" PRIu64 ": click at %g %g: selected %s%d\n", v.frame_number, at.x, at.y,
              v.selected < 0 ? "nothing " : "object ", v.selected);
}

// In the working folder, named by frame so that screenshots of one session never collide.
std::string default_screenshot_name(const Viewer& v) {
  return "tessera_view_" + std::to_string(v.frame_number) + ".png";
}

void set_selected_material(Viewer& v, const Material& m) {
  if (v.selected < 0) {
    std::printf("frame %" PRIu64 ": no object selected; material unchanged\n", v.frame_number);
    return;
  }
  v.scene.materials[v.scene.objects[size_t(v.selected)].material] = m;
  mark_changed(v, "material", true);
}

// A scripted material edit, as the panel's editor would make it.
void edit_material(Viewer& v, const InputEvent& e) {
  if (v.selected < 0) return set_selected_material(v, {});
  Material m = v.scene.materials[v.scene.objects[size_t(v.selected)].material];
  if (e.field == "preset") {
    m.base_color = find_metal_preset(e.path)->f0;
    m.metallic = 1.0f;
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

void handle_key(Viewer& v, const InputEvent& e) {
  switch (e.key) {
    case GLFW_KEY_P:
      v.screenshot = default_screenshot_name(v);
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

void handle(Viewer& v, const InputEvent& e) {
  switch (e.kind) {
    case EventKind::key:
      handle_key(v, e);
      break;
    case EventKind::drag: {
      const glm::vec2 d = e.to - e.from;
      if (e.button == MouseButton::middle || (e.button == MouseButton::left && e.shift)) {
        pan_camera(v.scene.camera, d.x, d.y, float(std::max(v.chain.extent.height, 1u)));
      } else if (e.button == MouseButton::left) {
        orbit_camera(v.scene.camera, d.x, d.y);
      }
      camera_moved(v);
      break;
    }
    case EventKind::click:
      pick(v, e.from);
      break;
    case EventKind::wheel:
      zoom_camera(v.scene.camera, e.wheel);
      camera_moved(v);
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
      v.screenshot = e.path;
      break;
    case EventKind::save:
      std::fprintf(stderr, "tessera view: saving is not available yet\n");
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
  }
}

void apply_panel_changes(Viewer& v, const PanelChanges& c) {
  if (c.material) set_selected_material(v, *c.material);
  if (c.light) {
    v.scene.lights[c.light_index] = *c.light;
    mark_changed(v, "light", true);
  }
  if (c.toggle_environment) {
    v.scene.environment = v.scene.environment ? nullptr : v.environment;
    mark_changed(v, "environment", true);
  }
}

// Builds this frame's panel; its changes apply to the frame about to be rendered.
void build_panel(Viewer& v) {
  begin_overlay_frame();
  PanelInput in;
  in.scene = &v.scene;
  in.stats = &v.last_stats;
  in.frame_ms = v.frame_ms;
  in.selected = v.selected;
  in.has_environment = v.environment != nullptr;
  in.environment_on = v.scene.environment != nullptr;
  in.unsaved = v.unsaved;
  apply_panel_changes(v, draw_view_panel(in, v.frame));
}

// Renders and presents one frame at the framebuffer's size; false if nothing was shown.
bool draw(Viewer& v, uint32_t width, uint32_t height) {
  if (v.recreate || v.chain.extent.width != width || v.chain.extent.height != height) {
    VK_CHECK(vkDeviceWaitIdle(v.ctx->device));
    create_swapchain(*v.ctx, v.chain, width, height, v.args.vsync);
    if (v.args.overlay) prepare_overlay(*v.ctx, *v.window, v.chain, v.overlay);
    v.recreate = false;
  }
  const bool overlay = v.args.overlay && v.overlay_visible;
  if (overlay) build_panel(v);
  v.window->wants_input_elsewhere = overlay && overlay_wants_input();
  UploadStats upload;
  if (v.scene_changed) upload = v.renderer->set_scene(v.scene);
  v.frame.width = v.chain.extent.width;
  v.frame.height = v.chain.extent.height;
  v.last_stats = v.renderer->render(v.frame);
  Image8 shot;
  const bool wants_shot = !v.screenshot.empty();
  bool overlay_drawn = false;
  OverlayRecorder recorder;
  if (overlay) {
    recorder = [&](VkCommandBuffer cmd, uint32_t index) {
      record_overlay(v.overlay, v.chain, cmd, index);
      overlay_drawn = true;
    };
  }
  const PresentResult result =
      present_frame(*v.ctx, v.presenter, v.chain, v.renderer->output_image(), recorder,
                    wants_shot ? &shot : nullptr);
  if (overlay && !overlay_drawn) discard_overlay_frame();
  if (result != PresentResult::presented) v.recreate = true;
  if (result == PresentResult::out_of_date) return false;
  const auto now = std::chrono::steady_clock::now();
  if (v.last_present != std::chrono::steady_clock::time_point{}) {
    v.frame_ms = std::chrono::duration<double, std::milli>(now - v.last_present).count();
  }
  v.last_present = now;
  if (v.frames_presented++ == 0) v.first_present = now;
  if (v.scene_changed) {
    // The edit is on screen: this frame was rendered from it and has been presented.
    std::printf("frame %" PRIu64 ": %s: uploaded %llu bytes, %.2f ms from the change to present\n",
                v.frame_number, v.change.c_str(), (unsigned long long)upload.bytes,
                std::chrono::duration<double, std::milli>(now - v.changed_at).count());
    v.scene_changed = false;
  }
  if (wants_shot) {
    write_png(v.screenshot, shot);
    std::printf("frame %" PRIu64 ": wrote %s (%ux%u)\n", v.frame_number, v.screenshot.c_str(),
                shot.width, shot.height);
    v.screenshot.clear();
  }
  return true;
}

void run_loop(Viewer& v) {
  const bool scripted = !v.args.script.empty();
  for (;; v.frame_number++) {
    uint32_t width = 0, height = 0;
    framebuffer_size(*v.window, width, height);
    const bool hidden = v.minimised || width == 0 || height == 0;
    // A minimised window waits for events instead of spinning; a script keeps counting frames.
    std::vector<InputEvent> events = poll_window(*v.window, hidden && !scripted);
    while (v.next_script_event < v.script.size() &&
           v.script[v.next_script_event].frame <= v.frame_number) {
      events.push_back(v.script[v.next_script_event++].event);
    }
    for (const InputEvent& e : events) handle(v, e);
    if (window_should_close(*v.window)) break;
    framebuffer_size(*v.window, width, height);
    if (!v.minimised && width > 0 && height > 0) draw(v, width, height);
    if (v.exit) break;
  }
}

}  // namespace

int run_view(const ViewArgs& args) {
  Viewer v;
  v.args = args;
  v.frame = args.frame;
  if (!args.script.empty()) v.script = load_view_script(args.script);
  SceneFile file = load_scene_argument(args.scene, false, false);
  apply_render_defaults(file.render, v.frame, args.size_given, false, false, false);
  v.scene = std::move(file.scene);
  v.environment = v.scene.environment;

  v.window = open_window(v.frame.width, v.frame.height, "tessera view: " + args.scene);
  ContextOptions options;
  options.device = args.device;
  options.validation = args.validate;
  options.instance_extensions = window_instance_extensions();
  options.swapchain = true;
  v.ctx = create_context(options);
  v.chain.surface = create_window_surface(v.ctx->instance, *v.window);
  create_presenter(*v.ctx, v.presenter);
  v.renderer = std::make_unique<Renderer>(*v.ctx);
  v.renderer->set_scene(v.scene);
  run_loop(v);
  if (v.frames_presented > 1) {
    const double seconds = std::chrono::duration<double>(v.last_present - v.first_present).count();
    std::printf("%llu frames presented, %.1f frames per second after the first\n",
                (unsigned long long)v.frames_presented, double(v.frames_presented - 1) / seconds);
  }
  v.release();
  return validation_exit_status(v.ctx.get());
}

}  // namespace tessera
