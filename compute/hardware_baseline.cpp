// The graphics-pipeline baseline (Renderer::render_hardware): benchmarks and tests only.
// It draws the scene the compute path renders, from the same buffers, with the same shading
// code (shaders/lighting.glsl), into the same HDR image, then runs the same resolve pass.
#include <chrono>
#include <string>

#include "compute/graphics_util.h"
#include "compute/renderer_state.h"
#include "compute/vk_check.h"
#include "core/check.h"

namespace tessera {
namespace {

constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
// Brdf values are passed as the TS_SPEC_BRDF specialization constant.
static_assert(uint32_t(Brdf::classic) == TS_BRDF_CLASSIC &&
              uint32_t(Brdf::filament) == TS_BRDF_FILAMENT &&
              uint32_t(Brdf::blinn_phong) == TS_BRDF_BLINN_PHONG);

VkRenderPass create_pass(const Context& ctx) {
  VkAttachmentDescription a[2] = {};
  a[0].format = VK_FORMAT_R16G16B16A16_SFLOAT;  // the renderer's HDR image
  a[0].samples = VK_SAMPLE_COUNT_1_BIT;
  a[0].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  a[0].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  a[0].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  a[0].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  a[0].initialLayout = VK_IMAGE_LAYOUT_GENERAL;  // where the compute passes keep it
  a[0].finalLayout = VK_IMAGE_LAYOUT_GENERAL;
  a[1] = a[0];
  a[1].format = kDepthFormat;
  a[1].storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  a[1].initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  a[1].finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
  VkAttachmentReference color{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkAttachmentReference depth{1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &color;
  subpass.pDepthStencilAttachment = &depth;
  const VkSubpassDependency deps[2] = {
      // Earlier compute passes and copies used the HDR image and the scene buffers.
      {VK_SUBPASS_EXTERNAL, 0,
       VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
       VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
           VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
       VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT,
       VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_COLOR_ATTACHMENT_READ_BIT |
           VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
           VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT,
       0},
      // The resolve pass reads what the draws wrote.
      {0, VK_SUBPASS_EXTERNAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
       VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
       VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
       VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT, 0},
  };
  VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  info.attachmentCount = 2;
  info.pAttachments = a;
  info.subpassCount = 1;
  info.pSubpasses = &subpass;
  info.dependencyCount = 2;
  info.pDependencies = deps;
  VkRenderPass pass = VK_NULL_HANDLE;
  VK_CHECK(vkCreateRenderPass(ctx.device, &info, nullptr, &pass));
  return pass;
}

void destroy_size_dependent(Renderer::State& s) {
  if (s.baseline_framebuffer) vkDestroyFramebuffer(s.ctx.device, s.baseline_framebuffer, nullptr);
  s.baseline_framebuffer = VK_NULL_HANDLE;
  destroy_image(s.ctx, s.depth);
  s.baseline_width = s.baseline_height = 0;
}

// Depth image and framebuffer for the current image size (the HDR image may have been
// recreated since: the framebuffer is rebuilt whenever the size changed).
void ensure_targets(Renderer::State& s) {
  const Context& ctx = s.ctx;
  if (s.baseline_width == s.width && s.baseline_height == s.height && s.baseline_framebuffer)
    return;
  destroy_size_dependent(s);
  s.depth = create_image(ctx, s.width, s.height, kDepthFormat,
                         VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT);
  VkImageView views[2] = {s.hdr.view, s.depth.view};
  VkFramebufferCreateInfo fb{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
  fb.renderPass = s.baseline_pass;
  fb.attachmentCount = 2;
  fb.pAttachments = views;
  fb.width = s.width;
  fb.height = s.height;
  fb.layers = 1;
  VK_CHECK(vkCreateFramebuffer(ctx.device, &fb, nullptr, &s.baseline_framebuffer));
  s.baseline_width = s.width;
  s.baseline_height = s.height;
}

uint32_t div_up(uint32_t a, uint32_t b) {
  return (a + b - 1) / b;
}

}  // namespace

void destroy_hardware_baseline(Renderer::State& s) {
  destroy_size_dependent(s);
  for (VkPipeline& p : s.baseline_pipelines) {
    if (p) vkDestroyPipeline(s.ctx.device, p, nullptr);
    p = VK_NULL_HANDLE;
  }
  if (s.baseline_pass) vkDestroyRenderPass(s.ctx.device, s.baseline_pass, nullptr);
  s.baseline_pass = VK_NULL_HANDLE;
}

Renderer::BaselineStats Renderer::render_hardware(const FrameSettings& settings) {
  State& s = *s_;
  Context& ctx = s.ctx;
  if (!s.has_scene) throw Error("render_hardware() was called before set_scene()");
  require_graphics_queue(ctx);
  const uint32_t old_width = s.width, old_height = s.height;
  ensure_frame_resources(s, settings);
  if (s.width != old_width || s.height != old_height) destroy_size_dependent(s);
  init_capacities(s);
  ensure_scratch_buffers(s, 1);
  if (!s.baseline_pass) s.baseline_pass = create_pass(ctx);
  VkPipeline& pipeline =
      s.baseline_pipelines[size_t(settings.brdf) * 2 + (settings.energy_compensation ? 1 : 0)];
  if (!pipeline) {
    const GraphicsPipelineDesc desc{
        "baseline_shade_vert",
        "baseline_shade_frag",
        false,
        VkCullModeFlags(s.options.cull == CullMode::back    ? VK_CULL_MODE_BACK_BIT
                        : s.options.cull == CullMode::front ? VK_CULL_MODE_FRONT_BIT
                                                            : VK_CULL_MODE_NONE),
        VK_COMPARE_OP_GREATER,  // reverse depth: nearer is larger
        VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT |
            VK_COLOR_COMPONENT_A_BIT,
        uint32_t(settings.brdf),
        settings.energy_compensation ? VK_TRUE : VK_FALSE};
    pipeline = create_graphics_pipeline(ctx, s.baseline_pass, s.pipelines.layout, desc);
  }
  ensure_targets(s);
  const bool timestamps = ctx.timestamp_valid_bits > 0;
  if (timestamps && s.query_capacity < 3) {
    if (s.queries) vkDestroyQueryPool(ctx.device, s.queries, nullptr);
    VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    info.queryCount = 3;
    VK_CHECK(vkCreateQueryPool(ctx.device, &info, nullptr, &s.queries));
    s.query_capacity = 3;
  }
  if (s.descriptors_dirty) {
    update_descriptors();
    s.descriptors_dirty = false;
  }
  write_frame_constants(settings);

  // One instanced draw per run of consecutive object slots that share a mesh (the canonical
  // order sorts by mesh first, so each mesh is one run).
  struct Draw {
    uint32_t first_index, index_count, base_vertex, first_instance, instances;
  };
  std::vector<Draw> draws;
  const auto& objects = s.uploaded.objects;
  for (uint32_t slot = 0; slot < objects.size(); ++slot) {
    const gpu::GpuObject& o = objects[slot];
    if (!draws.empty() && draws.back().first_index == o.first_index &&
        draws.back().base_vertex == o.base_vertex &&
        draws.back().first_instance + draws.back().instances == slot) {
      draws.back().instances++;
    } else {
      draws.push_back({o.first_index, o.triangle_count * 3, o.base_vertex, slot, 1});
    }
  }

  BaselineStats stats;
  stats.draws = uint32_t(draws.size());
  const auto start = std::chrono::steady_clock::now();
  submit_and_wait(ctx, [&](VkCommandBuffer cmd) {
    memory_barrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_WRITE_BIT,
                   VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                   VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, s.pipelines.layout, 0, 1, &s.set,
                            0, nullptr);
    record_precomputation(s, cmd, settings);
    if (timestamps) {
      vkCmdResetQueryPool(cmd, s.queries, 0, 3);
      vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, s.queries, 0);
    }
    VkClearValue clears[2];
    // Pre-exposed and clamped like every value the shading pass writes (shade.comp).
    const glm::vec3 clear = glm::min(s.background * s.hdr_pre_exposure, glm::vec3(65504.0f));
    clears[0].color = {{clear.r, clear.g, clear.b, 1.0f}};
    clears[1].depthStencil = {0.0f, 0};  // reverse depth: 0 is infinitely far
    VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    begin.renderPass = s.baseline_pass;
    begin.framebuffer = s.baseline_framebuffer;
    begin.renderArea = {{0, 0}, {s.width, s.height}};
    begin.clearValueCount = 2;
    begin.pClearValues = clears;
    vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, s.pipelines.layout, 0, 1, &s.set,
                            0, nullptr);
    const VkViewport viewport{0, 0, float(s.width), float(s.height), 0, 1};
    const VkRect2D scissor{{0, 0}, {s.width, s.height}};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    if (!draws.empty()) vkCmdBindIndexBuffer(cmd, s.indices.buffer, 0, VK_INDEX_TYPE_UINT32);
    for (const Draw& d : draws) {
      vkCmdDrawIndexed(cmd, d.index_count, d.instances, d.first_index, int32_t(d.base_vertex),
                       d.first_instance);
    }
    vkCmdEndRenderPass(cmd);
    if (timestamps) vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, s.queries, 1);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, s.pipelines[Pipeline::resolve]);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, s.pipelines.layout, 0, 1, &s.set,
                            0, nullptr);
    vkCmdDispatch(cmd, div_up(s.width, 8), div_up(s.height, 8), 1);
    memory_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                   VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
    if (timestamps) vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, s.queries, 2);
    stats.cpu_record_submit_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  });
  if (timestamps) {
    uint64_t ticks[3];
    VK_CHECK(vkGetQueryPoolResults(ctx.device, s.queries, 0, 3, sizeof(ticks), ticks,
                                   sizeof(uint64_t),
                                   VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    const uint64_t mask =
        ctx.timestamp_valid_bits >= 64 ? ~0ull : (1ull << ctx.timestamp_valid_bits) - 1;
    const double ms = ctx.properties.limits.timestampPeriod * 1e-6;
    stats.render_pass_ms = double(((ticks[1] & mask) - (ticks[0] & mask)) & mask) * ms;
    stats.resolve_ms = double(((ticks[2] & mask) - (ticks[1] & mask)) & mask) * ms;
    stats.gpu_total_ms = stats.render_pass_ms + stats.resolve_ms;
    stats.has_timestamps = true;
  }
  return stats;
}

}  // namespace tessera
