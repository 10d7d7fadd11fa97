// The shading pass resolves its own pixels (GpuFrame.resolve_in_shading): the display image it
// writes must hold the bytes the separate resolve pass computes from the HDR image as stored.
// The reference is that pass itself (RendererInternal::record_resolve, which the window and the
// hardware baseline still use), run by a renderer that stops after shading.
#include <string>

#include <gtest/gtest.h>

#include "compute/gpu_memory.h"
#include "compute/renderer_internal.h"
#include "core/builtin_scenes.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

class ResolveInShading : public test::VulkanTest {};

// Counts the pixels whose bytes differ, and reports the first.
size_t differing_pixels(const Image8& fused, const Image8& separate) {
  EXPECT_EQ(fused.pixels.size(), separate.pixels.size());
  size_t differ = 0;
  for (size_t i = 0; i < fused.pixels.size() && i < separate.pixels.size(); ++i) {
    if (fused.pixels[i] == separate.pixels[i]) continue;
    if (differ++ == 0) {
      ADD_FAILURE() << "pixel " << i << ": shading wrote " << int(fused.pixels[i].r) << ","
                    << int(fused.pixels[i].g) << "," << int(fused.pixels[i].b)
                    << ", the resolve pass " << int(separate.pixels[i].r) << ","
                    << int(separate.pixels[i].g) << "," << int(separate.pixels[i].b);
    }
  }
  return differ;
}

// Both HDR formats (fp16 rounds, which the shading pass must reproduce), one and four samples per
// pixel, the tone curves, a debug view, and exposures that spread the values over the curve.
TEST_F(ResolveInShading, SameBytesAsTheResolvePass) {
  Renderer fused(context());
  RendererOptions stop_after_shading;
  stop_after_shading.resolve = false;
  Renderer separate(context(), stop_after_shading);
  for (const char* name : {"lights", "environment"}) {
    const Scene scene = make_builtin_scene(name);
    fused.set_scene(scene);
    separate.set_scene(scene);
    for (HdrFormat format : {HdrFormat::fp16, HdrFormat::fp32}) {
      for (uint32_t samples : {1u, 4u}) {
        for (auto [tonemap, view, ev] : {std::tuple{ToneMap::aces, View::shaded, 0.0f},
                                         std::tuple{ToneMap::reinhard, View::shaded, 1.5f},
                                         std::tuple{ToneMap::clamp, View::normal, 0.0f}}) {
          const FrameSettings fs{.width = 72,
                                 .height = 40,
                                 .exposure_ev = ev,
                                 .hdr_format = format,
                                 .tonemap = tonemap,
                                 .view = view,
                                 .samples = samples};
          SCOPED_TRACE(std::string(name) + (format == HdrFormat::fp16 ? " fp16" : " fp32") +
                       " samples " + std::to_string(samples) + " tonemap " +
                       std::to_string(int(tonemap)) + " view " + std::to_string(int(view)));
          const FrameStats stats = fused.render(fs);
          // Resolved in the shading pass (else this compares the resolve pass with itself):
          // lavapipe's fp16 stores round toward zero, which the renderer's probe identifies.
          ASSERT_TRUE(stats.has_timestamps);
          EXPECT_EQ(stats.pass_ms[size_t(Pass::resolve)], 0.0);
          EXPECT_GT(stats.pass_ms[size_t(Pass::shade)], 0.0);
          separate.render(fs);
          submit_and_wait(context(), [&](VkCommandBuffer cmd) {
            RendererInternal::record_resolve(separate, cmd);
          });
          const Image8 a = fused.read_ldr();
          const Image8 b = separate.read_ldr();
          EXPECT_EQ(differing_pixels(a, b), 0u);
          // The same HDR image underneath, so the comparison is of the resolves alone.
          EXPECT_EQ(fused.read_hdr().pixels, separate.read_hdr().pixels);
        }
      }
    }
  }
}

}  // namespace
}  // namespace tessera
