#include "compute/vulkan_loader.h"

#include <dlfcn.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "core/check.h"

namespace tessera {
namespace {

constexpr const char* kDefaultLibrary = "libvulkan.so.1";

struct Loader {
  std::string library;
  std::vector<PFN_vkVoidFunction> commands;  // null where the loader lacks the command
};

std::string library_name() {
  const char* name = std::getenv("TESSERA_VULKAN_LIBRARY");
  return name && *name ? name : kDefaultLibrary;
}

Loader open_loader() {
  Loader loader{library_name(), {}};
  // Never closed: Vulkan objects may outlive any owner Tessera could give the handle.
  void* handle = dlopen(loader.library.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* why = dlerror();
    throw Error("cannot load the Vulkan loader " + loader.library + " (" +
                (why ? why : "unknown reason") +
                "); install it (Debian package libvulkan1) or set TESSERA_VULKAN_LIBRARY to "
                "its path");
  }
  // The loader exports every core command of the Vulkan versions it supports, as the dynamic
  // linker would have found them; these dispatch on the handle passed, so one address serves
  // every instance and device.
  if (!dlsym(handle, "vkGetInstanceProcAddr")) {
    throw Error(loader.library + " is not a Vulkan loader (it has no vkGetInstanceProcAddr)");
  }
  loader.commands.resize(detail::kVulkanCommandCount);
  for (size_t i = 0; i < detail::kVulkanCommandCount; ++i) {
    loader.commands[i] =
        reinterpret_cast<PFN_vkVoidFunction>(dlsym(handle, detail::kVulkanCommandNames[i]));
  }
  return loader;
}

const Loader& loader() {
  // A throwing initializer leaves it uninitialized, so a later call tries again.
  static const Loader instance = open_loader();
  return instance;
}

}  // namespace

void load_vulkan() {
  loader();
}

PFN_vkVoidFunction detail::vulkan_command(size_t index) {
  TESSERA_CHECK(index < kVulkanCommandCount);
  const Loader& l = loader();
  if (!l.commands[index]) {
    throw Error(std::string("the Vulkan loader ") + l.library + " has no " +
                kVulkanCommandNames[index] + "; Tessera needs a Vulkan 1.2 loader or newer");
  }
  return l.commands[index];
}

}  // namespace tessera
