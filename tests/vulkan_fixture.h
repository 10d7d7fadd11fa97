#pragma once
// Base fixture of every test that touches Vulkan: a lavapipe context with the Khronos
// validation layer and synchronization validation on, one for all the tests of the process
// (vulkan_fixture.cpp says why). A test fails if the layer reports any warning or error while
// it runs; the test program fails if it reports any as the device is destroyed at its end
// (objects a test leaked). TESSERA_TEST_VALIDATION=0 leaves the layer out (the sanitizers' run,
// vulkan_fixture.cpp says why).

#include <memory>

#include <gtest/gtest.h>

#include "compute/context.h"
#include "compute/renderer.h"
#include "core/image.h"
#include "core/scene.h"

namespace tessera::test {

class VulkanTest : public ::testing::Test {
 public:
  void SetUp() override;
  void TearDown() override;
  Context& context();

  /// Renders `scene` once with a fresh renderer, at `samples` per pixel (FrameSettings), and
  /// returns what the tests look at.
  struct Frame {
    FrameStats stats;
    ImageF hdr;
    Image8 ldr;
    std::vector<uint64_t> visibility;
    std::vector<uint32_t> coverage;  // only with options.debug_coverage
  };
  Frame render(const Scene& scene, uint32_t width, uint32_t height, RendererOptions options,
               uint32_t samples);
  Frame render(const Scene& scene, uint32_t width, uint32_t height, RendererOptions options = {}) {
    return render(scene, width, height, options, 1);
  }
  /// The same with `renderer` and its options, which keeps the pipelines it built: building
  /// them costs lavapipe more than rendering a small frame, so tests that render many scenes
  /// with one set of options reuse one renderer. `coverage`: the renderer was made with
  /// RendererOptions::debug_coverage, and Frame::coverage is read.
  static Frame render(Renderer& renderer, const Scene& scene, uint32_t width, uint32_t height,
                      uint32_t samples = 1, bool coverage = false);
  /// The same with every frame setting given (anti-aliasing weights, for one).
  static Frame render(Renderer& renderer, const Scene& scene, const FrameSettings& settings,
                      bool coverage = false);
};

/// Frame settings of `width` x `height` pixels and `samples` per pixel, the rest default.
FrameSettings frame_of(uint32_t width, uint32_t height, uint32_t samples = 1);

/// Path of a file in the test's own output folder (created if needed).
std::string output_path(const std::string& name);

/// Runs a shell command, returning its exit status and capturing stdout and stderr in `output`.
int run_command(const std::string& command, std::string& output);

}  // namespace tessera::test
