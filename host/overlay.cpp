#include "host/overlay.h"

#include <cfloat>

#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>
#include <imgui.h>

#include "compute/gpu_memory.h"
#include "compute/vk_check.h"
#include "core/check.h"

namespace tessera {
namespace {

void check_imgui_result(VkResult result) {
  vk_check(result, "Dear ImGui's Vulkan backend");
}

VkRenderPass create_render_pass(const Context& ctx, VkFormat format) {
  // Draws over what the resolve pass or the copy wrote (load), then hands the image to
  // presentation.
  VkAttachmentDescription colour{};
  colour.format = format;
  colour.samples = VK_SAMPLE_COUNT_1_BIT;
  colour.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
  colour.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  colour.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  colour.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  colour.initialLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  colour.finalLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
  VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &ref;
  VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  info.attachmentCount = 1;
  info.pAttachments = &colour;
  info.subpassCount = 1;
  info.pSubpasses = &subpass;
  VkRenderPass pass = VK_NULL_HANDLE;
  VK_CHECK(vkCreateRenderPass(ctx.device, &info, nullptr, &pass));
  return pass;
}

void destroy_framebuffers(const Context& ctx, Overlay& overlay) {
  for (VkFramebuffer f : overlay.framebuffers) vkDestroyFramebuffer(ctx.device, f, nullptr);
  overlay.framebuffers.clear();
}

void start_imgui(const Context& ctx, Window& window, const Swapchain& chain, Overlay& overlay) {
  // The font atlas is the backend's one sampled image.
  VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1};
  VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pool_info.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  pool_info.maxSets = 1;
  pool_info.poolSizeCount = 1;
  pool_info.pPoolSizes = &size;
  VK_CHECK(vkCreateDescriptorPool(ctx.device, &pool_info, nullptr, &overlay.pool));

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini written into the working folder
  ImGui::StyleColorsDark();
  // Tighter rows than ImGui's default, so the panel's open sections fit a 512-pixel window.
  ImGui::GetStyle().ItemSpacing.y = 3.0f;
  ImGui::GetStyle().FramePadding.y = 2.0f;
  // Installed after the window's callbacks, which ImGui's call in turn.
  if (!ImGui_ImplGlfw_InitForVulkan(window.handle, true)) {
    throw Error("Dear ImGui's GLFW backend did not initialise");
  }
  ImGui_ImplVulkan_InitInfo info{};
  info.Instance = ctx.instance;
  info.PhysicalDevice = ctx.physical_device;
  info.Device = ctx.device;
  info.QueueFamily = ctx.queue_family;
  info.Queue = ctx.queue;
  info.DescriptorPool = overlay.pool;
  info.MinImageCount = std::max<uint32_t>(2, uint32_t(chain.images.size()));
  info.ImageCount = info.MinImageCount;
  info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
  info.CheckVkResultFn = check_imgui_result;
  if (!ImGui_ImplVulkan_Init(&info, overlay.render_pass)) {
    throw Error("Dear ImGui's Vulkan backend did not initialise");
  }
  submit_and_wait(ctx, [](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
  ImGui_ImplVulkan_DestroyFontUploadObjects();
  overlay.started = true;
}

}  // namespace

void prepare_overlay(const Context& ctx, Window& window, const Swapchain& chain, Overlay& overlay) {
  destroy_framebuffers(ctx, overlay);
  if (overlay.render_pass && overlay.format != chain.view_format) {
    // ImGui's pipeline was built for the old render pass; rare enough to start over.
    destroy_overlay(ctx, overlay);
  }
  if (!overlay.render_pass) {
    overlay.render_pass = create_render_pass(ctx, chain.view_format);
    overlay.format = chain.view_format;
  }
  if (!overlay.started) {
    start_imgui(ctx, window, chain, overlay);
  } else {
    ImGui_ImplVulkan_SetMinImageCount(std::max<uint32_t>(2, uint32_t(chain.images.size())));
  }
  for (VkImageView view : chain.views) {
    VkFramebufferCreateInfo info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    info.renderPass = overlay.render_pass;
    info.attachmentCount = 1;
    info.pAttachments = &view;
    info.width = chain.extent.width;
    info.height = chain.extent.height;
    info.layers = 1;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
    VK_CHECK(vkCreateFramebuffer(ctx.device, &info, nullptr, &framebuffer));
    overlay.framebuffers.push_back(framebuffer);
  }
}

void begin_overlay_frame(bool mouse_elsewhere) {
  ImGui_ImplVulkan_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  if (mouse_elsewhere) {
    // Between the backend reading GLFW's state and ImGui using it.
    ImGuiIO& io = ImGui::GetIO();
    io.MousePos = ImVec2(-FLT_MAX, -FLT_MAX);
    for (bool& down : io.MouseDown) down = false;
  }
  ImGui::NewFrame();
}

void record_overlay(const Overlay& overlay, const Swapchain& chain, VkCommandBuffer cmd,
                    uint32_t index) {
  ImGui::Render();
  VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  begin.renderPass = overlay.render_pass;
  begin.framebuffer = overlay.framebuffers[index];
  begin.renderArea.extent = chain.extent;
  vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
  ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
  vkCmdEndRenderPass(cmd);
}

void discard_overlay_frame() {
  ImGui::EndFrame();
}

bool overlay_wants_keyboard() {
  return ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureKeyboard;
}

bool overlay_popup_open() {
  return ImGui::GetCurrentContext() &&
         ImGui::IsPopupOpen("", ImGuiPopupFlags_AnyPopupId | ImGuiPopupFlags_AnyPopupLevel);
}

void destroy_overlay(const Context& ctx, Overlay& overlay) {
  destroy_framebuffers(ctx, overlay);
  if (overlay.started) {
    ImGui_ImplVulkan_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
  if (overlay.pool) vkDestroyDescriptorPool(ctx.device, overlay.pool, nullptr);
  if (overlay.render_pass) vkDestroyRenderPass(ctx.device, overlay.render_pass, nullptr);
  overlay = Overlay{};
}

}  // namespace tessera
