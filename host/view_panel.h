#pragma once
// What the overlay's panel shows and lets a person change: frame and per-pass GPU times,
// triangle counts, the selected object's material, the lights and the render options. Built
// with Dear ImGui between begin_overlay_frame and record_overlay (host/overlay.h).

#include <optional>

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

/// What the person changed this frame; the viewer applies it (as undoable edits where the
/// scene changes).
struct PanelChanges {
  std::optional<Material> material;  // new material of the selected object
  std::optional<Light> light;        // new value of light `light_index`
  uint32_t light_index = 0;
  bool delete_light = false;  // light `light_index`
  bool add_light = false;
  bool toggle_environment = false;
};

/// Draws the panel; `frame` (render options) is changed in place.
PanelChanges draw_view_panel(const PanelInput& in, FrameSettings& frame);

/// Marks object `selected` of `scene` (an index, or -1 for none) in the window: corner brackets
/// around the screen rectangle of its mesh's bounding box seen through `scene.camera`, in
/// ImGui's background layer over the whole `width` x `height` window pixels. The overlay
/// draws it after the screenshot's read-back, so it never enters the compared image.
void draw_selection_mark(const Scene& scene, int selected, float width, float height);

}  // namespace tessera
