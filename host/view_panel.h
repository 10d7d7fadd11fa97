#pragma once
// What the overlay's panel shows and lets a person change: frame and per-pass GPU times,
// triangle counts, the selected object's material, the lights and the render options. Built
// with Dear ImGui between begin_overlay_frame and record_overlay (host/overlay.h).

#include <optional>
#include <string>

#include "compute/renderer.h"
#include "core/frame_settings.h"
#include "core/scene.h"

namespace tessera {

struct PanelInput {
  const Scene* scene = nullptr;
  const FrameStats* stats = nullptr;  // the last frame's
  double frame_ms = 0.0;              // wall time between the last two presented frames
  int selected = -1;                  // object index or -1
  bool has_environment = false;       // the scene was loaded with one (it may be switched off)
  bool environment_on = false;
  bool unsaved = false;
};

/// The render options the panel edits: undoable edits of the viewer, saved in the scene
/// file's "render" block.
struct RenderOptions {
  Brdf brdf = Brdf::classic;
  ToneMap tonemap = ToneMap::aces;
  float exposure_ev = 0.0f;
  bool energy_compensation = false;
  View view = View::shaded;
  bool operator==(const RenderOptions&) const = default;
};

RenderOptions render_options_of(const FrameSettings& frame);
void set_render_options(FrameSettings& frame, const RenderOptions& options);

/// A rectangle of window pixels (lo: top left); empty when lo > hi.
struct PanelRect {
  glm::vec2 lo{1.0f}, hi{0.0f};
  bool contains(glm::vec2 p) const {
    return p.x >= lo.x && p.y >= lo.y && p.x < hi.x && p.y < hi.y;
  }
};

/// What the person changed this frame; the viewer applies it (as undoable edits).
struct PanelChanges {
  std::optional<Material> material;  // new material of the selected object
  std::optional<Light> light;        // new value of light `light_index`
  uint32_t light_index = 0;
  bool delete_light = false;  // light `light_index`
  bool add_light = false;
  bool toggle_environment = false;
  std::optional<RenderOptions> options;  // new render options
  std::string options_label;             // what changed in them: "tone map reinhard"
  bool continuing = false;  // the change continues a drag of the widget that made the last one
  PanelRect rect;           // where the panel was drawn, for the input under it
};

/// Draws the panel over a `width` x `height` window (at most 40% of its width, its height at
/// most the window's, scrolling inside).
PanelChanges draw_view_panel(const PanelInput& in, const FrameSettings& frame, float width,
                             float height);

/// Marks object `selected` of `scene` (an index, or -1 for none) in the window: corner brackets
/// around the screen rectangle of its mesh's bounding box seen through `scene.camera`, in
/// ImGui's background layer over the whole `width` x `height` window pixels. The overlay
/// draws it after the screenshot's read-back, so it never enters the compared image.
void draw_selection_mark(const Scene& scene, int selected, float width, float height);

}  // namespace tessera
