#pragma once
// Tessera opens the Vulkan loader (libvulkan.so.1) at run time instead of linking it, so that a
// machine without it gets Tessera's own message instead of the dynamic linker's, and binaries
// start (to print help, list scenes, render with --device reference) without Vulkan. The
// Vulkan commands Tessera calls (compute/vulkan_commands.txt) are defined in a generated file
// as functions with their usual names and prototypes that forward to the loader's, so code
// calls vkCreateBuffer(...) as usual.
//
// TESSERA_VULKAN_LIBRARY, when set and not empty, names the library to open instead of
// libvulkan.so.1: a file name searched like dlopen() does, or a path.

#include <cstddef>

#include <vulkan/vulkan.h>

namespace tessera {

/// Opens the Vulkan loader and resolves every command in compute/vulkan_commands.txt, once per
/// process; later calls return at once. Thread-safe. Throws tessera::Error naming the library
/// if it cannot be opened or is not a Vulkan loader. create_context() and list_devices() call
/// it; calling any listed Vulkan command calls it too.
void load_vulkan();

namespace detail {

/// Generated from compute/vulkan_commands.txt: the names of the commands, in order.
extern const char* const kVulkanCommandNames[];
extern const size_t kVulkanCommandCount;

/// The loader's address of kVulkanCommandNames[index] (index < kVulkanCommandCount), loading
/// the loader first if needed. Throws tessera::Error if the loader cannot be opened or lacks the
/// command (a loader older than the Vulkan version that introduced it).
PFN_vkVoidFunction vulkan_command(size_t index);

}  // namespace detail
}  // namespace tessera
