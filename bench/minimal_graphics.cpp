// The minimal graphics program of issue 13, the yardstick the hardware baseline is held to:
// N instances of one 960-triangle sphere (core/mesh.h's make_uv_sphere(32, 16)) in ONE indexed
// instanced draw, laid out on a side x side grid (side = ceil(sqrt N)) with centres
// (((i mod side) + 0.5) / side * 2 - 1) * 3, (((i div side) + 0.5) / side * 2 - 1) * 1.7, 0)
// and radius 0.45 * min(6, 3.4) / side, seen from (0, 0, 3) looking at the origin with a 60
// degree vertical field of view; Cook-Torrance with 4 point lights per fragment
// (bench/shaders/minimal.frag); RGBA16F colour and D32 depth; one render pass, timed by
// timestamps before and after it. Vertices and instances come through vertex-input bindings,
// nothing else is read per vertex or fragment but one uniform block. It shares only the device
// set-up and memory helpers with Tessera; `tessera bench --scene yardstick` draws the same
// scene (core/bench_scenes.h: the same layout, materials and lights).
//
//   build/bench/tessera_minimal_graphics [--device D] [--objects 1,10,100] [--size WxH] [--repeat
//   K]
//       [--warmup K] [--warmup-ms MS] [--runs K] [--json FILE] [--csv FILE] [--png PREFIX]
//
// Prints per object count the median, fastest and slowest frame (and with --runs the median of
// the runs' medians and their spread), the warm-up used and the pixels covered. --png writes
// PREFIX_N.png of each count (clamped, sRGB-encoded) to check the picture.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/packing.hpp>

#include "bench/minimal_shaders.h"
#include "compute/baselines/graphics_util.h"
#include "compute/context.h"
#include "compute/gpu_memory.h"
#include "compute/vk_check.h"
#include "core/check.h"
#include "core/image.h"
#include "core/mesh.h"
#include "core/statistics.h"
#include "core/warmup.h"

