#include "compute/context.h"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string_view>

#include "compute/pipelines.h"
#include "compute/vk_check.h"
#include "compute/vulkan_loader.h"
#include "core/check.h"

namespace tessera {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

VKAPI_ATTR VkBool32 VKAPI_CALL on_validation_message(
    VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT,
    const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  auto* log = static_cast<ValidationLog*>(user);
  const bool error = severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  (error ? log->errors : log->warnings)++;
  std::string text = std::string(error ? "validation error: " : "validation warning: ") +
                     (data->pMessage ? data->pMessage : "");
  std::fprintf(stderr, "%s\n", text.c_str());
  std::lock_guard lock(log->mutex);
  log->messages.push_back(std::move(text));
  return VK_FALSE;
}

bool has_layer(const char* name) {
  uint32_t count = 0;
  vkEnumerateInstanceLayerProperties(&count, nullptr);
  std::vector<VkLayerProperties> layers(count);
  vkEnumerateInstanceLayerProperties(&count, layers.data());
  return std::any_of(layers.begin(), layers.end(), [&](const VkLayerProperties& l) {
    return std::strcmp(l.layerName, name) == 0;
  });
}

VkInstance create_instance(const ContextOptions& options, bool validation) {
  load_vulkan();
  uint32_t version = 0;
  if (vkEnumerateInstanceVersion(&version) != VK_SUCCESS || version < VK_API_VERSION_1_2) {
    throw Error("the Vulkan loader is older than 1.2; Tessera needs Vulkan 1.2");
  }
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "tessera";
  app.apiVersion = VK_API_VERSION_1_2;

  std::vector<const char*> extensions;
  for (const std::string& e : options.instance_extensions) extensions.push_back(e.c_str());
  std::vector<const char*> layers;
  const VkValidationFeatureEnableEXT enables[] = {
      VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
  VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = enables;
  if (validation) {
    if (!has_layer(kValidationLayer)) {
      throw Error(std::string("validation was requested but ") + kValidationLayer +
                  " is not installed (Debian package vulkan-validationlayers)");
    }
    layers.push_back(kValidationLayer);
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
  }
  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pNext = validation ? &features : nullptr;
  info.pApplicationInfo = &app;
  info.enabledLayerCount = uint32_t(layers.size());
  info.ppEnabledLayerNames = layers.data();
  info.enabledExtensionCount = uint32_t(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  VkInstance instance = VK_NULL_HANDLE;
  VkResult result = vkCreateInstance(&info, nullptr, &instance);
  if (result == VK_ERROR_INCOMPATIBLE_DRIVER) {
    throw Error(
        "no Vulkan driver is installed (for the CPU driver: Debian package mesa-vulkan-drivers)");
  }
  vk_check(result, "vkCreateInstance");
  return instance;
}

std::vector<VkPhysicalDevice> physical_devices(VkInstance instance) {
  uint32_t count = 0;
  VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
  std::vector<VkPhysicalDevice> devices(count);
  VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));
  return devices;
}

// Whether `device` offers the device extension `name`.
bool device_has_extension(VkPhysicalDevice device, std::string_view name) {
  uint32_t count = 0;
  VK_CHECK(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr));
  std::vector<VkExtensionProperties> available(count);
  VK_CHECK(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, available.data()));
  for (const VkExtensionProperties& e : available) {
    if (std::string_view(e.extensionName) == name) return true;
  }
  return false;
}

