// What a frame's timestamps measure (Timing, compute/renderer.h): per pass, or the frame alone,
// which `tessera bench` reports as the frame's time because timestamps between the passes add to
// it. Either way the image is the same, and the per-pass times add up to their frame's total.
#include <cmath>
#include <numeric>

#include <gtest/gtest.h>

#include "compute/renderer.h"
#include "core/builtin_scenes.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

class FrameTiming : public test::VulkanTest {};

TEST_F(FrameTiming, FrameTimingLeavesThePassesOutAndTheImageAlone) {
  Renderer renderer(context());
  renderer.set_scene(make_builtin_scene("spheres"));
  for (uint32_t samples : {1u, 4u}) {
    SCOPED_TRACE("samples " + std::to_string(samples));
    const FrameSettings fs{.width = 96, .height = 64, .samples = samples};
    const FrameStats per_pass = renderer.render(fs, Timing::per_pass);
    const ImageF per_pass_image = renderer.read_hdr();
    ASSERT_TRUE(per_pass.has_timestamps) << "lavapipe writes timestamps";
    // Consecutive intervals between the first and the last timestamp: they sum to the total
    // (up to rounding of each interval's milliseconds).
    const double sum = std::accumulate(per_pass.pass_ms.begin(), per_pass.pass_ms.end(), 0.0);
    EXPECT_NEAR(sum, per_pass.gpu_total_ms, 1e-9 * per_pass.gpu_total_ms);
    EXPECT_GT(per_pass.pass_ms[size_t(Pass::setup)], 0.0);
    EXPECT_GT(per_pass.pass_ms[size_t(Pass::shade)], 0.0);

    const FrameStats frame = renderer.render(fs, Timing::frame);
    EXPECT_TRUE(frame.has_timestamps);
    EXPECT_GT(frame.gpu_total_ms, 0.0);
    for (size_t p = 0; p < kPassCount; ++p) {
      EXPECT_EQ(frame.pass_ms[p], 0.0) << pass_name(Pass(p)) << " under Timing::frame";
    }
    // The same frame otherwise: the same counts and the same bits.
    EXPECT_EQ(frame.raster_triangles, per_pass.raster_triangles);
    EXPECT_EQ(frame.small_triangles, per_pass.small_triangles);
    EXPECT_EQ(frame.tile_entries, per_pass.tile_entries);
    EXPECT_EQ(renderer.read_hdr().pixels, per_pass_image.pixels);
  }
}

}  // namespace
}  // namespace tessera