namespace tessera {
namespace {

constexpr VkFormat kColorFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

struct Options {
  std::string device = "auto";
  std::vector<uint32_t> objects = {1, 10, 100};
  uint32_t width = 512, height = 512;
  uint32_t repeat = 10;
  WarmupRule warmup;
  uint32_t runs = 1;
  std::string json, csv, png;
  std::string command;
};

uint32_t whole(const std::string& option, const std::string& text, uint32_t lo, uint32_t hi) {
  char* end = nullptr;
  const unsigned long v = std::strtoul(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || text[0] == '-' || v < lo || v > hi)
    throw Error(option + ": expects a whole number from " + std::to_string(lo) + " to " +
                std::to_string(hi) + ", got '" + text + "'");
  return uint32_t(v);
}

Options parse(int argc, char** argv) {
  Options o;
  o.command = "tessera_minimal_graphics";
  for (int i = 1; i < argc; ++i) o.command += std::string(" ") + argv[i];
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (i + 1 >= argc) throw Error(flag + ": unknown option or missing value");
    const std::string v = argv[++i];
    if (flag == "--device") {
      o.device = v;
    } else if (flag == "--objects") {
      o.objects.clear();
      size_t start = 0;
      while (start <= v.size()) {
        const size_t comma = std::min(v.find(',', start), v.size());
        o.objects.push_back(whole(flag, v.substr(start, comma - start), 1, 10'000'000));
        start = comma + 1;
      }
    } else if (flag == "--size") {
      const size_t x = v.find('x');
      if (x == std::string::npos) throw Error("--size: expects WxH, got '" + v + "'");
      o.width = whole(flag, v.substr(0, x), 1, 16384);
      o.height = whole(flag, v.substr(x + 1), 1, 16384);
    } else if (flag == "--repeat") {
      o.repeat = whole(flag, v, 1, 1000);
    } else if (flag == "--warmup") {
      o.warmup.min_frames = whole(flag, v, 0, 100);
    } else if (flag == "--warmup-ms") {
      o.warmup.ms = whole(flag, v, 0, 600000);
    } else if (flag == "--runs") {
      o.runs = whole(flag, v, 1, 100);
    } else if (flag == "--json") {
      o.json = v;
    } else if (flag == "--csv") {
      o.csv = v;
    } else if (flag == "--png") {
      o.png = v;
    } else {
      throw Error("unknown option '" + flag + "'");
    }
  }
  return o;
}

// The frame's uniform block (std140, as minimal.vert and minimal.frag declare it).
struct FrameBlock {
  glm::mat4 view_proj;
  glm::vec4 camera;
  glm::vec4 light_position[4];
  glm::vec4 light_radiance[4];
  glm::vec4 ambient;
};

// Per instance (vertex-input binding 1).
struct Instance {
  glm::vec4 centre_radius;
  glm::vec4 base_metallic;
  float roughness;
};

// The layout, and the 7 x 7 palette and four lights of core/bench_scenes.cpp's
// yardstick family, so that both programs draw the same picture.
std::vector<Instance> make_instances(uint32_t n) {
  const uint32_t side = uint32_t(std::ceil(std::sqrt(double(n))));
  std::vector<Instance> out(n);
  for (uint32_t i = 0; i < n; ++i) {
    const float s = float(side);
    const glm::vec3 c(((float(i % side) + 0.5f) / s * 2.0f - 1.0f) * 3.0f,
                      ((float(i / side) + 0.5f) / s * 2.0f - 1.0f) * 1.7f, 0.0f);
    const uint32_t m = i % 49, row = m / 7, col = m % 7;
    out[i] = {glm::vec4(c, 0.45f * std::min(6.0f, 3.4f) / s),
              glm::vec4(0.5f, 0.1f + 0.1f * float(col % 3), 0.05f, float(row) / 6.0f),
              float(col) / 6.0f};
  }
  return out;
}

FrameBlock make_frame(uint32_t width, uint32_t height) {
  FrameBlock f{};
  const glm::vec3 eye(0.0f, 0.0f, 3.0f);
  glm::mat4 proj =
      glm::perspectiveRH_ZO(glm::radians(60.0f), float(width) / float(height), 0.1f, 100.0f);
  proj[1][1] *= -1.0f;  // Vulkan's framebuffer y points down
  f.view_proj = proj * glm::lookAtRH(eye, glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f));
  f.camera = glm::vec4(eye, 1.0f);
  const float d = 4.0f;  // kYardstickLightDistance; intensity 3 d^2 W/sr, white
  const glm::vec2 corners[4] = {{-1, 1}, {1, 1}, {-1, -1}, {1, -1}};
  for (int i = 0; i < 4; ++i) {
    f.light_position[i] = glm::vec4(corners[i] * d, d, 1.0f);
    f.light_radiance[i] = glm::vec4(glm::vec3(3.0f * d * d), 0.0f);
  }
  f.ambient = glm::vec4(glm::vec3(0.03f), 0.0f);
  return f;
}

// A device-local buffer holding `bytes` of `data`, through a staging copy.
Buffer upload(const Context& ctx, const void* data, VkDeviceSize bytes, VkBufferUsageFlags usage) {
  Buffer staging = create_buffer(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryKind::upload);
  std::memcpy(staging.mapped, data, bytes);
  Buffer b =
      create_buffer(ctx, bytes, usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryKind::device);
  submit_and_wait(ctx, [&](VkCommandBuffer cmd) {
    const VkBufferCopy region{0, 0, bytes};
    vkCmdCopyBuffer(cmd, staging.buffer, b.buffer, 1, &region);
    memory_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                   // Vertex and index fetch; the uniforms are read by both shader stages.
                   VK_PIPELINE_STAGE_VERTEX_INPUT_BIT | VK_PIPELINE_STAGE_VERTEX_SHADER_BIT |
                       VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                   VK_ACCESS_VERTEX_ATTRIBUTE_READ_BIT | VK_ACCESS_INDEX_READ_BIT |
                       VK_ACCESS_UNIFORM_READ_BIT);
  });
  destroy_buffer(ctx, staging);
  return b;
}

