#pragma once
// The Dear ImGui overlay of `tessera view` (libimgui 1.86 with its GLFW and Vulkan backends):
// a render pass that draws the panel over the swapchain image after the frame was resolved
// into it and after a screenshot's read-back, so it never enters a screenshot. What
// the panel shows and edits is host/view_panel.h.

#include <vector>

#include <vulkan/vulkan.h>

#include "compute/context.h"
#include "compute/swapchain.h"
#include "host/window.h"

namespace tessera {

struct Overlay {
  VkRenderPass render_pass = VK_NULL_HANDLE;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  std::vector<VkFramebuffer> framebuffers;  // one per swapchain image
  VkFormat format = VK_FORMAT_UNDEFINED;
  bool started = false;  // ImGui and its backends initialised
};

/// Initialises ImGui for `window` (its callbacks chain to the window's own) and for drawing
/// into `chain`'s images; call after each create_swapchain (it rebuilds the framebuffers).
/// Throws Error if a backend fails to initialise.
void prepare_overlay(const Context& ctx, Window& window, const Swapchain& chain, Overlay& overlay);

/// Starts an ImGui frame (the panel is built between this and record_overlay). With
/// `mouse_elsewhere` (the camera has the mouse: a press outside the panel, held or not yet
/// seen by ImGui) the panel sees no pointer and no button in this frame, so a camera drag
/// that crosses it neither hovers nor presses its widgets.
void begin_overlay_frame(bool mouse_elsewhere);

/// Ends the ImGui frame and records its drawing into `cmd` over swapchain image `index`
/// (COLOR_ATTACHMENT_OPTIMAL on entry, PRESENT_SRC_KHR after).
void record_overlay(const Overlay& overlay, const Swapchain& chain, VkCommandBuffer cmd,
                    uint32_t index);

/// Ends an ImGui frame begun but not drawn (the frame was not presented).
void discard_overlay_frame();

/// True while the panel has the keyboard (a text field or an active widget), so the camera's
/// keys should not act.
bool overlay_wants_keyboard();

/// True while one of the panel's popups (a combo's list) is open: it takes any press.
bool overlay_popup_open();

/// Shuts ImGui down and destroys the overlay's objects; the device must be idle.
void destroy_overlay(const Context& ctx, Overlay& overlay);

}  // namespace tessera
