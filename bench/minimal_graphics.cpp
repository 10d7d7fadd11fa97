// The minimal graphics program of issue 13, the yardstick the hardware baseline is held to:
// N instances of one 960-triangle sphere (core/mesh.h's make_uv_sphere(32, 16)) in ONE indexed
// instanced draw, laid out on a side x side grid (side = ceil(sqrt N)) with centres
// (((i mod side) + 0.5) / side * 2 - 1) * 3, (((i div side) + 0.5) / side * 2 - 1) * 1.7, 0)
// and radius 0.45 * min(6, 3.4) / side, seen from (0, 0, 3) looking at the origin with a 60
// degree vertical field of view; Cook-Torrance with 4 point lights per fragment
// (bench/shaders/minimal_shading.glsl); RGBA16F colour and D32 depth; one render pass, timed by
// timestamps before and after it. Vertices and instances come through vertex-input bindings,
// nothing else is read per vertex or fragment but one uniform block. It shares only the device
// set-up and memory helpers with Tessera; `tessera bench --scene yardstick` draws the same
// scene (core/bench_scenes.h: the same layout, materials and lights).
//
// --variant walks a ladder from this program (rung 0, the default, unchanged) to the hardware
// baseline's work (compute/baselines/), one difference a rung (kRungs below), so that each
// difference's cost is measured: the rungs from storage_shading on draw with Tessera's own
// scene buffers and descriptor set (a Renderer holding the yardstick scene, as the baseline
// does), and the last runs the baseline's own shaders.
//
//   build/bench/tessera_minimal_graphics [--device D] [--objects 1,10,100] [--size WxH] [--repeat
//   K]
//       [--warmup K] [--warmup-ms MS] [--runs K] [--json FILE] [--csv FILE] [--png PREFIX]
//       [--pfm PREFIX] [--variant all|K,K,...|NAME,...]
//
// Prints per rung and object count the median, fastest and slowest frame (and with --runs the
// median of the runs' medians and their spread), the warm-up used and the pixels covered, then
// with several rungs each rung's step over the previous one. Runs go over every object count
// and, within one, every rung in turn. --png writes PREFIX_N.png of each count (clamped,
// sRGB-encoded; PREFIX_RUNG_N.png for rungs other than 0) to check the picture, --pfm the
// same names .pfm with the linear values as the image holds them.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/packing.hpp>

#include "bench/minimal_shaders.h"
#include "compute/baselines/baseline_shaders.h"
#include "compute/baselines/graphics_util.h"
#include "compute/context.h"
#include "compute/gpu_memory.h"
#include "compute/renderer.h"
#include "compute/renderer_internal.h"
#include "compute/timestamps.h"
#include "compute/vk_check.h"
#include "core/bench_scenes.h"
#include "core/check.h"
#include "core/image.h"
#include "core/mesh.h"
#include "core/statistics.h"
#include "core/warmup.h"

