#include "host/view_command.h"

#include <chrono>
#include <cinttypes>
#include <cstdio>

#include <GLFW/glfw3.h>
#include <imgui.h>

#include "compute/vk_check.h"
#include "core/check.h"
#include "core/image.h"
#include "host/report.h"
#include "host/scene_source.h"
#include "host/viewer.h"

namespace tessera {
namespace {

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
  in.unsaved = v.history.dirty();
  apply_panel_changes(v, draw_view_panel(in, v.frame));
  const ImVec2 display = ImGui::GetIO().DisplaySize;
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
  if (wants_shot) {
    // A screenshot that cannot be written says why and leaves the session running.
    const std::string reason = unwritable_reason(v.screenshot);
    try {
      if (!reason.empty()) throw Error(reason);
      write_png(v.screenshot, shot);
      std::printf("frame %" PRIu64 ": wrote %s (%ux%u)\n", v.frame_number, v.screenshot.c_str(),
                  shot.width, shot.height);
    } catch (const Error& error) {
      std::printf("frame %" PRIu64 ": screenshot %s not written: %s\n", v.frame_number,
                  v.screenshot.c_str(), error.what());
    }
    v.screenshot.clear();
  }
  return true;
}

void run_loop(Viewer& v) {
  const bool scripted = !v.args.script.empty();
  for (;; v.frame_number++) {
    uint32_t width = 0, height = 0;
    framebuffer_size(*v.window, width, height);
    // X11 keeps an iconified window's size, so both the flag and a 0 x 0 framebuffer count.
    auto hidden = [&] {
      return v.minimised || window_iconified(*v.window) || width == 0 || height == 0;
    };
    // A minimised window waits for events instead of spinning; a script keeps counting frames.
    std::vector<InputEvent> events = poll_window(*v.window, hidden() && !scripted);
    while (v.next_script_event < v.script.size() &&
           v.script[v.next_script_event].frame <= v.frame_number) {
      events.push_back(v.script[v.next_script_event++].event);
    }
    for (const InputEvent& e : events) handle_event(v, e);
    fly_held_keys(v, float(v.frame_ms) * 1e-3f);
    if (window_should_close(*v.window)) break;
    framebuffer_size(*v.window, width, height);
    if (!hidden()) draw(v, width, height);
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
  v.render_defaults = file.render;
  v.environment = v.scene.environment;
  v.orbit = from_camera(v.scene.camera);

  v.window = open_window(v.frame.width, v.frame.height, "tessera view: " + args.scene);
  ContextOptions options;
  options.device = args.device;
  options.validation = args.validate;
  options.instance_extensions = window_instance_extensions();
  options.swapchain = true;
  v.ctx = create_context(options);
  v.chain.surface = create_window_surface(v.ctx->instance, *v.window);
  create_presenter(*v.ctx, v.presenter);
  // The presenter records the resolve pass, into the swapchain image where it can.
  v.renderer = std::make_unique<Renderer>(*v.ctx, RendererOptions{.resolve = false});
  v.renderer->set_scene(v.scene);
  run_loop(v);
  autosave_if_unsaved(v);
  if (v.frames_presented > 1) {
    const double seconds = std::chrono::duration<double>(v.last_present - v.first_present).count();
    std::printf("%llu frames presented, %.1f frames per second after the first\n",
                (unsigned long long)v.frames_presented, double(v.frames_presented - 1) / seconds);
  }
  v.release();
  return validation_exit_status(v.ctx.get());
}

}  // namespace tessera
