#pragma once
// The Vulkan instance, the chosen physical device, one logical device and queue.

#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <vulkan/vulkan.h>

namespace tessera {

struct PipelineCache;  // compute/pipelines.h

struct ContextOptions {
  /// "auto" (a discrete GPU if there is one, else lavapipe), "lavapipe", "gpu" (discrete, else
  /// integrated or virtual), or a device index as listed by list_devices().
  std::string device = "auto";
  /// Enables the Khronos validation layer with synchronization validation; every warning and
  /// error it reports is counted in Context::validation.
  bool validation = false;
  /// Instance extensions a window system needs (e.g. from glfwGetRequiredInstanceExtensions).
  std::vector<std::string> instance_extensions;
  /// Enables VK_KHR_swapchain on the device, for presenting the output image in a window, and
  /// VK_KHR_swapchain_mutable_format where the device has it.
  bool swapchain = false;
};

/// What the validation layer reported. Thread-safe: the layer may call from any thread.
struct ValidationLog {
  std::atomic<uint32_t> errors{0};
  std::atomic<uint32_t> warnings{0};
  std::mutex mutex;
  std::vector<std::string> messages;
  void clear();
};

struct DeviceInfo {
  uint32_t index;
  std::string name;
  VkPhysicalDeviceType type;
  std::string missing;       // features Tessera needs that the device lacks ("" if none)
  bool is_default = false;   // the device `--device auto` (no --device) picks
  bool is_lavapipe = false;  // the device `--device lavapipe` picks
};

/// The command buffer and fence that submit_and_wait records into and waits on, made once per
/// context and reused for every submission. Freeing a command buffer per submission left about
/// 11 KB per frame behind in the Khronos validation layer (1.3.239, Debian 12; heaptrack put it
/// in the layer's state for vkAllocateCommandBuffers and the commands recorded): 10 MB over 1,000
/// frames of `tessera view --validate`, which the viewer's memory test measured.
struct Submission {
  std::mutex mutex;  // one submission at a time: the buffer, the fence and the queue are shared
  std::atomic<std::thread::id> recording{};  // the thread inside submit_and_wait's `record`
  VkCommandBuffer cmd = VK_NULL_HANDLE;      // from Context::command_pool, freed with it
  VkFence fence = VK_NULL_HANDLE;
};

struct Context {
  VkInstance instance = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkPhysicalDevice physical_device = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  uint32_t queue_family = 0;
  VkQueue queue = VK_NULL_HANDLE;
  VkCommandPool command_pool = VK_NULL_HANDLE;
  std::unique_ptr<Submission> submission;  // submit_and_wait's (a pointer: Context is const there)
  VkPhysicalDeviceProperties properties{};
  VkPhysicalDeviceMemoryProperties memory_properties{};
  // The largest single allocation and buffer the device allows (maxMemoryAllocationSize;
  // maxBufferSize where the device has VK_KHR_maintenance4, else 2^64 - 1): the caps of a buffer
  // the shaders read through its device address (the scene's texels), which no descriptor binds.
  uint64_t max_allocation_size = 0;
  uint64_t max_buffer_size = 0;
  uint32_t timestamp_valid_bits = 0;      // 0: the queue cannot write timestamps
  bool swapchain_mutable_format = false;  // VK_KHR_swapchain_mutable_format is enabled
  // multiDrawIndirect and drawIndirectFirstInstance, enabled where the device has both (the
  // hardware baseline's level of detail draws with them).
  bool multi_draw_indirect = false;
  /// Set when the environment variable TESSERA_PIPELINE_STATISTICS is 1 and the device has
  /// VK_KHR_pipeline_executable_properties: each compute pipeline, as it is built, prints the
  /// driver's statistics of its code (registers, spills, ...) to stderr. A developer's
  /// diagnostic (docs/development.md, "Pipeline statistics").
  bool pipeline_statistics = false;
  /// How the shaders keep the polygons they clip to the view and cut by pixel edges
  /// (view_clip.glsl, coverage.glsl; TS_SPEC_POLYGONS_IN_REGISTERS): walked as queues whose
  /// arrays only constants index (true: set for CPU devices, whose compiler then keeps them in
  /// registers and compiles the coverage code about three times as fast), or indexed by corner
  /// (false: GPUs, which ran that up to 18 % faster on the H200). Both give the same bits. Read
  /// when a pipeline is built: changing it builds pipelines of the other form from then on (tests
  /// compare the two).
  bool polygons_in_registers = false;
  /// Set (note_render_pass, compute/timestamps.h) once a render pass has been recorded on the
  /// queue: lavapipe then defers timestamps, and write_timestamp makes up for it. Mutable: the
  /// graphics baselines and the window's overlay record through a const Context.
  mutable std::atomic<bool> render_pass_recorded{false};
  std::string driver;                         // driver name and version, e.g. "NVIDIA 580.159.04"
  std::unique_ptr<ValidationLog> validation;  // set when validation is enabled
  // The compute pipelines built on this device, with the layouts they share: every renderer of
  // the context reuses them (compute/pipelines.h). Destroyed with the context.
  std::unique_ptr<PipelineCache> pipeline_cache;

  Context() = default;
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;
  ~Context();
};

/// Creates the instance and device chosen by `options`. Throws tessera::Error naming what is
/// missing: the Vulkan loader or any device, the requested device, Vulkan 1.2, 64-bit
/// integers or 64-bit buffer atomics, the validation layer when asked for.
std::unique_ptr<Context> create_context(const ContextOptions& options);

/// Every physical device the loader sees, with what Tessera would miss on each.
std::vector<DeviceInfo> list_devices();

/// "discrete GPU", "CPU", ... for messages.
const char* device_type_name(VkPhysicalDeviceType type);

}  // namespace tessera
