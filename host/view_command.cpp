#include "host/view_command.h"

#include <algorithm>
#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include <GLFW/glfw3.h>
#include <imgui.h>

#include "compute/timestamps.h"
#include "compute/vk_check.h"
#include "core/check.h"
#include "core/image.h"
#include "host/report.h"
#include "host/scene_source.h"
#include "host/stop_signal.h"
#include "host/viewer.h"

namespace tessera {
namespace {

// Builds this frame's panel; its changes apply to the frame about to be rendered.
void build_panel(Viewer& v) {
  Window& w = *v.window;
  begin_overlay_frame(w.camera_press || (w.held >= 0 && !w.held_by_panel));
  w.camera_press = false;
  PanelInput in;
  in.scene = &v.scene;
  in.stats = &v.last_stats;
  in.frame_ms = v.frame_ms;
  in.selected = v.selected;
  in.has_environment = v.environment != nullptr;
  in.environment_on = v.scene.environment != nullptr;
  in.unsaved = v.history.dirty();
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  const PanelChanges changes = draw_view_panel(in, v.frame, display.x, display.y);
  v.window->panel = changes.rect;
  apply_panel_changes(v, changes);
  draw_selection_mark(v.scene, v.selected, display.x, display.y);
}

// Renders and presents one frame at the framebuffer's size; false if nothing was shown.
bool draw(Viewer& v, uint32_t width, uint32_t height) {
  if (v.recreate || v.chain.extent.width != width || v.chain.extent.height != height) {
    VK_CHECK(vkDeviceWaitIdle(v.ctx->device));
    const bool first = v.chain.swapchain == VK_NULL_HANDLE;
    const bool was_direct = v.chain.direct;
    const VkFormat old_format = v.chain.format;
    create_swapchain(*v.ctx, v.chain, width, height,
                     {v.args.vsync, v.args.present, v.args.surface_format});
    prepare_presenter(*v.ctx, v.presenter, v.chain, *v.renderer);
    if (v.args.overlay) prepare_overlay(*v.ctx, *v.window, v.chain, v.overlay);
    v.recreate = false;
    if (first || was_direct != v.chain.direct || old_format != v.chain.format) {
      std::printf("frame %" PRIu64 ": presenting %s images %s\n", v.frame_number,
                  format_name(v.chain.format).c_str(),
                  v.chain.direct ? "directly (the resolve pass writes them)"
                                 : ("by copy: " + v.chain.path_reason).c_str());
    }
  }
  const bool overlay = v.args.overlay && v.overlay_visible;
  v.window->panel = PanelRect{};
  if (overlay) build_panel(v);
  v.window->panel_popup = overlay && overlay_popup_open();
  v.window->panel_has_keyboard = overlay && overlay_wants_keyboard();
  UploadStats upload;
  if (v.scene_changed && v.scene_edited) {
    upload = v.renderer->set_scene(v.scene);
    v.scene_edited = false;
  } else if (v.scene_changed) {
    v.renderer->set_camera(v.scene.camera);  // an orbit: nothing to compare or upload
  }
  v.frame.width = v.chain.extent.width;
  v.frame.height = v.chain.extent.height;
  // A light added (or a BRDF, ... not drawn before this session) respecializes the shading
  // pass: on a CPU device the window stalls for seconds. Said before, in the log and the title,
  // so that the wait is not taken for a hang. lavapipe keeps no pipeline cache worth saving
  // between sessions (its VkPipelineCache data is the 32-byte header alone).
  const bool specializes = v.scene_changed && v.renderer->builds_shading_pipeline(v.frame);
  if (specializes) {
    std::printf("frame %" PRIu64
                ": %s: specializing the shaders to the new set of lights and options (seconds "
                "on a CPU device; once a session for each set)...\n",
                v.frame_number, v.change.c_str());
    set_window_title(*v.window, v.title + " (specializing shaders...)");
  }
  v.last_stats = v.renderer->render(v.frame);
  if (specializes) set_window_title(*v.window, v.title);
  Image8 shot;
  const bool wants_shot = !v.screenshots.empty();
  bool overlay_drawn = false;
  OverlayRecorder recorder;
  if (overlay) {
    note_render_pass(*v.ctx);  // the overlay's render pass: compute/timestamps.h says why
    recorder = [&](VkCommandBuffer cmd, uint32_t index) {
      record_overlay(v.overlay, v.chain, cmd, index);
      overlay_drawn = true;
    };
  }
  const PresentResult result = present_frame(*v.ctx, v.presenter, v.chain, *v.renderer, recorder,
                                             wants_shot ? &shot : nullptr, &v.last_stats);
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
  for (const Viewer::Screenshot& screenshot : v.screenshots) {
    // A screenshot that cannot be written says why and leaves the session running; a
    // scripted one counts as a failed script command.
    const std::string& path = screenshot.path;
    const std::string reason = unwritable_reason(path);
    try {
      if (!reason.empty()) throw Error(reason);
      write_png(path, shot);
      std::printf("frame %" PRIu64 ": wrote %s (%ux%u)\n", v.frame_number, path.c_str(), shot.width,
                  shot.height);
    } catch (const Error& error) {
      std::printf("frame %" PRIu64 ": screenshot %s not written: %s\n", v.frame_number,
                  path.c_str(), error.what());
      if (screenshot.scripted) v.script_failures++;
    }
  }
  v.screenshots.clear();
  return true;
}

// Whether the device renders a framebuffer of `width` x `height`; says once, for each size
// it cannot, why not and that the window stays as it was until made smaller.
bool renderable_size(Viewer& v, uint32_t width, uint32_t height) {
  try {
    check_image_size(*v.ctx, width, height, v.frame.samples, v.tile_size);
  } catch (const ImageSizeError& e) {
    if (v.refused_size != std::pair{width, height}) {
      std::printf("frame %" PRIu64
                  ": the window's %ux%u pixels are not drawn: a frame of that "
                  "size %s; make the window smaller\n",
                  v.frame_number, width, height, e.reason.c_str());
      v.refused_size = {width, height};
    }
    return false;
  }
  v.refused_size = {};
  return true;
}

// The session whose unsaved edits a lost X server must not take with it; null once the
// session has written its autosave itself.
Viewer* g_session = nullptr;

// Sets g_session for the guard's life; declared after the Viewer, so that it ends first.
struct SessionGuard {
  explicit SessionGuard(Viewer& v) { g_session = &v; }
  ~SessionGuard() { g_session = nullptr; }
  SessionGuard(const SessionGuard&) = delete;
  SessionGuard& operator=(const SessionGuard&) = delete;
};

// Xlib's I/O error handler (on_window_system_lost), called from inside a GLFW call of the
// frame loop: between events, so the scene is whole. Writing the autosave is CPU work only
// (the scene to JSON); no Vulkan or Xlib call can be made now. _Exit, not exit: static
// destructors would tear down the Vulkan loader under a live device and driver threads.
[[noreturn]] void on_x_server_lost(const std::string& display) {
  if (g_session) autosave_if_unsaved(*g_session);
  std::fprintf(stderr,
               "tessera: error: lost the connection to the X server (display \"%s\": the server "
               "stopped or closed the connection)\n",
               display.c_str());
  std::fflush(nullptr);
  std::_Exit(kExitRuntimeError);
}

// Interactive frames after the last input, so that ImGui's hover and animations settle.
constexpr int kSettleFrames = 3;
// An idle interactive viewer sleeps in the window system up to this long between checks of the
// stop signals.
constexpr double kIdleWaitSeconds = 0.25;

void run_loop(Viewer& v) {
  int settle = kSettleFrames;  // frames still to draw after the last activity
  uint64_t seen_activity = 0;
  for (;;) {
    // Until its last event has played; then the window is left to a person.
    const bool scripted = v.next_script_event < v.script.size();
    uint32_t width = 0, height = 0;
    framebuffer_size(*v.window, width, height);
    // X11 keeps an iconified window's size, so both the flag and a 0 x 0 framebuffer count.
    // A window larger than the device can render (a maximised window on a large screen with
    // lavapipe's 128 MiB buffers) is drawn again once it is made smaller.
    auto hidden = [&] {
      return v.minimised || window_iconified(*v.window) || width == 0 || height == 0 ||
             !renderable_size(v, width, height);
    };
    // A script renders every frame, so that its frame numbers mean the same on every run.
    // Interactively, a frame is drawn only when something may have changed; otherwise the
    // viewer waits for the window system.
    const bool busy = scripted || settle > 0 || v.scene_changed || !v.screenshots.empty() ||
                      v.recreate || fly_keys_held(v);
    std::vector<InputEvent> events =
        poll_window(*v.window, busy && !(hidden() && !scripted) ? 0.0 : kIdleWaitSeconds);
    if (v.window->activity != seen_activity) {
      seen_activity = v.window->activity;
      settle = kSettleFrames;
    }
    if (const int signal = stop_signal()) {
      std::printf("frame %" PRIu64 ": %s received: leaving as if the window were closed\n",
                  v.frame_number, stop_signal_name(signal));
      break;
    }
    while (v.next_script_event < v.script.size() &&
           v.script[v.next_script_event].frame <= v.frame_number) {
      events.push_back(v.script[v.next_script_event++].event);
    }
    const bool draws = scripted || settle > 0 || !events.empty() || v.scene_changed ||
                       !v.screenshots.empty() || v.recreate || fly_keys_held(v);
    if (!draws) continue;
    for (const InputEvent& e : events) handle_event(v, e);
    // The window's title says what the panel's does, for a hidden panel too.
    const std::string title =
        "tessera view: " + (v.scene_file.empty() ? v.args.scene : v.scene_file) +
        (v.history.dirty() ? " (unsaved edits)" : "");
    if (title != v.title) set_window_title(*v.window, v.title = title);
    // A frame's time is the time it takes to draw one, whatever the idle time before it.
    fly_held_keys(v, float(std::min(v.frame_ms, 100.0)) * 1e-3f);
    if (window_should_close(*v.window)) break;
    framebuffer_size(*v.window, width, height);
    if (!hidden()) {
      draw(v, width, height);
      if (settle > 0) settle--;
    }
    if (v.exit) break;
    v.frame_number++;
  }
}

}  // namespace

int run_view(const ViewArgs& args) {
  Viewer v;
  v.args = args;
  v.frame = args.frame;
  if (!args.script.empty()) {
    // A script that does not parse is a bad command line, as a bad option value is.
    try {
      v.script = load_view_script(args.script);
    } catch (const Error& e) {
      throw UsageError(e.what(), "tessera view --help");
    }
  }
  SceneFile file = load_scene_argument(args.scene, args.strict, false);
  if (args.camera_given) use_model_camera(file, args.camera, "tessera view --help");
  apply_render_defaults(file.render, v.frame, args.size_given, false, false, false);
  frame_model_camera(file.scene, args.scene, args.camera_given, v.frame.width, v.frame.height);
  v.scene = std::move(file.scene);
  if (const std::string note = unlit_scene_note(v.scene, args.scene, v.frame.view); !note.empty())
    std::printf("tessera: %s\n", note.c_str());
  if (const std::string note = coarse_positions_note(v.scene, args.scene); !note.empty())
    std::printf("tessera: %s\n", note.c_str());
  if (const std::string note = near_lights_note(v.scene, args.scene); !note.empty())
    std::printf("tessera: %s\n", note.c_str());
  v.render_defaults = file.render;
  v.description = file.description;
  v.options_at[v.history.state()] = render_options_of(v.frame);
  // Ctrl+S never writes JSON over a model file: its scene goes to a new FILE.json beside it.
  if (is_scene_path(args.scene) && !is_model_path(args.scene)) v.scene_file = args.scene;
  for (const std::string& autosave : earlier_autosaves(v)) {
    std::printf(
        "tessera: note: %s holds unsaved edits of an earlier session (open it with --scene %s)\n",
        autosave.c_str(), autosave.c_str());
  }
  v.environment = v.scene.environment;
  v.orbit = from_camera(v.scene.camera);
  v.home_camera = v.scene.camera;

  // The device before the window: a starting size it cannot render is refused as `render`
  // refuses it, before a window opens. (A window the user makes larger than that later is
  // not drawn until made smaller again: renderable_size.)
  ContextOptions options;
  options.device = args.device;
  options.validation = args.validate;
  options.instance_extensions = window_instance_extensions();
  options.swapchain = true;
  v.ctx = create_context(options);
  const RendererOptions renderer_options = tuned_for_device(*v.ctx, {.resolve = false});
  try {
    check_image_size(*v.ctx, v.frame.width, v.frame.height, v.frame.samples,
                     renderer_options.tile_size);
  } catch (const ImageSizeError& e) {
    throw_image_size_error(e, args.size_given, v.render_defaults.size_place, "tessera view --help");
  }
  const SessionGuard guard(v);
  on_window_system_lost(on_x_server_lost);
  v.window = open_window(v.frame.width, v.frame.height, "tessera view: " + args.scene);
  v.chain.surface = create_window_surface(v.ctx->instance, *v.window);
  create_presenter(*v.ctx, v.presenter);
  // The presenter records the resolve pass, into the swapchain image where it can. Building
  // the pipelines takes seconds on a CPU device, with the window still empty: say so.
  std::printf("compiling shaders...\n");
  set_window_title(*v.window, "tessera view: " + args.scene + " (compiling shaders...)");
  poll_window(*v.window, 0.0);
  v.renderer = std::make_unique<Renderer>(*v.ctx, renderer_options);
  v.tile_size = renderer_options.tile_size;
  try {
    v.renderer->set_scene(v.scene);
  } catch (const SceneSizeError& e) {
    throw Error(args.scene + ": " + e.what());  // which scene is too large for this device
  }
  // Ctrl+C and SIGTERM end the session normally (autosave, summary).
  catch_stop_signals();
  try {
    run_loop(v);
  } catch (const Error&) {
    // The session ends with the error, but not with the user's edits.
    g_session = nullptr;
    autosave_if_unsaved(v);
    throw;
  }
  g_session = nullptr;
  bool lost = !autosave_if_unsaved(v);
  for (const Viewer::Screenshot& screenshot : v.screenshots) {
    std::printf("frame %" PRIu64
                ": screenshot %s not written: no frame was presented after it was asked for "
                "(the window stayed minimised or too large to draw)\n",
                v.frame_number, screenshot.path.c_str());
    if (screenshot.scripted) v.script_failures++;
    lost = true;
  }
  if (v.frames_presented > 1) {
    const double seconds = std::chrono::duration<double>(v.last_present - v.first_present).count();
    std::printf("%llu frames presented, %.1f frames per second after the first\n",
                (unsigned long long)v.frames_presented, double(v.frames_presented - 1) / seconds);
  }
  if (v.script_failures > 0) {
    // Said last. A script is used as a test: any command it could not carry out fails the run.
    std::fprintf(stderr, "tessera: error: %u script command%s failed (said above)\n",
                 v.script_failures, v.script_failures == 1 ? "" : "s");
    lost = true;
  }
  v.release();
  const int status = validation_exit_status(v.ctx.get());
  return status != 0 ? status : lost ? kExitRuntimeError : 0;
}

}  // namespace tessera
