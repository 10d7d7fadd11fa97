// The graphics-pipeline baseline: benchmarks and tests only. It draws the scene the compute
// path renders, from the same buffers, with the same shading code (shaders/lighting.glsl),
// into an RGBA16F attachment copied into the same HDR image, then runs the same resolve pass,
// all through the renderer's internal interface (compute/renderer_internal.h).
#include "compute/baselines/hardware_baseline.h"

#include <chrono>
#include <cstring>
#include <string>
#include <vector>

#include "compute/renderer_internal.h"
#include "compute/timestamps.h"
#include "compute/vk_check.h"
#include "core/check.h"
#include "shaders/shared/gpu_types.h"

namespace tessera {
namespace {

constexpr VkFormat kColorFormat = VK_FORMAT_R16G16B16A16_SFLOAT;  // as the renderer's HDR image
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

VkRenderPass create_pass(const Context& ctx) {
  VkAttachmentDescription a[2] = {};
  a[0].format = kColorFormat;
  a[0].samples = VK_SAMPLE_COUNT_1_BIT;
  a[0].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  a[0].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  a[0].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  a[0].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  a[0].initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;           // cleared
  a[0].finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;  // copied into the renderer's image
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
      // The copy into the renderer's HDR image reads what the draws wrote.
      {0, VK_SUBPASS_EXTERNAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
       VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
       VK_ACCESS_TRANSFER_READ_BIT, 0},
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

// Moves the renderer's HDR image between GENERAL (where its passes keep it) and the copy's
// destination layout; every earlier access to it (the initial barrier made them available)
// and the copy are ordered around the change.
void hdr_layout(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to) {
  VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  const bool to_copy = to == VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  b.srcAccessMask = to_copy ? 0 : VK_ACCESS_TRANSFER_WRITE_BIT;
  b.dstAccessMask = to_copy ? VK_ACCESS_TRANSFER_WRITE_BIT
                            : VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCmdPipelineBarrier(
      cmd, to_copy ? VK_PIPELINE_STAGE_ALL_COMMANDS_BIT : VK_PIPELINE_STAGE_TRANSFER_BIT,
      to_copy ? VK_PIPELINE_STAGE_TRANSFER_BIT : VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0,
      nullptr, 0, nullptr, 1, &b);
}

}  // namespace

HardwareBaseline::HardwareBaseline(Renderer& renderer)
    : renderer_(renderer), ctx_(RendererInternal::context(renderer)) {}

HardwareBaseline::~HardwareBaseline() {
  vkDeviceWaitIdle(ctx_.device);
  destroy_targets();
  for (const auto& [key, p] : pipelines_) {
    if (p) vkDestroyPipeline(ctx_.device, p, nullptr);
  }
  if (pass_) vkDestroyRenderPass(ctx_.device, pass_, nullptr);
  if (queries_) vkDestroyQueryPool(ctx_.device, queries_, nullptr);
}

void HardwareBaseline::destroy_targets() {
  if (framebuffer_) vkDestroyFramebuffer(ctx_.device, framebuffer_, nullptr);
  framebuffer_ = VK_NULL_HANDLE;
  destroy_image(ctx_, depth_);
  destroy_image(ctx_, color_);
}

// Depth image and framebuffer for the renderer's current HDR image, rebuilt whenever the
// renderer recreated its images (a new size).
void HardwareBaseline::ensure_targets(uint64_t generation, uint32_t width, uint32_t height) {
  if (framebuffer_ && images_generation_ == generation) return;
  destroy_targets();
  // An attachment-only colour image, as a graphics renderer would draw into: the renderer's
  // HDR image is a storage image in GENERAL layout, which a driver may keep uncompressed.
  color_ = create_image(ctx_, width, height, kColorFormat,
                        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                        VK_IMAGE_ASPECT_COLOR_BIT);
  depth_ = create_image(ctx_, width, height, kDepthFormat,
                        VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT);
  VkImageView views[2] = {color_.view, depth_.view};
  VkFramebufferCreateInfo fb{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
  fb.renderPass = pass_;
  fb.attachmentCount = 2;
  fb.pAttachments = views;
  fb.width = width;
  fb.height = height;
  fb.layers = 1;
  VK_CHECK(vkCreateFramebuffer(ctx_.device, &fb, nullptr, &framebuffer_));
  images_generation_ = generation;
}

BaselineStats HardwareBaseline::render(const FrameSettings& settings) {
  const Context& ctx = ctx_;
  require_graphics_queue(ctx);
  if (settings.samples != 1) {
    throw Error("the hardware baseline renders 1 sample per pixel, not " +
                std::to_string(settings.samples) +
                " (--samples applies to the compute path and "
                "the reference)");
  }
  // Its colour attachment is copied into the renderer's HDR image, so the formats must match.
  if (settings.hdr_format != HdrFormat::fp16) {
    throw Error(
        "the hardware baseline renders into an fp16 HDR image (--hdr-format fp32 applies to "
        "the compute path and the reference)");
  }
  if (settings.lod == Lod::automatic && !ctx.multi_draw_indirect) {
    throw Error(
        "the hardware baseline's level of detail needs multiDrawIndirect and "
        "drawIndirectFirstInstance, which this device lacks");
  }
  const RendererInternal::Frame frame = RendererInternal::prepare_frame(renderer_, settings);
  if (!pass_) pass_ = create_pass(ctx);
  // Mirrored objects need the opposite front face and double-sided ones no culling: Vulkan 1.2
  // has no dynamic state for either. Variant v: bit 0 mirrored, bit 1 double-sided. Each is
  // specialized as the compute path's shading pass is for this frame (frame.shading). Only the
  // variants the scene's objects use are built: each costs lavapipe about as much as a frame.
  VkPipeline pipelines[4] = {};
  auto build_variant = [&](uint32_t v) {
    const int mirrored = v & 1, double_sided = v >> 1;
    PipelineKey key{};
    std::memcpy(key.data(), &frame.shading, sizeof(frame.shading));
    key.back() = uint32_t(v);
    VkPipeline& pipeline = pipelines_[key];
    if (!pipeline) {
      const GraphicsPipelineDesc desc{
          "baseline_shade_vert",
          // Without texture-map code where no map is sampled (shader_module says why).
          samples_texture_maps(frame.shading) ? "baseline_shade_frag"
                                              : "baseline_shade_frag_untextured",
          false,
          VkCullModeFlags(double_sided                    ? VK_CULL_MODE_NONE
                          : frame.cull == CullMode::back  ? VK_CULL_MODE_BACK_BIT
                          : frame.cull == CullMode::front ? VK_CULL_MODE_FRONT_BIT
                                                          : VK_CULL_MODE_NONE),
          VK_COMPARE_OP_GREATER,  // reverse depth: nearer is larger
          VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT |
              VK_COLOR_COMPONENT_A_BIT,
          mirrored == 1, frame.shading};
      pipeline = create_graphics_pipeline(ctx, pass_, frame.layout, desc);
    }
    pipelines[v] = pipeline;
  };
  ensure_targets(frame.images_generation, frame.width, frame.height);
  const bool timestamps = ctx.timestamp_valid_bits > 0;
  if (timestamps && !queries_) {
    VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    info.queryCount = timestamp_pool_size(ctx, 3);
    VK_CHECK(vkCreateQueryPool(ctx.device, &info, nullptr, &queries_));
  }

  // One instanced draw per run of consecutive object slots that share a mesh, mirroring and
  // double-sidedness (the canonical order sorts by mesh first, so each mesh is one run unless
  // some of its objects are mirrored or differ in material sidedness). Under level of detail
  // the run is one multi-draw of the indexed draws the lod pass wrote, one per object, each at
  // its object's level.
  struct Draw {
    uint32_t first_index, index_count, base_vertex, first_instance, instances, variant, mesh;
  };
  std::vector<Draw> draws;
  const auto& objects = frame.objects;
  for (uint32_t slot = 0; slot < objects.size(); ++slot) {
    const gpu::GpuObject& o = objects[slot];
    const uint32_t variant = o.mirrored | o.double_sided << 1;
    if (!draws.empty() && draws.back().mesh == o.mesh && draws.back().variant == variant &&
        draws.back().first_instance + draws.back().instances == slot) {
      draws.back().instances++;
    } else {
      draws.push_back(
          {o.first_index, o.triangle_count * 3, o.base_vertex, slot, 1, variant, o.mesh});
      if (!pipelines[variant]) build_variant(variant);
    }
  }

  BaselineStats stats;
  stats.draws = uint32_t(draws.size());
  const auto start = std::chrono::steady_clock::now();
  note_render_pass(ctx);
  submit_and_wait(ctx, [&](VkCommandBuffer cmd) {
    memory_barrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_WRITE_BIT,
                   VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                   VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, frame.layout, 0, 1, &frame.set, 0,
                            nullptr);
    RendererInternal::record_precomputation(renderer_, cmd, settings);
    if (timestamps) {
      vkCmdResetQueryPool(cmd, queries_, 0, timestamp_pool_size(ctx, 3));
      write_timestamp(ctx, cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, queries_, 0, 3);
    }
    // Part of the timed frame, as the compute path's lod passes are.
    if (frame.lod) RendererInternal::record_lod(renderer_, cmd);
    VkClearValue clears[2];
    clears[0].color = {{frame.background.r, frame.background.g, frame.background.b, 1.0f}};
    clears[1].depthStencil = {0.0f, 0};  // reverse depth: 0 is infinitely far
    VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    begin.renderPass = pass_;
    begin.framebuffer = framebuffer_;
    begin.renderArea = {{0, 0}, {frame.width, frame.height}};
    begin.clearValueCount = 2;
    begin.pClearValues = clears;
    vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, frame.layout, 0, 1, &frame.set, 0,
                            nullptr);
    const VkViewport viewport{0, 0, float(frame.width), float(frame.height), 0, 1};
    const VkRect2D scissor{{0, 0}, {frame.width, frame.height}};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    if (!draws.empty()) vkCmdBindIndexBuffer(cmd, frame.indices, 0, VK_INDEX_TYPE_UINT32);
    VkPipeline bound = VK_NULL_HANDLE;
    for (const Draw& d : draws) {
      if (pipelines[d.variant] != bound) {
        bound = pipelines[d.variant];
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, bound);
      }
      if (frame.lod) {
        vkCmdDrawIndexedIndirect(
            cmd, frame.lod_draws,
            VkDeviceSize(d.first_instance) * sizeof(VkDrawIndexedIndirectCommand), d.instances,
            sizeof(VkDrawIndexedIndirectCommand));
      } else {
        vkCmdDrawIndexed(cmd, d.index_count, d.instances, d.first_index, int32_t(d.base_vertex),
                         d.first_instance);
      }
    }
    vkCmdEndRenderPass(cmd);
    if (timestamps) write_timestamp(ctx, cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queries_, 1, 3);
    // Bit for bit into the image the resolve pass reads, which is back in GENERAL after.
    hdr_layout(cmd, frame.hdr_image, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    VkImageCopy region{};
    region.srcSubresource = region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.extent = {frame.width, frame.height, 1};
    vkCmdCopyImage(cmd, color_.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, frame.hdr_image,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    hdr_layout(cmd, frame.hdr_image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
    RendererInternal::record_resolve(renderer_, cmd);
    if (timestamps) write_timestamp(ctx, cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queries_, 2, 3);
    stats.cpu_record_submit_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  });
  if (timestamps) {
    uint64_t ticks[3];
    VK_CHECK(vkGetQueryPoolResults(ctx.device, queries_, 0, 3, sizeof(ticks), ticks,
                                   sizeof(uint64_t),
                                   VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    stats.render_pass_ms = timestamp_interval_ms(ctx, ticks[0], ticks[1]);
    stats.resolve_ms = timestamp_interval_ms(ctx, ticks[1], ticks[2]);
    stats.gpu_total_ms = stats.render_pass_ms + stats.resolve_ms;
    stats.has_timestamps = true;
  }
  return stats;
}

}  // namespace tessera
