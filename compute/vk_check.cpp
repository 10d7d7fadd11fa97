#include "compute/vk_check.h"

#include "core/check.h"

namespace tessera {

std::string vk_result_name(VkResult result) {
  switch (result) {
#define TS_RESULT(name) \
  case name:            \
    return #name;
    TS_RESULT(VK_SUCCESS)
    TS_RESULT(VK_NOT_READY)
    TS_RESULT(VK_TIMEOUT)
    TS_RESULT(VK_INCOMPLETE)
    TS_RESULT(VK_ERROR_OUT_OF_HOST_MEMORY)
    TS_RESULT(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    TS_RESULT(VK_ERROR_INITIALIZATION_FAILED)
    TS_RESULT(VK_ERROR_DEVICE_LOST)
    TS_RESULT(VK_ERROR_MEMORY_MAP_FAILED)
    TS_RESULT(VK_ERROR_LAYER_NOT_PRESENT)
    TS_RESULT(VK_ERROR_EXTENSION_NOT_PRESENT)
    TS_RESULT(VK_ERROR_FEATURE_NOT_PRESENT)
    TS_RESULT(VK_ERROR_INCOMPATIBLE_DRIVER)
    TS_RESULT(VK_ERROR_TOO_MANY_OBJECTS)
    TS_RESULT(VK_ERROR_FORMAT_NOT_SUPPORTED)
    TS_RESULT(VK_ERROR_FRAGMENTED_POOL)
    TS_RESULT(VK_ERROR_OUT_OF_POOL_MEMORY)
    TS_RESULT(VK_ERROR_SURFACE_LOST_KHR)
    TS_RESULT(VK_ERROR_OUT_OF_DATE_KHR)
    TS_RESULT(VK_SUBOPTIMAL_KHR)
#undef TS_RESULT
    default:
      return "VkResult " + std::to_string(int(result));
  }
}

void vk_check(VkResult result, const char* call) {
  if (result != VK_SUCCESS) throw Error(std::string(call) + " failed: " + vk_result_name(result));
}

}  // namespace tessera
