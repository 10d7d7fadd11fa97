// Golden images: the built-in scenes under the main option combinations, compared bit for bit
// with images stored in tests/golden/. These are regression tests (the accuracy tests compare
// with the independent reference): a refactoring must leave every bit as it was, and a change
// meant to alter images must say which and why when it regenerates them
// (TESSERA_UPDATE_GOLDENS=1, then review the PNGs before committing).
//
// Exact on lavapipe (Mesa 22.3.6 as Debian 12 ships it), the device the suite runs on. Besides
// the display image, the linear HDR image and the visibility buffer are compared through a
// 64-bit FNV-1a hash of their bytes, kept in a .hash file beside the PNG.
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "core/builtin_scenes.h"
#include "tests/golden.h"
#include "tests/support/image_assertions.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

struct GoldenCase {
  const char* name;
  const char* scene;
  FrameSettings settings;
  bool generic_shading = false;
};

FrameSettings with(void (*edit)(FrameSettings&)) {
  FrameSettings s;
  s.width = 96;
  s.height = 72;  // not square, not a multiple of the tile size
  edit(s);
  return s;
}

const GoldenCase kCases[] = {
    {"spheres", "spheres", with([](FrameSettings&) {})},
    {"spheres_generic", "spheres", with([](FrameSettings&) {}), true},
    {"spheres_filament_compensated", "spheres", with([](FrameSettings& s) {
       s.brdf = Brdf::filament;
       s.energy_compensation = true;
     })},
    {"spheres_classic_compensated", "spheres",
     with([](FrameSettings& s) { s.energy_compensation = true; })},
    {"spheres_blinn_phong", "spheres", with([](FrameSettings& s) { s.brdf = Brdf::blinn_phong; })},
    {"spheres_reinhard_minus1ev", "spheres", with([](FrameSettings& s) {
       s.tonemap = ToneMap::reinhard;
       s.exposure_ev = -1.0f;
     })},
    {"spheres_clamp_plus2ev", "spheres", with([](FrameSettings& s) {
       s.tonemap = ToneMap::clamp;
       s.exposure_ev = 2.0f;
     })},
    {"spheres_view_normal", "spheres", with([](FrameSettings& s) { s.view = View::normal; })},
    {"spheres_view_triangle", "spheres", with([](FrameSettings& s) { s.view = View::triangle; })},
    {"spheres_view_object", "spheres", with([](FrameSettings& s) { s.view = View::object; })},
    {"metals", "metals", with([](FrameSettings&) {})},
    {"lights", "lights", with([](FrameSettings&) {})},
    {"lights_generic", "lights", with([](FrameSettings&) {}), true},
    {"textured", "textured", with([](FrameSettings&) {})},
    {"textured_anisotropy8", "textured", with([](FrameSettings& s) { s.max_anisotropy = 8; })},
    {"textured_view_uv", "textured", with([](FrameSettings& s) { s.view = View::uv; })},
    {"environment", "environment", with([](FrameSettings&) {})},
    {"environment_generic", "environment", with([](FrameSettings&) {}), true},
    {"environment_filament_compensated", "environment", with([](FrameSettings& s) {
       s.brdf = Brdf::filament;
       s.energy_compensation = true;
     })},
};

uint64_t fnv1a(const void* data, size_t bytes, uint64_t h = 0xcbf29ce484222325ull) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 0x100000001b3ull;
  return h;
}

std::string golden_dir() {
  return TESSERA_GOLDEN_DIR;
}

class Golden : public test::VulkanTest, public ::testing::WithParamInterface<GoldenCase> {};

TEST_P(Golden, BitIdentical) {
  const GoldenCase& c = GetParam();
  RendererOptions options;
  options.specialize_lights = !c.generic_shading;
  Renderer renderer(context(), options);
  renderer.set_scene(make_builtin_scene(c.scene));
  renderer.render(c.settings);
  test::expect_golden(renderer, c.name);
}

INSTANTIATE_TEST_SUITE_P(BuiltinScenes, Golden, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<GoldenCase>& info) {
                           return std::string(info.param.name);
                         });

}  // namespace

void test::expect_golden(Renderer& renderer, const std::string& name) {
  const ImageF hdr = renderer.read_hdr();
  const Image8 ldr = renderer.read_ldr();
  const std::vector<uint64_t> vis = renderer.read_visibility();
  const uint64_t hdr_hash = fnv1a(hdr.pixels.data(), hdr.pixels.size() * sizeof(hdr.pixels[0]));
  const uint64_t vis_hash = fnv1a(vis.data(), vis.size() * sizeof(vis[0]));

  const std::string base = golden_dir() + "/" + name;
  EXPECT_MATCHES_GOLDEN(ldr, base + ".png", 0);

  const char* update = std::getenv("TESSERA_UPDATE_GOLDENS");
  if (update && std::string(update) == "1") {
    std::ofstream(base + ".hash") << std::hex << hdr_hash << " " << vis_hash << "\n";
    return;
  }
  std::ifstream in(base + ".hash");
  ASSERT_TRUE(in) << base << ".hash does not exist; run with TESSERA_UPDATE_GOLDENS=1";
  uint64_t want_hdr = 0, want_vis = 0;
  in >> std::hex >> want_hdr >> want_vis;
  EXPECT_EQ(vis_hash, want_vis) << "visibility buffer differs from the golden one";
  EXPECT_EQ(hdr_hash, want_hdr) << "linear HDR image differs from the golden one";
}

}  // namespace tessera
