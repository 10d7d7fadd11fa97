#include "host/window.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
// Last: Xlib's macros (None, Bool, Status, ...) would clash with names in the headers above.
#include <X11/Xlib.h>

#include "compute/vk_check.h"
#include "core/check.h"

namespace tessera {
namespace {

// A press and release closer than this (window pixels) is a click, not a drag.
constexpr float kClickSlop = 3.0f;

std::string glfw_error() {
  const char* description = nullptr;
  glfwGetError(&description);
  return description ? description : "no description";
}

Window& of(GLFWwindow* handle) {
  return *static_cast<Window*>(glfwGetWindowUserPointer(handle));
}

MouseButton button_of(int glfw_button) {
  return glfw_button == GLFW_MOUSE_BUTTON_MIDDLE  ? MouseButton::middle
         : glfw_button == GLFW_MOUSE_BUTTON_RIGHT ? MouseButton::right
                                                  : MouseButton::left;
}

glm::vec2 cursor(GLFWwindow* handle) {
  double x = 0, y = 0;
  glfwGetCursorPos(handle, &x, &y);
  return {float(x), float(y)};
}

void on_key(GLFWwindow* handle, int key, int, int action, int mods) {
  Window& w = of(handle);
  w.activity++;
  w.shift = mods & GLFW_MOD_SHIFT;
  if (w.panel_has_keyboard || (action != GLFW_PRESS && action != GLFW_REPEAT)) return;
  InputEvent e;
  e.kind = EventKind::key;
  e.key = key;
  e.ctrl = mods & GLFW_MOD_CONTROL;
  e.shift = mods & GLFW_MOD_SHIFT;
  w.events.push_back(e);
}

void on_button(GLFWwindow* handle, int button, int action, int mods) {
  Window& w = of(handle);
  w.activity++;
  w.shift = mods & GLFW_MOD_SHIFT;
  if (action == GLFW_PRESS && w.held < 0) {
    // Decided now, from where the pointer is at the press (not from ImGui's WantCaptureMouse,
    // which is the last frame's: a press right after arriving on the panel would also orbit).
    w.held = button;
    w.moved = false;
    w.last = cursor(handle);
    w.pressed_at = w.last;
    w.held_by_panel = on_panel(w, w.last);
    w.camera_press = !w.held_by_panel;
  } else if (action == GLFW_RELEASE && button == w.held) {
    if (!w.moved && button == GLFW_MOUSE_BUTTON_LEFT && !w.held_by_panel) {
      InputEvent e;
      e.kind = EventKind::click;
      e.from = w.pressed_at;
      w.events.push_back(e);
    }
    w.held = -1;
  }
}

void on_cursor(GLFWwindow* handle, double x, double y) {
  Window& w = of(handle);
  w.activity++;
  const glm::vec2 now{float(x), float(y)};
  if (w.held >= 0) {
    if (!w.moved && glm::length(now - w.pressed_at) >= kClickSlop) {
      w.moved = true;
      w.last = w.pressed_at;
    }
    if (w.moved && !w.held_by_panel) {
      InputEvent e;
      e.kind = EventKind::drag;
      e.button = button_of(w.held);
      e.shift = w.shift;
      e.from = w.last;
      e.to = now;
      w.events.push_back(e);
    }
  }
  if (w.held < 0 || w.moved) w.last = now;
}

void on_scroll(GLFWwindow* handle, double, double dy) {
  Window& w = of(handle);
  w.activity++;
  if (w.held_by_panel || on_panel(w, cursor(handle))) return;  // the panel scrolls
  InputEvent e;
  e.kind = EventKind::wheel;
  e.wheel = float(dy);
  w.events.push_back(e);
}

void on_redraw(GLFWwindow* handle) {
  of(handle).activity++;
}

void on_framebuffer(GLFWwindow* handle, int, int) {
  of(handle).activity++;
}

WindowSystemLost g_window_system_lost = nullptr;

// Xlib calls this once the connection is broken; no Xlib call may be made from it, and Xlib
// exits the process if it returns.
int on_io_error(Display* display) {
  const char* name = display ? DisplayString(display) : nullptr;
  g_window_system_lost(name ? name : "");
  return 0;
}

}  // namespace

void on_window_system_lost(WindowSystemLost handler) {
  g_window_system_lost = handler;
  XSetIOErrorHandler(handler ? on_io_error : nullptr);
}

Window::~Window() {
  if (handle) glfwDestroyWindow(handle);
  glfwTerminate();
}

std::unique_ptr<Window> open_window(uint32_t width, uint32_t height, const std::string& title) {
  if (!glfwInit()) throw Error("cannot open a window: " + glfw_error());
  auto window = std::make_unique<Window>();
  if (!glfwVulkanSupported()) {
    throw Error("cannot open a window: GLFW found no Vulkan loader (" + glfw_error() + ")");
  }
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  window->handle = glfwCreateWindow(int(width), int(height), title.c_str(), nullptr, nullptr);
  if (!window->handle) throw Error("cannot open a window: " + glfw_error());
  glfwSetWindowUserPointer(window->handle, window.get());
  glfwSetKeyCallback(window->handle, on_key);
  glfwSetMouseButtonCallback(window->handle, on_button);
  glfwSetCursorPosCallback(window->handle, on_cursor);
  glfwSetScrollCallback(window->handle, on_scroll);
  glfwSetWindowRefreshCallback(window->handle, on_redraw);
  glfwSetFramebufferSizeCallback(window->handle, on_framebuffer);
  return window;
}

std::vector<std::string> window_instance_extensions() {
  // Asked before any window is open (the device is opened first): GLFW must be initialised.
  // open_window's glfwInit then does nothing, and its Window ends GLFW.
  if (!glfwInit()) throw Error("cannot open a window: " + glfw_error());
  if (!glfwVulkanSupported()) {
    throw Error("cannot open a window: GLFW found no Vulkan loader (" + glfw_error() + ")");
  }
  uint32_t count = 0;
  const char** names = glfwGetRequiredInstanceExtensions(&count);
  if (!names) throw Error("GLFW cannot make Vulkan surfaces here: " + glfw_error());
  return std::vector<std::string>(names, names + count);
}

VkSurfaceKHR create_window_surface(VkInstance instance, Window& window) {
  VkSurfaceKHR surface = VK_NULL_HANDLE;
  vk_check(glfwCreateWindowSurface(instance, window.handle, nullptr, &surface),
           "glfwCreateWindowSurface");
  return surface;
}

void framebuffer_size(const Window& window, uint32_t& width, uint32_t& height) {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window.handle, &w, &h);
  width = uint32_t(std::max(w, 0));
  height = uint32_t(std::max(h, 0));
}

bool on_panel(const Window& window, glm::vec2 at) {
  return window.panel_popup || window.panel.contains(at);
}

void wake_window() {
  glfwPostEmptyEvent();
}

std::vector<InputEvent> poll_window(Window& window, double wait_seconds) {
  if (wait_seconds > 0) {
    glfwWaitEventsTimeout(wait_seconds);
  } else {
    glfwPollEvents();
  }
  std::vector<InputEvent> events;
  events.swap(window.events);
  return events;
}

bool window_should_close(const Window& window) {
  return glfwWindowShouldClose(window.handle);
}

bool window_iconified(const Window& window) {
  return glfwGetWindowAttrib(window.handle, GLFW_ICONIFIED);
}

void set_window_size(Window& window, uint32_t width, uint32_t height) {
  glfwSetWindowSize(window.handle, int(width), int(height));
}

void set_window_title(Window& window, const std::string& title) {
  glfwSetWindowTitle(window.handle, title.c_str());
}

}  // namespace tessera
