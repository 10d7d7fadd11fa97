#pragma once
// The GLFW window of `tessera view`: created for Vulkan (no OpenGL context), with its input
// turned into InputEvents (host/view_events.h).

#include <memory>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "host/view_events.h"
#include "host/view_panel.h"

struct GLFWwindow;

namespace tessera {

struct Window {
  GLFWwindow* handle = nullptr;
  std::vector<InputEvent> events;  // input since the last take_events
  // Mouse state for turning motion into drags and press-release into clicks.
  int held = -1;       // GLFW button held, or -1
  bool moved = false;  // the held button's pointer moved past the click slop
  glm::vec2 pressed_at{0.0f};
  glm::vec2 last{0.0f};
  bool shift = false;
  bool held_by_panel = false;  // the held button was pressed on the panel, which has the drag
  bool camera_press = false;   // a press off the panel since the viewer last cleared this
  // Set each frame by the viewer: where the overlay's panel was last drawn (empty if it was
  // not), whether one of its popups is open (it takes every press), and whether it has the
  // keyboard. A press is the panel's if the pointer is inside at the time of the press; the
  // whole drag then stays the panel's, and a press outside stays the camera's.
  PanelRect panel;
  uint64_t activity = 0;  // counts window-system input and redraw requests, to wake an idle loop
  bool panel_popup = false;
  bool panel_has_keyboard = false;

  Window() = default;
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;
  ~Window();
};

/// Initialises GLFW and opens a `width` x `height` window titled `title`. Throws Error, with
/// GLFW's description, when there is no display (no X server, DISPLAY unset) or GLFW finds no
/// Vulkan loader.
std::unique_ptr<Window> open_window(uint32_t width, uint32_t height, const std::string& title);

/// The instance extensions GLFW needs for a surface (VK_KHR_surface and the platform's).
/// Initialises GLFW if open_window has not; throws Error as open_window does where it cannot.
std::vector<std::string> window_instance_extensions();

/// Creates a surface for `window` on `instance`; the caller destroys it. Throws Error.
VkSurfaceKHR create_window_surface(VkInstance instance, Window& window);

/// The framebuffer's size in pixels: 0 x 0 while minimised.
void framebuffer_size(const Window& window, uint32_t& width, uint32_t& height);

/// Handles pending window-system events (waiting up to `wait_seconds` for one if > 0) and
/// moves the input received into the returned list.
std::vector<InputEvent> poll_window(Window& window, double wait_seconds);

/// Called when the connection to the X server is lost (the server stopped or went away) with
/// what Xlib says of it (the display's name); it must not return. GLFW's X11 platform leaves
/// this to Xlib, whose default handler prints a line and exits the process at once.
using WindowSystemLost = void (*)(const std::string& display);
/// Installs `handler` for the process (Xlib's I/O error handler is global); null puts Xlib's
/// default back.
void on_window_system_lost(WindowSystemLost handler);

/// Wakes a poll_window that is waiting (from any thread).
void wake_window();

/// True if window position `at` is on the panel as last drawn, or a panel popup is open.
bool on_panel(const Window& window, glm::vec2 at);

bool window_should_close(const Window& window);
bool window_iconified(const Window& window);
void set_window_size(Window& window, uint32_t width, uint32_t height);
void set_window_title(Window& window, const std::string& title);

}  // namespace tessera
