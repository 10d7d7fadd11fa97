// Tessera opens the Vulkan loader at run time (compute/vulkan_loader.h): no binary links it, and
// a missing loader gets Tessera's message instead of the dynamic linker's.
#include <gtest/gtest.h>

#include <string>

#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

// The shared libraries `binary` names as DT_NEEDED, as readelf prints them.
std::string needed_libraries(const std::string& binary) {
  std::string out;
  EXPECT_EQ(test::run_command("readelf -d " + binary, out), 0) << out;
  std::string needed;
  for (size_t pos = out.find("(NEEDED)"); pos != std::string::npos;
       pos = out.find("(NEEDED)", pos + 1)) {
    needed += out.substr(pos, out.find('\n', pos) - pos) + "\n";
  }
  return needed;
}

TEST(VulkanLoader, NoBinaryNeedsTheLoader) {
  for (const char* binary : {TESSERA_BINARY, "/proc/self/exe"}) {
    const std::string needed = needed_libraries(binary);
    EXPECT_NE(needed.find("libc.so"), std::string::npos) << binary << ":\n" << needed;
    EXPECT_EQ(needed.find("libvulkan"), std::string::npos) << binary << ":\n" << needed;
  }
}

TEST(VulkanLoader, MissingLoaderGetsTesserasMessage) {
  const std::string hide = "TESSERA_VULKAN_LIBRARY=/nonexistent/libvulkan.so.1 ";
  for (const char* command : {" devices", " render --device lavapipe --out x.png"}) {
    std::string out;
    EXPECT_EQ(test::run_command(hide + TESSERA_BINARY + command, out), 1) << out;
    EXPECT_NE(out.find("cannot load the Vulkan loader /nonexistent/libvulkan.so.1"),
              std::string::npos)
        << out;
    EXPECT_NE(out.find("Debian package libvulkan1"), std::string::npos) << out;
  }
}

TEST(VulkanLoader, CommandsWithoutVulkanRunWithoutTheLoader) {
  std::string out;
  EXPECT_EQ(test::run_command("TESSERA_VULKAN_LIBRARY=/nonexistent/libvulkan.so.1 " +
                                  std::string(TESSERA_BINARY) + " scenes",
                              out),
            0)
      << out;
  EXPECT_NE(out.find("spheres"), std::string::npos) << out;
}

TEST(VulkanLoader, ALibraryThatIsNotTheLoaderIsNamed) {
  std::string out;
  EXPECT_EQ(
      test::run_command(
          "TESSERA_VULKAN_LIBRARY=libc.so.6 " + std::string(TESSERA_BINARY) + " devices", out),
      1)
      << out;
  EXPECT_NE(out.find("libc.so.6 is not a Vulkan loader"), std::string::npos) << out;
}

}  // namespace
}  // namespace tessera