namespace tessera {
namespace {

constexpr VkFormat kColorFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

// Where a rung's vertices, instances, material and lights come from.
enum class Data {
  own,              // its own buffers and one uniform block, through vertex input (rung 0)
  scene_instances,  // Tessera's descriptor set (frame constants, materials, lights); its own
                    // unit-sphere vertices and instances (centre, radius, material index)
                    // through vertex input, the instances made from Tessera's objects
  scene,            // Tessera's set only: vertices and objects pulled from its storage buffers
};

// One rung of the ladder: rung k is rung k - 1 with `change` made.
struct Rung {
  const char* name;
  const char* vertex_shader;  // embedded name, bench/shaders/ or compute/baselines/shaders/
  const char* fragment_shader;
  bool reverse_depth;    // z = near / w, GREATER, cleared to 0 (else LESS, cleared to 1)
  bool transfer_layout;  // the colour attachment ends the pass in TRANSFER_SRC_OPTIMAL
  Data data;
  const char* change;
};

constexpr Rung kRungs[] = {
    {"minimal", "minimal_vert", "minimal_frag", false, false, Data::own, "the issue's program"},
    {"reverse_depth", "minimal_reverse_vert", "minimal_reverse_frag", true, false, Data::own,
     "reverse depth (z = near, GREATER, cleared to 0), early fragment tests declared"},
    {"transfer_layout", "minimal_reverse_vert", "minimal_reverse_frag", true, true, Data::own,
     "the colour attachment ends the pass in TRANSFER_SRC_OPTIMAL, as the baseline's (which "
     "copies it)"},
    {"storage_shading", "ladder_storage_vert", "ladder_storage_frag", true, true,
     Data::scene_instances,
     "Tessera's descriptor set: the material (80 B) and 4 lights (80 B each) read per fragment "
     "from storage buffers by a flat material index"},
    {"vertex_pulling", "ladder_pulling_vert", "ladder_storage_frag", true, true, Data::scene,
     "no vertex input: 48-byte vertices by gl_VertexIndex and 160-byte objects by "
     "gl_InstanceIndex from storage buffers, model and normal matrices"},
    {"baseline_vertex", "baseline_shade_vert", "ladder_varyings_frag", true, true, Data::scene,
     "the baseline's vertex stage: + tangent (with mirroring), uv, uv1: 15 varyings"},
    {"tessera_brdf", "baseline_shade_vert", "ladder_brdf_frag", true, true, Data::scene,
     "Tessera's BRDF code (shaders/brdf.glsl: classic Cook-Torrance with its guards) in place "
     "of the minimal program's, lights and ambient still the minimal program's"},
    {"baseline_shaders", "baseline_shade_vert", "baseline_shade_frag", true, true, Data::scene,
     "the baseline's fragment stage: the rest of Tessera's material and lighting code (light "
     "kinds and falloffs, range fade, light-on-surface and zero-normal guards, occlusion and "
     "emissive terms, double-sided test, pre-exposure)"},
};
constexpr uint32_t kRungCount = uint32_t(std::size(kRungs));

// The SPIR-V of an embedded shader of this program or of the baselines.
std::span<const uint32_t> find_ladder_shader(const char* name) {
  const std::span<const uint32_t> own = find_minimal_shader(name);
  return own.empty() ? find_baseline_shader(name) : own;
}

struct Options {
  std::string device = "auto";
  std::vector<uint32_t> rungs = {0};
  std::vector<uint32_t> objects = {1, 10, 100};
  uint32_t width = 512, height = 512;
  uint32_t repeat = 10;
  WarmupRule warmup;
  uint32_t runs = 1;
  std::string json, csv, png, pfm;
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

// The items of a comma-separated list, empty ones included (so that "1,,2" is refused).
std::vector<std::string> split_commas(const std::string& text) {
  std::vector<std::string> items;
  size_t start = 0;
  while (start <= text.size()) {
    const size_t comma = std::min(text.find(',', start), text.size());
    items.push_back(text.substr(start, comma - start));
    start = comma + 1;
  }
  return items;
}

// --variant: "all", or rungs by number or name, in the order given, each once.
std::vector<uint32_t> parse_rungs(const std::string& text) {
  std::vector<uint32_t> rungs;
  if (text == "all") {
    for (uint32_t k = 0; k < kRungCount; ++k) rungs.push_back(k);
    return rungs;
  }
  for (const std::string& item : split_commas(text)) {
    uint32_t k = 0;
    while (k < kRungCount && item != kRungs[k].name && item != std::to_string(k)) ++k;
    if (k == kRungCount) {
      std::string names;
      for (const Rung& r : kRungs) names += std::string(names.empty() ? "" : ", ") + r.name;
      throw Error("--variant: expects all, or rungs 0 to " + std::to_string(kRungCount - 1) +
                  " by number or name (" + names + "), got '" + item + "'");
    }
    if (std::find(rungs.begin(), rungs.end(), k) != rungs.end())
      throw Error("--variant: rung '" + item + "' given twice");
    rungs.push_back(k);
  }
  return rungs;
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
      for (const std::string& item : split_commas(v))
        o.objects.push_back(whole(flag, item, 1, 10'000'000));
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
    } else if (flag == "--pfm") {
      o.pfm = v;
    } else if (flag == "--variant") {
      o.rungs = parse_rungs(v);
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

// Per instance of the storage_shading rung (vertex-input binding 1).
struct SceneInstance {
  glm::vec4 centre_radius;
  uint32_t material;  // index into Tessera's material buffer
};

// The instances of Tessera's objects as uploaded (slot order, material indices as remapped by
// the upload): a yardstick object's model is a translation times a uniform scale, its radius.
std::vector<SceneInstance> scene_instances(std::span<const gpu::GpuObject> objects) {
  std::vector<SceneInstance> out;
  for (const gpu::GpuObject& o : objects)
    out.push_back({glm::vec4(glm::vec3(o.model[3]), o.model[0][0]), o.material});
  return out;
}

// One subpass drawing colour and depth. With `transfer_layout` the colour attachment ends in
// TRANSFER_SRC_OPTIMAL and the copy after the pass waits for it, as the baseline's pass does.
VkRenderPass create_pass(const Context& ctx, bool transfer_layout) {
  VkAttachmentDescription a[2] = {};
  a[0].format = kColorFormat;
  a[0].samples = VK_SAMPLE_COUNT_1_BIT;
  a[0].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  a[0].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  a[0].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  a[0].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  a[0].initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  a[0].finalLayout = transfer_layout ? VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL
                                     : VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
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
  const VkSubpassDependency deps[2] = {
      // The previous frame's attachment writes (and the read-back copy) finish before these.
      {VK_SUBPASS_EXTERNAL, 0,
       VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT |
           VK_PIPELINE_STAGE_TRANSFER_BIT,
       VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT,
       VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
           VK_ACCESS_TRANSFER_READ_BIT,
       VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
           VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT,
       0},
      // The baseline's: its copy into the renderer's HDR image reads what the draws wrote.
      {0, VK_SUBPASS_EXTERNAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
       VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
       VK_ACCESS_TRANSFER_READ_BIT, 0},
  };
  VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  info.attachmentCount = 2;
  info.pAttachments = a;
  info.subpassCount = 1;
  info.pSubpasses = &subpass;
  info.dependencyCount = transfer_layout ? 2 : 1;
  info.pDependencies = deps;
  VkRenderPass pass = VK_NULL_HANDLE;
  VK_CHECK(vkCreateRenderPass(ctx.device, &info, nullptr, &pass));
  return pass;
}

// `rung`'s pipeline; `shading` specializes the baseline's shaders (the others have no
// specialization constants).
VkPipeline create_pipeline(const Context& ctx, VkRenderPass pass, VkPipelineLayout layout,
                           const Rung& rung, const Specialization& shading) {
  const VkVertexInputBindingDescription bindings[2] = {
      {0, sizeof(glm::vec3), VK_VERTEX_INPUT_RATE_VERTEX},
      {1, rung.data == Data::own ? uint32_t(sizeof(Instance)) : uint32_t(sizeof(SceneInstance)),
       VK_VERTEX_INPUT_RATE_INSTANCE}};
  const VkVertexInputAttributeDescription own_attributes[4] = {
      {0, 0, VK_FORMAT_R32G32B32_SFLOAT, 0},
      {1, 1, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(Instance, centre_radius)},
      {2, 1, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(Instance, base_metallic)},
      {3, 1, VK_FORMAT_R32_SFLOAT, offsetof(Instance, roughness)}};
  const VkVertexInputAttributeDescription scene_attributes[3] = {
      {0, 0, VK_FORMAT_R32G32B32_SFLOAT, 0},
      {1, 1, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(SceneInstance, centre_radius)},
      {2, 1, VK_FORMAT_R32_UINT, offsetof(SceneInstance, material)}};
  GraphicsPipelineDesc desc{rung.vertex_shader, rung.fragment_shader, false,
                            // make_uv_sphere's outward faces wind counter-clockwise; the y
                            // flip of the projection and Vulkan's y-down facing rule cancel.
                            VK_CULL_MODE_BACK_BIT,
                            rung.reverse_depth ? VK_COMPARE_OP_GREATER : VK_COMPARE_OP_LESS,
                            VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                                VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT};
  desc.shading = shading;
  desc.vertex_code = find_ladder_shader(rung.vertex_shader);
  desc.fragment_code = find_ladder_shader(rung.fragment_shader);
  TESSERA_CHECK(!desc.vertex_code.empty() && !desc.fragment_code.empty());
  if (rung.data != Data::scene) desc.bindings = bindings;
  if (rung.data == Data::own) desc.attributes = own_attributes;
  if (rung.data == Data::scene_instances) desc.attributes = scene_attributes;
  return create_graphics_pipeline(ctx, pass, layout, desc);
}

// Everything one rung at one image size needs: pipeline, attachments, and its data: the
// uniform block and the mesh, or Tessera's scene (set_objects).
class Program {
 public:
  Program(const Context& ctx, uint32_t width, uint32_t height, const Rung& rung)
      : ctx_(ctx), w_(width), h_(height), rung_(rung) {
    pass_ = create_pass(ctx, rung.transfer_layout);
    if (rung.data == Data::own) create_uniforms();
    if (rung.data != Data::scene) {
      const Mesh sphere = make_uv_sphere(32, 16);
      index_count_ = uint32_t(sphere.indices.size());
      vertices_ = upload(ctx, sphere.positions.data(), sphere.positions.size() * sizeof(glm::vec3),
                         VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
      indices_ = upload(ctx, sphere.indices.data(), sphere.indices.size() * sizeof(uint32_t),
                        VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
    }

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
    query_info.queryCount = timestamp_pool_size(ctx, 2);
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
    if (pool_) vkDestroyDescriptorPool(ctx_.device, pool_, nullptr);
    if (pipeline_) vkDestroyPipeline(ctx_.device, pipeline_, nullptr);
    if (own_layout_) vkDestroyPipelineLayout(ctx_.device, own_layout_, nullptr);
    if (set_layout_) vkDestroyDescriptorSetLayout(ctx_.device, set_layout_, nullptr);
    vkDestroyRenderPass(ctx_.device, pass_, nullptr);
  }
  Program(const Program&) = delete;
  Program& operator=(const Program&) = delete;

  /// Draws `n` objects from now on. Rungs that read Tessera's data take `scene`, the frame
  /// RendererInternal::prepare_frame made of the renderer holding the yardstick scene of `n`
  /// objects (valid until the renderer's scene changes); the others ignore it.
  void set_objects(uint32_t n, const RendererInternal::Frame* scene) {
    vkDeviceWaitIdle(ctx_.device);
    destroy_buffer(ctx_, instances_);
    objects_ = n;
    if (rung_.data == Data::own) {
      const std::vector<Instance> instances = make_instances(n);
      instances_ = upload(ctx_, instances.data(), instances.size() * sizeof(Instance),
                          VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
      return;
    }
    TESSERA_CHECK(scene && scene->objects.size() == n);
    scene_ = *scene;
    // One draw of n instances, as the baseline's for this scene: one mesh, none mirrored or
    // double-sided.
    const gpu::GpuObject& first = scene->objects[0];
    for (const gpu::GpuObject& o : scene->objects)
      TESSERA_CHECK(o.mesh == first.mesh && !o.mirrored && !o.double_sided);
    scene_index_count_ = first.triangle_count * 3;
    scene_first_index_ = first.first_index;
    scene_base_vertex_ = first.base_vertex;
    if (rung_.data == Data::scene_instances) {
      const std::vector<SceneInstance> instances = scene_instances(scene->objects);
      instances_ = upload(ctx_, instances.data(), instances.size() * sizeof(SceneInstance),
                          VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    }
    // The renderer's layout outlives its scenes: one pipeline serves every count.
    if (!pipeline_) pipeline_ = create_pipeline(ctx_, pass_, scene->layout, rung_, scene->shading);
  }

  /// One frame; returns the GPU time of its render pass in ms. With `pixels`, reads the image
  /// back into it (after the timed pass).
  double frame(std::vector<uint16_t>* pixels = nullptr) {
    Buffer readback;
    if (pixels) {
      readback = create_buffer(ctx_, VkDeviceSize(w_) * h_ * 8, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                               MemoryKind::readback);
    }
    const bool own = rung_.data == Data::own;
    note_render_pass(ctx_);
    submit_and_wait(ctx_, [&](VkCommandBuffer cmd) {
      vkCmdResetQueryPool(cmd, queries_, 0, timestamp_pool_size(ctx_, 2));
      write_timestamp(ctx_, cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, queries_, 0, 2);
      VkClearValue clears[2];
      clears[0].color = {{0.02f, 0.02f, 0.025f, 0.0f}};  // alpha 0: not covered
      // Reverse depth: 0 is infinitely far.
      clears[1].depthStencil = {rung_.reverse_depth ? 0.0f : 1.0f, 0};
      VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
      begin.renderPass = pass_;
      begin.framebuffer = framebuffer_;
      begin.renderArea = {{0, 0}, {w_, h_}};
      begin.clearValueCount = 2;
      begin.pClearValues = clears;
      vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
      vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                              own ? own_layout_ : scene_.layout, 0, 1, own ? &set_ : &scene_.set, 0,
                              nullptr);
      const VkViewport viewport{0, 0, float(w_), float(h_), 0, 1};
      const VkRect2D scissor{{0, 0}, {w_, h_}};
      vkCmdSetViewport(cmd, 0, 1, &viewport);
      vkCmdSetScissor(cmd, 0, 1, &scissor);
      if (rung_.data == Data::scene) {
        vkCmdBindIndexBuffer(cmd, scene_.indices, 0, VK_INDEX_TYPE_UINT32);
        vkCmdDrawIndexed(cmd, scene_index_count_, objects_, scene_first_index_,
                         int32_t(scene_base_vertex_), 0);
      } else {
        const VkBuffer buffers[2] = {vertices_.buffer, instances_.buffer};
        const VkDeviceSize offsets[2] = {0, 0};
        vkCmdBindVertexBuffers(cmd, 0, 2, buffers, offsets);
        vkCmdBindIndexBuffer(cmd, indices_.buffer, 0, VK_INDEX_TYPE_UINT32);
        vkCmdDrawIndexed(cmd, index_count_, objects_, 0, 0, 0);
      }
      vkCmdEndRenderPass(cmd);
      write_timestamp(ctx_, cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queries_, 1, 2);
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

  uint64_t triangles_per_object() const {
    return (rung_.data == Data::scene ? scene_index_count_ : index_count_) / 3;
  }

 private:
  // The uniform block, its set and the pipeline of the rungs that keep the minimal program's
  // data.
  void create_uniforms() {
    const VkDescriptorSetLayoutBinding binding{
        0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1,
        VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, nullptr};
    VkDescriptorSetLayoutCreateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    set_info.bindingCount = 1;
    set_info.pBindings = &binding;
    VK_CHECK(vkCreateDescriptorSetLayout(ctx_.device, &set_info, nullptr, &set_layout_));
    VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layout_info.setLayoutCount = 1;
    layout_info.pSetLayouts = &set_layout_;
    VK_CHECK(vkCreatePipelineLayout(ctx_.device, &layout_info, nullptr, &own_layout_));
    pipeline_ = create_pipeline(ctx_, pass_, own_layout_, rung_, Specialization{});

    const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1};
    VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pool_info.maxSets = 1;
    pool_info.poolSizeCount = 1;
    pool_info.pPoolSizes = &size;
    VK_CHECK(vkCreateDescriptorPool(ctx_.device, &pool_info, nullptr, &pool_));
    VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    alloc.descriptorPool = pool_;
    alloc.descriptorSetCount = 1;
    alloc.pSetLayouts = &set_layout_;
    VK_CHECK(vkAllocateDescriptorSets(ctx_.device, &alloc, &set_));
    const FrameBlock frame = make_frame(w_, h_);
    frame_ = upload(ctx_, &frame, sizeof(frame), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
    const VkDescriptorBufferInfo buffer_info{frame_.buffer, 0, sizeof(FrameBlock)};
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstSet = set_;
    write.descriptorCount = 1;
    write.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    write.pBufferInfo = &buffer_info;
    vkUpdateDescriptorSets(ctx_.device, 1, &write, 0, nullptr);
  }

  void record_readback(VkCommandBuffer cmd, const Buffer& readback) {
    // Where the pass left the colour attachment; the transfer_layout rungs' pass has no
    // transition left to make, only the wait.
    const VkImageLayout after_pass = rung_.transfer_layout
                                         ? VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL
                                         : VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    b.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    b.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
    b.oldLayout = after_pass;
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
  const Rung& rung_;
  VkRenderPass pass_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  // Data::own: the uniform block's set.
  VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
  VkPipelineLayout own_layout_ = VK_NULL_HANDLE;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  Buffer frame_, vertices_, indices_, instances_;
  uint32_t index_count_ = 0, objects_ = 0;
  // Tessera's data: the renderer's set, index buffer and the draw of its one mesh.
  RendererInternal::Frame scene_;
  uint32_t scene_index_count_ = 0, scene_first_index_ = 0, scene_base_vertex_ = 0;
  Attachment color_, depth_;
  VkFramebuffer framebuffer_ = VK_NULL_HANDLE;
  VkQueryPool queries_ = VK_NULL_HANDLE;
};

struct Point {
  uint32_t rung = 0;  // index into kRungs
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

// The image's RGB as it holds them (fp16 values, exactly).
ImageF unpack(const std::vector<uint16_t>& half, uint32_t w, uint32_t h) {
  ImageF image;
  image.width = w;
  image.height = h;
  image.pixels.resize(size_t(w) * h);
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    image.pixels[i] =
        glm::vec4(glm::unpackHalf1x16(half[4 * i]), glm::unpackHalf1x16(half[4 * i + 1]),
                  glm::unpackHalf1x16(half[4 * i + 2]), 1.0f);
  }
  return image;
}

// Clamped and sRGB-encoded, to look at.
Image8 picture(const ImageF& linear) {
  Image8 image;
  image.width = linear.width;
  image.height = linear.height;
  image.pixels.resize(linear.pixels.size());
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    const glm::vec4& c = linear.pixels[i];
    image.pixels[i] = {to_srgb8(c.r), to_srgb8(c.g), to_srgb8(c.b), 255};
  }
  return image;
}

void write_outputs(const Options& o, const Context& ctx, const std::vector<Point>& points) {
  if (!o.csv.empty()) {
    std::ofstream f(o.csv);
    f << "scene,objects,backend,width,height,triangles_submitted,pixels_shaded,total_ms,min_ms,"
         "max_ms,runs,run_spread_pct,warmup_frames,warmup_ms,warmup_stable,variant,device\n";
    for (const Point& p : points) {
      f << "yardstick," << p.objects << "," << kRungs[p.rung].name << "," << o.width << ","
        << o.height << "," << p.triangles << "," << p.pixels << "," << p.median_ms << ","
        << p.min_ms << "," << p.max_ms << "," << p.run_ms.size() << "," << p.spread_percent() << ","
        << p.warmup.frames << "," << p.warmup.ms << "," << (p.warmup.stable ? 1 : 0) << ","
        << p.rung << ",\"" << ctx.properties.deviceName << "\"\n";
    }
    if (!f) throw Error("cannot write CSV '" + o.csv + "'");
  }
  if (!o.json.empty()) {
    // The layout of `tessera bench --json` (scene, size, results[].objects / backend /
    // total_ms), so that `tessera bench --compare` reads it too; the backend is the rung's name
    // ("minimal" for rung 0).
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
      f << (i ? ",\n" : "\n") << "    {\"objects\": " << p.objects << ", \"backend\": \""
        << kRungs[p.rung].name << "\", \"variant\": " << p.rung
        << ", \"triangles_submitted\": " << p.triangles << ", \"pixels_shaded\": " << p.pixels
        << ", \"total_ms\": " << p.median_ms << ", \"min_ms\": " << p.min_ms
        << ", \"max_ms\": " << p.max_ms << ", \"run_ms\": [";
      for (size_t r = 0; r < p.run_ms.size(); ++r) f << (r ? ", " : "") << p.run_ms[r];
      f << "], \"run_spread_pct\": " << p.spread_percent()
        << ", \"warmup_frames\": " << p.warmup.frames << ", \"warmup_ms\": " << p.warmup.ms
        << ", \"warmup_stable\": " << (p.warmup.stable ? "true" : "false") << "}";
    }
    f << "\n  ]\n}\n";
    if (!f) throw Error("cannot write JSON '" + o.json + "'");
  }
}

// The yardstick scene of `n` objects in `renderer`, and the frame the rungs that draw with
// Tessera's data take: buffers uploaded, descriptor set written, what it computes once computed.
RendererInternal::Frame prepare_scene(const Context& ctx, Renderer& renderer, uint32_t n,
                                      const FrameSettings& fs) {
  renderer.set_scene(make_bench_scene("yardstick", n, 32, float(fs.width) / float(fs.height)));
  const RendererInternal::Frame frame = RendererInternal::prepare_frame(renderer, fs);
  submit_and_wait(ctx, [&](VkCommandBuffer cmd) {
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, frame.layout, 0, 1, &frame.set, 0,
                            nullptr);
    RendererInternal::record_precomputation(renderer, cmd, fs);
    memory_barrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_WRITE_BIT,
                   VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_READ_BIT);
  });
  return frame;
}

// Each rung's median against the previous rung's (in the order given), per object count.
void print_ladder(const Options& o, const std::vector<Point>& points) {
  const size_t counts = o.objects.size();
  std::printf("\nladder: median ms per object count (step over the previous rung)\n%-20s", "rung");
  for (uint32_t n : o.objects) std::printf(" %19u", n);
  std::printf("\n");
  for (size_t r = 0; r < o.rungs.size(); ++r) {
    std::printf("%u %-18s", o.rungs[r], kRungs[o.rungs[r]].name);
    for (size_t i = 0; i < counts; ++i) {
      const double ms = points[r * counts + i].median_ms;
      if (r == 0) {
        std::printf(" %19.3f", ms);
      } else {
        const double step = ms - points[(r - 1) * counts + i].median_ms;
        std::printf(" %8.3f (%+8.3f)", ms, step);
      }
    }
    std::printf("\n");
  }
  std::printf("rungs (each adds to the one before):\n");
  for (uint32_t k : o.rungs) std::printf("  %u %s: %s\n", k, kRungs[k].name, kRungs[k].change);
}

int run(int argc, char** argv) {
  const Options o = parse(argc, argv);
  ContextOptions co;
  co.device = o.device;
  const auto ctx = create_context(co);
  require_graphics_queue(*ctx);
  std::vector<std::unique_ptr<Program>> programs;
  bool needs_scene = false;
  for (uint32_t k : o.rungs) {
    programs.push_back(std::make_unique<Program>(*ctx, o.width, o.height, kRungs[k]));
    needs_scene = needs_scene || kRungs[k].data != Data::own;
  }
  // Tessera's buffers and set for the rungs that read them, as the baseline has them.
  std::unique_ptr<Renderer> renderer;
  if (needs_scene) renderer = std::make_unique<Renderer>(*ctx);
  FrameSettings fs;
  fs.width = o.width;
  fs.height = o.height;
  const size_t counts = o.objects.size();
  std::vector<Point> points(o.rungs.size() * counts);
  for (uint32_t run = 0; run < o.runs; ++run) {
    for (size_t i = 0; i < counts; ++i) {
      RendererInternal::Frame scene;
      if (renderer) scene = prepare_scene(*ctx, *renderer, o.objects[i], fs);
      // Every rung of this count in turn, so that they see the same state of the device.
      for (size_t r = 0; r < o.rungs.size(); ++r) {
        Program& program = *programs[r];
        Point& p = points[r * counts + i];
        p.rung = o.rungs[r];
        p.objects = o.objects[i];
        program.set_objects(p.objects, renderer ? &scene : nullptr);
        p.triangles = program.triangles_per_object() * p.objects;
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
          const std::string suffix = "_" +
                                     (p.rung == 0 ? "" : std::string(kRungs[p.rung].name) + "_") +
                                     std::to_string(p.objects);
          const ImageF linear = unpack(pixels, o.width, o.height);
          if (!o.png.empty()) write_png(o.png + suffix + ".png", picture(linear));
          if (!o.pfm.empty()) write_hdr_image(o.pfm + suffix + ".pfm", linear);
        }
      }
    }
  }
  std::printf("minimal graphics program, yardstick layout, %ux%u, device '%s' (%s),\n", o.width,
              o.height, ctx->properties.deviceName, ctx->driver.c_str());
  std::printf("medians of %u frames, warm-up of at least %u frames and %.0f ms; %u run(s)\n",
              o.repeat, o.warmup.min_frames, o.warmup.ms, o.runs);
  std::printf("%-18s %9s %10s %10s %10s %10s %10s %8s  %s\n", "rung", "objects", "triangles",
              "pixels", "median ms", "min ms", "max ms", "spread", "warm-up");
  for (Point& p : points) {
    p.median_ms = median(p.run_ms);
    char spread[16] = "-";
    if (p.run_ms.size() > 1) std::snprintf(spread, sizeof(spread), "%.1f %%", p.spread_percent());
    std::printf("%-18s %9u %10llu %10llu %10.3f %10.3f %10.3f %8s  %u f, %.0f ms%s\n",
                kRungs[p.rung].name, p.objects, (unsigned long long)p.triangles,
                (unsigned long long)p.pixels, p.median_ms, p.min_ms, p.max_ms, spread,
                p.warmup.frames, p.warmup.ms,
                o.warmup.ms > 0 && !p.warmup.stable ? " (unsettled)" : "");
  }
  if (o.rungs.size() > 1) print_ladder(o, points);
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