// Features Tessera needs that `device` lacks, as a readable list ("" if none).
std::string missing_features(VkPhysicalDevice device) {
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(device, &props);
  VkPhysicalDeviceVulkan12Features v12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  std::string missing;
  auto add = [&](const char* what) {
    missing += (missing.empty() ? "" : ", ") + std::string(what);
  };
  if (props.apiVersion < VK_API_VERSION_1_2) {
    add("Vulkan 1.2");
    return missing;
  }
  features.pNext = &v12;
  vkGetPhysicalDeviceFeatures2(device, &features);
  if (!features.features.shaderInt64) add("shaderInt64 (64-bit integers in shaders)");
  // The HDR image is written without a format so that one shader serves fp16 and fp32
  // (shaders/bindings.glsl).
  if (!features.features.shaderStorageImageWriteWithoutFormat)
    add("shaderStorageImageWriteWithoutFormat (storing to an image of any format)");
  VkPhysicalDeviceSubgroupProperties subgroup{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
  VkPhysicalDeviceProperties2 props2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  props2.pNext = &subgroup;
  vkGetPhysicalDeviceProperties2(device, &props2);
  const VkSubgroupFeatureFlags needed =
      VK_SUBGROUP_FEATURE_BASIC_BIT | VK_SUBGROUP_FEATURE_BALLOT_BIT;
  if ((subgroup.supportedOperations & needed) != needed ||
      !(subgroup.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT)) {
    add("subgroup ballot and arithmetic operations in compute shaders");
  }
  if (!v12.shaderBufferInt64Atomics) add("shaderBufferInt64Atomics (64-bit buffer atomics)");
  // The shaders read the scene's texels at a buffer device address (shaders/texture.glsl).
  if (!v12.bufferDeviceAddress) add("bufferDeviceAddress (buffers read at a device address)");
  return missing;
}

bool is_lavapipe(VkPhysicalDevice device) {
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(device, &props);
  return props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
}

int type_rank(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return 2;
    default:
      return 3;
  }
}

std::string describe_devices(const std::vector<VkPhysicalDevice>& devices) {
  std::string text;
  for (size_t i = 0; i < devices.size(); ++i) {
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(devices[i], &props);
    text += (text.empty() ? "" : "; ") + std::to_string(i) + ": " + props.deviceName + " (" +
            device_type_name(props.deviceType) + ")";
  }
  return text;
}

VkPhysicalDevice choose_device(VkInstance instance, const std::string& wanted) {
  std::vector<VkPhysicalDevice> devices = physical_devices(instance);
  if (devices.empty()) {
    throw Error("no Vulkan device found (for the CPU driver: Debian package mesa-vulkan-drivers)");
  }
  VkPhysicalDevice chosen = VK_NULL_HANDLE;
  if (wanted == "lavapipe") {
    for (VkPhysicalDevice d : devices) {
      if (is_lavapipe(d)) chosen = d;
    }
    if (!chosen)
      throw Error("no lavapipe (CPU) device found; devices: " + describe_devices(devices));
  } else if (wanted == "gpu" || wanted == "auto") {
    int best = 3;
    for (VkPhysicalDevice d : devices) {
      VkPhysicalDeviceProperties props;
      vkGetPhysicalDeviceProperties(d, &props);
      int rank = type_rank(props.deviceType);
      if (rank < best && missing_features(d).empty()) {
        best = rank;
        chosen = d;
      }
    }
    if (!chosen && wanted == "gpu") {
      bool any_gpu = false;
      for (VkPhysicalDevice d : devices) {
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(d, &props);
        any_gpu = any_gpu || props.deviceType != VK_PHYSICAL_DEVICE_TYPE_CPU;
      }
      throw Error(std::string(any_gpu ? "no GPU with the features Tessera needs"
                                      : "no GPU found (--device lavapipe renders on the CPU)") +
                  "; devices: " + describe_devices(devices));
    }
    if (!chosen) {
      for (VkPhysicalDevice d : devices) {
        if (is_lavapipe(d)) chosen = d;
      }
    }
    if (!chosen) chosen = devices[0];  // its missing features are reported below
  } else {
    unsigned index = 0;
    auto [end, ec] = std::from_chars(wanted.data(), wanted.data() + wanted.size(), index);
    if (ec != std::errc() || end != wanted.data() + wanted.size()) {
      throw Error("unknown device '" + wanted + "' (use lavapipe, gpu, or an index)");
    }
    if (index >= devices.size()) {
      throw Error("device index " + wanted +
                  " is out of range; devices: " + describe_devices(devices));
    }
    chosen = devices[index];
  }
  std::string missing = missing_features(chosen);
  if (!missing.empty()) {
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(chosen, &props);
    throw Error(std::string("device '") + props.deviceName +
                "' lacks what Tessera needs: " + missing);
  }
  return chosen;
}

}  // namespace

