#pragma once
// The state of a `tessera view` session and what input does to it (host/view_actions.cpp);
// the frame loop is host/view_command.cpp. Internal to the tool.

#include <chrono>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "compute/context.h"
#include "compute/present.h"
#include "compute/renderer.h"
#include "compute/swapchain.h"
#include "core/orbit_camera.h"
#include "core/scene_edit.h"
#include "core/scene_file.h"
#include "host/cli.h"
#include "host/overlay.h"
#include "host/view_panel.h"
#include "host/view_script.h"
#include "host/window.h"

namespace tessera {

struct Viewer {
  ViewArgs args;
  Scene scene;
  RenderDefaults render_defaults;  // the scene file's "render" block, written back on save
  std::string description;         // the scene file's "description", written back on save
  // The session's scene file: the one opened, or the one last saved to (a save under another
  // name makes that file the session's). Empty for a built-in scene until it is saved.
  std::string scene_file;
  // Script commands that could not be carried out (a failed save or screenshot, an edit
  // refused, no selection or light to act on, ...): each is said as it happens, and any makes
  // the exit status 1, as a script is used as a test. A person's input never counts.
  uint32_t script_failures = 0;
  bool event_failed = false;  // set by refuse() while an event is handled
  FrameSettings frame;
  OrbitCamera orbit;   // scene.camera is to_camera(orbit) once the camera has moved
  Camera home_camera;  // the scene's own, for the Home key
  EditHistory history;
  // The render options at each state of the history (EditHistory::state): a render option
  // edit is an edit of no scene operations, and undo and redo restore the options of the state
  // they reach.
  std::map<uint64_t, RenderOptions> options_at;
  uint64_t options_drag_state = ~0ull;             // the state the panel's last option edit made
  std::shared_ptr<const Environment> environment;  // the scene's, kept while switched off
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
  uint64_t frames_presented = 0;
  std::chrono::steady_clock::time_point first_present{};

  int selected = -1;           // index into scene.objects, or -1
  glm::vec2 pointer{0.0f};     // window position where new objects go (last click or drag)
  bool scene_changed = false;  // set_scene before the next frame
  bool scene_edited = false;   // and more than the camera changed (else set_camera will do)
  std::string change;          // what changed it ("camera", "material", ...), for the log
  std::chrono::steady_clock::time_point changed_at{};
  bool minimised = false;   // by the script (a real window reports a 0 x 0 framebuffer)
  uint32_t tile_size = 16;  // the renderer's (RendererOptions::tile_size), for size checks
  // The last framebuffer size the device could not render, said once (renderable_size).
  std::pair<uint32_t, uint32_t> refused_size{};
  bool exit = false;
  std::string title;  // the window's, as last set
  struct Screenshot {
    std::string path;
    bool scripted = false;  // a failure counts in script_failures
  };
  std::vector<Screenshot> screenshots;  // written from the next presented frame

  ~Viewer() { release(); }
  /// Destroys the window's Vulkan objects and the renderer, leaving the context.
  void release();
};

/// What input event `e` does: camera moves, picking, edits, undo and redo, saving, the
/// script-only events. Bad edits (a scene that would not validate) are refused with a message;
/// a scripted event that could not be carried out counts in Viewer::script_failures.
void handle_event(Viewer& v, const InputEvent& e);

/// Says (as a frame's log line) why the event being handled could not be carried out, and
/// marks it failed (Viewer::event_failed).
void refuse(Viewer& v, const std::string& why);

/// Moves the camera for the fly keys (WASD, Q, E) held now, over `seconds`.
void fly_held_keys(Viewer& v, float seconds);
/// True while a person holds a fly key (so frames must go on being drawn).
bool fly_keys_held(const Viewer& v);

/// Applies what the overlay's panel changed.
void apply_panel_changes(Viewer& v, const PanelChanges& c);

/// The scene changed by `what` ("camera", "delete object 3", ...); the renderer takes it with
/// set_scene before the next frame, and the log says what it uploaded.
void mark_changed(Viewer& v, const std::string& what);

/// Where Ctrl+S saves: the session's scene file, or NAME.json in the working folder for a scene
/// given by name and not saved yet (so the scenes folder is never written). A NAME.json that
/// is there already is not the session's: Ctrl+S then saves to the first free NAME-N.json.
std::string save_path(const Viewer& v);

/// The scene's autosave file: FILE.autosave.json beside the session's scene file (FILE without
/// its extension), NAME.builtin-autosave.json in the working folder for a scene given by name
/// and not saved yet, a name no scene file's autosave has (NAME.json's is NAME.autosave.json).
std::string autosave_path(const Viewer& v);

/// `path` if no file is there, else the first of STEM-2.EXT, STEM-3.EXT, ... that is free.
std::string free_path(const std::string& path);

/// The autosave files of earlier sessions beside the scene: autosave_path and its numbered
/// variants (FILE.autosave-2.json, ..., or NAME.builtin-autosave-2.json, ...), sorted by name;
/// never a built-in scene's for a scene file, nor a scene file's for a built-in scene.
std::vector<std::string> earlier_autosaves(const Viewer& v);

/// Leaving with unsaved edits writes them to free_path(autosave_path), so that an earlier
/// session's autosave is never overwritten, and says so on stderr; false (and the reason on
/// stderr) if they could not be written.
bool autosave_if_unsaved(Viewer& v);

}  // namespace tessera
