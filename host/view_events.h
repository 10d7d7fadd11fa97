#pragma once
// The input of `tessera view`, whether a person gives it (host/window.h turns GLFW callbacks
// into these) or a script replays it (host/view_script.h): one event type, one handler.

#include <cstdint>
#include <string>

#include <glm/glm.hpp>

namespace tessera {

enum class EventKind {
  key,         // a key press: `key` (a GLFW_KEY_* code), `ctrl`, `shift`
  drag,        // a mouse drag with `button` held from `from` to `to` (window pixels), `shift`
  click,       // a press and release of the left button at `from` without moving
  wheel,       // the scroll wheel turned by `wheel` notches (positive: away from the user)
  resize,      // the window resized to `width` x `height` (script only: a person drags)
  minimise,    // the window minimised (script: frames are not rendered until restore)
  restore,     // the window restored
  screenshot,  // the next presented frame written to `path` as PNG
  save,        // the scene saved to `path` (empty: to the scene's own file)
  exit,        // leave after this frame, as if the window were closed
  memory,      // print the process's resident memory (script only: leak checks)
  material,    // the selected object's material: `field` set to `value` or preset `path`
               // (script only: what the panel's material editor does)
  light,       // the panel's light controls: `field` add (at the eye), or for light `index`
               // delete, position, color (`value`) or intensity (`value.x`) (script only)
  option,      // the panel's render options: `field` brdf, tonemap or view set to the choice
               // `path`, exposure to `value.x` (EV), energy_compensation to `value.x` != 0
               // (script only)
};

enum class MouseButton { left, middle, right };

struct InputEvent {
  EventKind kind = EventKind::key;
  int key = 0;
  bool ctrl = false;
  bool shift = false;
  MouseButton button = MouseButton::left;
  glm::vec2 from{0.0f};
  glm::vec2 to{0.0f};
  float wheel = 0.0f;
  uint32_t width = 0;
  uint32_t height = 0;
  std::string path;
  std::string field;   // material: preset, base_color, metallic, roughness or emissive; light,
                       // option: what the event sets
  uint32_t index = 0;  // light: which
  glm::vec3 value{0.0f};
  bool scripted = false;  // from a script: a key of the fly set moves one step (no key is held)
};

}  // namespace tessera