VkRenderPass create_pass(const Context& ctx) {
  VkAttachmentDescription a[2] = {};
  a[0].format = kColorFormat;
  a[0].samples = VK_SAMPLE_COUNT_1_BIT;
  a[0].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  a[0].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  a[0].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  a[0].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  a[0].initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  a[0].finalLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  a[1] = a[0];
  a[1].format = kDepthFormat;
  a[1].storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  a[1].finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
  const VkAttachmentReference color{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  const VkAttachmentReference depth{1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &color;
  subpass.pDepthStencilAttachment = &depth;
  // The previous frame's attachment writes (and the read-back copy) finish before these.
  const VkSubpassDependency dep{
      VK_SUBPASS_EXTERNAL,
      0,
      VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT |
          VK_PIPELINE_STAGE_TRANSFER_BIT,
      VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT,
      VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
          VK_ACCESS_TRANSFER_READ_BIT,
      VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
          VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT,
      0};
  VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  info.attachmentCount = 2;
  info.pAttachments = a;
  info.subpassCount = 1;
  info.pSubpasses = &subpass;
  info.dependencyCount = 1;
  info.pDependencies = &dep;
  VkRenderPass pass = VK_NULL_HANDLE;
  VK_CHECK(vkCreateRenderPass(ctx.device, &info, nullptr, &pass));
  return pass;
}

VkPipeline create_pipeline(const Context& ctx, VkRenderPass pass, VkPipelineLayout layout) {
  const VkVertexInputBindingDescription bindings[2] = {
      {0, sizeof(glm::vec3), VK_VERTEX_INPUT_RATE_VERTEX},
      {1, sizeof(Instance), VK_VERTEX_INPUT_RATE_INSTANCE}};
  const VkVertexInputAttributeDescription attributes[4] = {
      {0, 0, VK_FORMAT_R32G32B32_SFLOAT, 0},
      {1, 1, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(Instance, centre_radius)},
      {2, 1, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(Instance, base_metallic)},
      {3, 1, VK_FORMAT_R32_SFLOAT, offsetof(Instance, roughness)}};
  GraphicsPipelineDesc desc{"minimal_vert", "minimal_frag", false,
                            // make_uv_sphere's outward faces wind counter-clockwise; the y
                            // flip of the projection and Vulkan's y-down facing rule cancel.
                            VK_CULL_MODE_BACK_BIT, VK_COMPARE_OP_LESS,
                            VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                                VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT};
  desc.vertex_code = find_minimal_shader("minimal_vert");
  desc.fragment_code = find_minimal_shader("minimal_frag");
  desc.bindings = bindings;
  desc.attributes = attributes;
  return create_graphics_pipeline(ctx, pass, layout, desc);
}

// Everything one image size needs: pipeline, attachments, the uniform block and the mesh.
class Program {
 public:
  Program(const Context& ctx, uint32_t width, uint32_t height) : ctx_(ctx), w_(width), h_(height) {
    pass_ = create_pass(ctx);
    const VkDescriptorSetLayoutBinding binding{
        0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1,
        VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, nullptr};
    VkDescriptorSetLayoutCreateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    set_info.bindingCount = 1;
    set_info.pBindings = &binding;
    VK_CHECK(vkCreateDescriptorSetLayout(ctx.device, &set_info, nullptr, &set_layout_));
    VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layout_info.setLayoutCount = 1;
    layout_info.pSetLayouts = &set_layout_;
    VK_CHECK(vkCreatePipelineLayout(ctx.device, &layout_info, nullptr, &layout_));
    pipeline_ = create_pipeline(ctx, pass_, layout_);

    const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1};
    VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pool_info.maxSets = 1;
    pool_info.poolSizeCount = 1;
    pool_info.pPoolSizes = &size;
    VK_CHECK(vkCreateDescriptorPool(ctx.device, &pool_info, nullptr, &pool_));
    VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    alloc.descriptorPool = pool_;
    alloc.descriptorSetCount = 1;
    alloc.pSetLayouts = &set_layout_;
    VK_CHECK(vkAllocateDescriptorSets(ctx.device, &alloc, &set_));
    const FrameBlock frame = make_frame(width, height);
    frame_ = upload(ctx, &frame, sizeof(frame), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
    const VkDescriptorBufferInfo buffer_info{frame_.buffer, 0, sizeof(FrameBlock)};
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstSet = set_;
    write.descriptorCount = 1;
    write.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    write.pBufferInfo = &buffer_info;
    vkUpdateDescriptorSets(ctx.device, 1, &write, 0, nullptr);

    const Mesh sphere = make_uv_sphere(32, 16);
    index_count_ = uint32_t(sphere.indices.size());
    vertices_ = upload(ctx, sphere.positions.data(), sphere.positions.size() * sizeof(glm::vec3),
                       VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    indices_ = upload(ctx, sphere.indices.data(), sphere.indices.size() * sizeof(uint32_t),
                      VK_BUFFER_USAGE_INDEX_BUFFER_BIT);

    color_ = create_image(ctx, width, height, kColorFormat,
                          VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                          VK_IMAGE_ASPECT_COLOR_BIT);
    depth_ = create_image(ctx, width, height, kDepthFormat,
                          VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT);
    const VkImageView views[2] = {color_.view, depth_.view};
    VkFramebufferCreateInfo fb{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    fb.renderPass = pass_;
    fb.attachmentCount = 2;
    fb.pAttachments = views;
    fb.width = width;
    fb.height = height;
    fb.layers = 1;
    VK_CHECK(vkCreateFramebuffer(ctx.device, &fb, nullptr, &framebuffer_));
    if (ctx.timestamp_valid_bits == 0)
      throw Error(std::string("device '") + ctx.properties.deviceName +
                  "' cannot write timestamps on its queue");
    VkQueryPoolCreateInfo query_info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    query_info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    query_info.queryCount = 2;
    VK_CHECK(vkCreateQueryPool(ctx.device, &query_info, nullptr, &queries_));
  }

  ~Program() {
    vkDeviceWaitIdle(ctx_.device);
    destroy_buffer(ctx_, instances_);
    destroy_buffer(ctx_, vertices_);
    destroy_buffer(ctx_, indices_);
    destroy_buffer(ctx_, frame_);
    vkDestroyQueryPool(ctx_.device, queries_, nullptr);
    vkDestroyFramebuffer(ctx_.device, framebuffer_, nullptr);
    destroy_image(ctx_, color_);
    destroy_image(ctx_, depth_);
    vkDestroyDescriptorPool(ctx_.device, pool_, nullptr);
    vkDestroyPipeline(ctx_.device, pipeline_, nullptr);
    vkDestroyPipelineLayout(ctx_.device, layout_, nullptr);
    vkDestroyDescriptorSetLayout(ctx_.device, set_layout_, nullptr);
    vkDestroyRenderPass(ctx_.device, pass_, nullptr);
  }
  Program(const Program&) = delete;
  Program& operator=(const Program&) = delete;

  void set_objects(uint32_t n) {
    vkDeviceWaitIdle(ctx_.device);
    destroy_buffer(ctx_, instances_);
    const std::vector<Instance> instances = make_instances(n);
    instances_ = upload(ctx_, instances.data(), instances.size() * sizeof(Instance),
                        VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    objects_ = n;
  }

  /// One frame; returns the GPU time of its render pass in ms. With `pixels`, reads the image
  /// back into it (after the timed pass).
  double frame(std::vector<uint16_t>* pixels = nullptr) {
    Buffer readback;
    if (pixels) {
      readback = create_buffer(ctx_, VkDeviceSize(w_) * h_ * 8, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                               MemoryKind::readback);
    }
    submit_and_wait(ctx_, [&](VkCommandBuffer cmd) {
      vkCmdResetQueryPool(cmd, queries_, 0, 2);
      vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, queries_, 0);
      VkClearValue clears[2];
      clears[0].color = {{0.02f, 0.02f, 0.025f, 0.0f}};  // alpha 0: not covered
      clears[1].depthStencil = {1.0f, 0};
      VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
      begin.renderPass = pass_;
      begin.framebuffer = framebuffer_;
      begin.renderArea = {{0, 0}, {w_, h_}};
      begin.clearValueCount = 2;
      begin.pClearValues = clears;
      vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
      vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 0, 1, &set_, 0,
                              nullptr);
      const VkViewport viewport{0, 0, float(w_), float(h_), 0, 1};
      const VkRect2D scissor{{0, 0}, {w_, h_}};
      vkCmdSetViewport(cmd, 0, 1, &viewport);
      vkCmdSetScissor(cmd, 0, 1, &scissor);
      const VkBuffer buffers[2] = {vertices_.buffer, instances_.buffer};
      const VkDeviceSize offsets[2] = {0, 0};
      vkCmdBindVertexBuffers(cmd, 0, 2, buffers, offsets);
      vkCmdBindIndexBuffer(cmd, indices_.buffer, 0, VK_INDEX_TYPE_UINT32);
      vkCmdDrawIndexed(cmd, index_count_, objects_, 0, 0, 0);
      vkCmdEndRenderPass(cmd);
      vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queries_, 1);
      if (pixels) record_readback(cmd, readback);
    });
    uint64_t ticks[2];
    VK_CHECK(vkGetQueryPoolResults(ctx_.device, queries_, 0, 2, sizeof(ticks), ticks,
                                   sizeof(uint64_t),
                                   VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    if (pixels) {
      pixels->resize(size_t(w_) * h_ * 4);
      std::memcpy(pixels->data(), readback.mapped, pixels->size() * sizeof(uint16_t));
      destroy_buffer(ctx_, readback);
    }
    return timestamp_interval_ms(ctx_, ticks[0], ticks[1]);
  }

 private:
  void record_readback(VkCommandBuffer cmd, const Buffer& readback) {
    VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    b.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    b.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
    b.oldLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    b.newLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = color_.image;
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                         VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr, 1, &b);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {w_, h_, 1};
    vkCmdCopyImageToBuffer(cmd, color_.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback.buffer,
                           1, &region);
    memory_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                   VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
  }

  const Context& ctx_;
  uint32_t w_, h_;
  VkRenderPass pass_ = VK_NULL_HANDLE;
  VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  Buffer frame_, vertices_, indices_, instances_;
  uint32_t index_count_ = 0, objects_ = 0;

 public:
  uint64_t triangles_per_object() const { return index_count_ / 3; }
  Attachment color_, depth_;
  VkFramebuffer framebuffer_ = VK_NULL_HANDLE;
  VkQueryPool queries_ = VK_NULL_HANDLE;
};

struct Point {
  uint32_t objects = 0;
  uint64_t triangles = 0;
  uint64_t pixels = 0;  // covered (alpha 1)
  std::vector<double> run_ms;
  double median_ms = 0, min_ms = 1e300, max_ms = 0;
  WarmupStats warmup;
  double spread_percent() const {
    if (run_ms.size() < 2 || median_ms <= 0) return 0.0;
    const auto [lo, hi] = std::minmax_element(run_ms.begin(), run_ms.end());
    return (*hi - *lo) / median_ms * 100.0;
  }
};

uint8_t to_srgb8(float linear) {
  const float c = std::clamp(linear, 0.0f, 1.0f);
  const float s = c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
  return uint8_t(std::lround(s * 255.0f));
}

void write_picture(const std::string& path, const std::vector<uint16_t>& half, uint32_t w,
                   uint32_t h) {
  Image8 image;
  image.width = w;
  image.height = h;
  image.pixels.resize(size_t(w) * h);
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    image.pixels[i] = {to_srgb8(glm::unpackHalf1x16(half[4 * i])),
                       to_srgb8(glm::unpackHalf1x16(half[4 * i + 1])),
                       to_srgb8(glm::unpackHalf1x16(half[4 * i + 2])), 255};
  }
  write_png(path, image);
}

void write_outputs(const Options& o, const Context& ctx, const std::vector<Point>& points) {
  if (!o.csv.empty()) {
    std::ofstream f(o.csv);
    f << "scene,objects,backend,width,height,triangles_submitted,pixels_shaded,total_ms,min_ms,"
         "max_ms,runs,run_spread_pct,warmup_frames,warmup_ms,warmup_stable,device\n";
    for (const Point& p : points) {
      f << "yardstick," << p.objects << ",minimal," << o.width << "," << o.height << ","
        << p.triangles << "," << p.pixels << "," << p.median_ms << "," << p.min_ms << ","
        << p.max_ms << "," << p.run_ms.size() << "," << p.spread_percent() << "," << p.warmup.frames
        << "," << p.warmup.ms << "," << (p.warmup.stable ? 1 : 0) << ",\""
        << ctx.properties.deviceName << "\"\n";
    }
    if (!f) throw Error("cannot write CSV '" + o.csv + "'");
  }
  if (!o.json.empty()) {
    // The layout of `tessera bench --json` (scene, size, results[].objects / backend /
    // total_ms), so that `tessera bench --compare` reads it too.
    std::ofstream f(o.json);
    f.precision(9);  // as tessera bench writes them
    const std::time_t now = std::time(nullptr);
    char date[32];
    std::strftime(date, sizeof(date), "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
    f << "{\n  \"device\": \"" << ctx.properties.deviceName << "\",\n  \"driver\": \"" << ctx.driver
      << "\",\n  \"command\": \"" << o.command << "\",\n  \"date\": \"" << date
      << "\",\n  \"scene\": \"yardstick\",\n  \"width\": " << o.width
      << ",\n  \"height\": " << o.height << ",\n  \"frames\": " << o.repeat
      << ",\n  \"runs\": " << o.runs << ",\n  \"warmup\": {\"min_frames\": " << o.warmup.min_frames
      << ", \"min_ms\": " << o.warmup.ms << "},\n  \"statistic\": \"median\",\n  \"results\": [";
    for (size_t i = 0; i < points.size(); ++i) {
      const Point& p = points[i];
      f << (i ? ",\n" : "\n") << "    {\"objects\": " << p.objects
        << ", \"backend\": \"minimal\", \"triangles_submitted\": " << p.triangles
        << ", \"pixels_shaded\": " << p.pixels << ", \"total_ms\": " << p.median_ms
        << ", \"min_ms\": " << p.min_ms << ", \"max_ms\": " << p.max_ms << ", \"run_ms\": [";
      for (size_t r = 0; r < p.run_ms.size(); ++r) f << (r ? ", " : "") << p.run_ms[r];
      f << "], \"run_spread_pct\": " << p.spread_percent()
        << ", \"warmup_frames\": " << p.warmup.frames << ", \"warmup_ms\": " << p.warmup.ms
        << ", \"warmup_stable\": " << (p.warmup.stable ? "true" : "false") << "}";
    }
    f << "\n  ]\n}\n";
    if (!f) throw Error("cannot write JSON '" + o.json + "'");
  }
}

int run(int argc, char** argv) {
  const Options o = parse(argc, argv);
  ContextOptions co;
  co.device = o.device;
  const auto ctx = create_context(co);
  require_graphics_queue(*ctx);
  Program program(*ctx, o.width, o.height);
  std::vector<Point> points(o.objects.size());
  for (uint32_t run = 0; run < o.runs; ++run) {
    for (size_t i = 0; i < o.objects.size(); ++i) {
      Point& p = points[i];
      p.objects = o.objects[i];
      p.triangles = program.triangles_per_object() * p.objects;
      program.set_objects(p.objects);
      const WarmupStats w = warm_up([&] { return program.frame(); }, o.warmup);
      p.warmup.frames += w.frames;
      p.warmup.ms += w.ms;
      p.warmup.stable = run == 0 ? w.stable : p.warmup.stable && w.stable;
      std::vector<double> times;
      for (uint32_t f = 0; f < o.repeat; ++f) times.push_back(program.frame());
      const Summary s = summarize(times);
      p.run_ms.push_back(s.median);
      p.min_ms = std::min(p.min_ms, s.min);
      p.max_ms = std::max(p.max_ms, s.max);
      if (run == 0) {
        std::vector<uint16_t> pixels;
        program.frame(&pixels);
        const uint16_t one = glm::packHalf1x16(1.0f);
        for (size_t k = 3; k < pixels.size(); k += 4) p.pixels += pixels[k] == one;
        if (!o.png.empty())
          write_picture(o.png + "_" + std::to_string(p.objects) + ".png", pixels, o.width,
                        o.height);
      }
    }
  }
  std::printf("minimal graphics program, yardstick layout, %ux%u, device '%s' (%s),\n", o.width,
              o.height, ctx->properties.deviceName, ctx->driver.c_str());
  std::printf("medians of %u frames, warm-up of at least %u frames and %.0f ms; %u run(s)\n",
              o.repeat, o.warmup.min_frames, o.warmup.ms, o.runs);
  std::printf("%9s %10s %10s %10s %10s %10s %8s  %s\n", "objects", "triangles", "pixels",
              "median ms", "min ms", "max ms", "spread", "warm-up");
  for (Point& p : points) {
    p.median_ms = median(p.run_ms);
    char spread[16] = "-";
    if (p.run_ms.size() > 1) std::snprintf(spread, sizeof(spread), "%.1f %%", p.spread_percent());
    std::printf("%9u %10llu %10llu %10.3f %10.3f %10.3f %8s  %u f, %.0f ms%s\n", p.objects,
                (unsigned long long)p.triangles, (unsigned long long)p.pixels, p.median_ms,
                p.min_ms, p.max_ms, spread, p.warmup.frames, p.warmup.ms,
                o.warmup.ms > 0 && !p.warmup.stable ? " (unsettled)" : "");
  }
  write_outputs(o, *ctx, points);
  return 0;
}

}  // namespace
}  // namespace tessera

int main(int argc, char** argv) {
  try {
    return tessera::run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tessera_minimal_graphics: error: %s\n", e.what());
    return 1;
  }
}