void ValidationLog::clear() {
  std::lock_guard lock(mutex);
  errors = 0;
  warnings = 0;
  messages.clear();
}

const char* device_type_name(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return "CPU";
    default:
      return "other";
  }
}

std::vector<DeviceInfo> list_devices() {
  VkInstance instance = create_instance({}, false);
  std::vector<DeviceInfo> infos;
  std::vector<VkPhysicalDevice> devices = physical_devices(instance);
  VkPhysicalDevice preferred = VK_NULL_HANDLE;
  try {
    if (!devices.empty()) preferred = choose_device(instance, "auto");
  } catch (const Error&) {
    // The preferred device lacks features: no device is marked as the default.
  }
  for (uint32_t i = 0; i < devices.size(); ++i) {
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(devices[i], &props);
    infos.push_back({i, props.deviceName, props.deviceType, missing_features(devices[i]),
                     devices[i] == preferred, is_lavapipe(devices[i])});
  }
  vkDestroyInstance(instance, nullptr);
  return infos;
}

std::unique_ptr<Context> create_context(const ContextOptions& options) {
  auto ctx = std::make_unique<Context>();
  ctx->instance = create_instance(options, options.validation);
  if (options.validation) {
    ctx->validation = std::make_unique<ValidationLog>();
    VkDebugUtilsMessengerCreateInfoEXT info{
        VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                           VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    info.pfnUserCallback = on_validation_message;
    info.pUserData = ctx->validation.get();
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(ctx->instance, "vkCreateDebugUtilsMessengerEXT"));
    TESSERA_CHECK(create != nullptr);
    VK_CHECK(create(ctx->instance, &info, nullptr, &ctx->messenger));
  }

  ctx->physical_device = choose_device(ctx->instance, options.device);
  vkGetPhysicalDeviceProperties(ctx->physical_device, &ctx->properties);
  ctx->polygons_in_registers = ctx->properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
  vkGetPhysicalDeviceMemoryProperties(ctx->physical_device, &ctx->memory_properties);
  VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  VkPhysicalDeviceMaintenance3Properties maintenance3{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_3_PROPERTIES};
  VkPhysicalDeviceMaintenance4PropertiesKHR maintenance4{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_4_PROPERTIES_KHR};
  VkPhysicalDeviceProperties2 props2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  props2.pNext = &driver;
  driver.pNext = &maintenance3;
  // maxBufferSize is Vulkan 1.3's (or VK_KHR_maintenance4's); Tessera asks for 1.2.
  const bool has_maintenance4 =
      device_has_extension(ctx->physical_device, VK_KHR_MAINTENANCE_4_EXTENSION_NAME);
  if (has_maintenance4) maintenance3.pNext = &maintenance4;
  vkGetPhysicalDeviceProperties2(ctx->physical_device, &props2);
  ctx->driver = std::string(driver.driverName) + " " + driver.driverInfo;
  ctx->max_allocation_size = maintenance3.maxMemoryAllocationSize;
  ctx->max_buffer_size = has_maintenance4 ? maintenance4.maxBufferSize : UINT64_MAX;

  uint32_t family_count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(ctx->physical_device, &family_count, nullptr);
  std::vector<VkQueueFamilyProperties> families(family_count);
  vkGetPhysicalDeviceQueueFamilyProperties(ctx->physical_device, &family_count, families.data());
  // A family with graphics too, when there is one, so that a window can present from it.
  int family = -1;
  for (uint32_t i = 0; i < family_count; ++i) {
    const VkQueueFlags flags = families[i].queueFlags;
    if (!(flags & VK_QUEUE_COMPUTE_BIT)) continue;
    if (family < 0 || (flags & VK_QUEUE_GRAPHICS_BIT)) family = int(i);
    if (flags & VK_QUEUE_GRAPHICS_BIT) break;
  }
  if (family < 0) {
    throw Error(std::string("device '") + ctx->properties.deviceName + "' has no compute queue");
  }
  ctx->queue_family = uint32_t(family);
  ctx->timestamp_valid_bits = families[family].timestampValidBits;

  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queue_info.queueFamilyIndex = ctx->queue_family;
  queue_info.queueCount = 1;
  queue_info.pQueuePriorities = &priority;

  VkPhysicalDeviceVulkan12Features v12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  v12.shaderBufferInt64Atomics = VK_TRUE;
  v12.bufferDeviceAddress = VK_TRUE;  // missing_features required it
  VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  features.pNext = &v12;
  features.features.shaderInt64 = VK_TRUE;
  features.features.shaderStorageImageWriteWithoutFormat = VK_TRUE;
  VkPhysicalDeviceFeatures available{};
  vkGetPhysicalDeviceFeatures(ctx->physical_device, &available);
  ctx->multi_draw_indirect = available.multiDrawIndirect && available.drawIndirectFirstInstance;
  features.features.multiDrawIndirect = ctx->multi_draw_indirect ? VK_TRUE : VK_FALSE;
  features.features.drawIndirectFirstInstance = ctx->multi_draw_indirect ? VK_TRUE : VK_FALSE;

  std::vector<const char*> extensions;
  VkPhysicalDevicePipelineExecutablePropertiesFeaturesKHR executable_info{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PIPELINE_EXECUTABLE_PROPERTIES_FEATURES_KHR};
  const char* statistics = std::getenv("TESSERA_PIPELINE_STATISTICS");
  if (statistics && std::string_view(statistics) == "1") {
    if (device_has_extension(ctx->physical_device,
                             VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME)) {
      extensions.push_back(VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME);
      executable_info.pipelineExecutableInfo = VK_TRUE;
      v12.pNext = &executable_info;
      ctx->pipeline_statistics = true;
    } else {
      std::fprintf(stderr, "tessera: TESSERA_PIPELINE_STATISTICS: device '%s' lacks %s\n",
                   ctx->properties.deviceName,
                   VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME);
    }
  }
  if (options.swapchain) {
    extensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
    // Lets the resolve pass write B8G8R8A8 and sRGB swapchain images through an R8G8B8A8_UNORM
    // view (compute/swapchain.h); its dependencies (image format list, maintenance2) are core
    // in Vulkan 1.2.
    if (device_has_extension(ctx->physical_device,
                             VK_KHR_SWAPCHAIN_MUTABLE_FORMAT_EXTENSION_NAME)) {
      extensions.push_back(VK_KHR_SWAPCHAIN_MUTABLE_FORMAT_EXTENSION_NAME);
      ctx->swapchain_mutable_format = true;
    }
  }
  VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  info.pNext = &features;
  info.queueCreateInfoCount = 1;
  info.pQueueCreateInfos = &queue_info;
  info.enabledExtensionCount = uint32_t(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  VK_CHECK(vkCreateDevice(ctx->physical_device, &info, nullptr, &ctx->device));
  vkGetDeviceQueue(ctx->device, ctx->queue_family, 0, &ctx->queue);

  VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pool_info.queueFamilyIndex = ctx->queue_family;
  VK_CHECK(vkCreateCommandPool(ctx->device, &pool_info, nullptr, &ctx->command_pool));
  ctx->submission = std::make_unique<Submission>();
  VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  alloc.commandPool = ctx->command_pool;
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  VK_CHECK(vkAllocateCommandBuffers(ctx->device, &alloc, &ctx->submission->cmd));
  VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VK_CHECK(vkCreateFence(ctx->device, &fence_info, nullptr, &ctx->submission->fence));
  ctx->pipeline_cache = std::make_unique<PipelineCache>();
  return ctx;
}

Context::~Context() {
  if (device) {
    vkDeviceWaitIdle(device);
    if (pipeline_cache) destroy_pipeline_cache(*this);
    if (submission && submission->fence) vkDestroyFence(device, submission->fence, nullptr);
    if (command_pool) vkDestroyCommandPool(device, command_pool, nullptr);
    vkDestroyDevice(device, nullptr);
  }
  if (messenger) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy) destroy(instance, messenger, nullptr);
  }
  if (instance) vkDestroyInstance(instance, nullptr);
}

}  // namespace tessera
