#pragma once
// VK_CHECK stays on in release builds: a failed Vulkan call throws tessera::Error naming the
// call and its VkResult, so the user sees what failed instead of a crash later on.

#include <string>

#include <vulkan/vulkan.h>

namespace tessera {

/// Name of a VkResult ("VK_ERROR_OUT_OF_DEVICE_MEMORY", ...), or its number if unknown.
std::string vk_result_name(VkResult result);

/// Throws tessera::Error("<call> failed: <result>") for any result other than VK_SUCCESS.
void vk_check(VkResult result, const char* call);

}  // namespace tessera

#define VK_CHECK(call) ::tessera::vk_check((call), #call)
