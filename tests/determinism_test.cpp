// Same scene, same bits: across runs, submission orders, rasterizer paths and thread counts.
#include <algorithm>
#include <fstream>
#include <iterator>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "core/builtin_scenes.h"
#include "core/mesh.h"
#include "tests/support/image_assertions.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

class Determinism : public test::VulkanTest {};

using tessera::testing::same_bits;

// Overlapping, intersecting and coplanar objects, so that depth ties and overdraw matter.
Scene crowded_scene() {
  Scene s = make_sphere_grid_scene();
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-6.0f, 6.0f);
  const size_t n = s.objects.size();
  for (size_t i = 0; i < n; ++i) {
    Object o = s.objects[i];
    o.transform[3] += glm::vec4(u(rng) * 0.2f, u(rng) * 0.2f, u(rng) * 0.2f, 0.0f);
    s.objects.push_back(o);
  }
  // Large intersecting cubes: triangles big enough for the per-tile rasterizer.
  s.meshes.push_back(make_cube());
  for (int i = 0; i < 3; ++i) {
    glm::mat4 t = glm::translate(glm::mat4(1.0f), glm::vec3(-3.0f + 3.0f * i, 0.5f * i, 0.5f));
    t = glm::rotate(t, 0.4f + 0.7f * i, glm::normalize(glm::vec3(1.0f, 2.0f, 0.5f)));
    s.objects.push_back(
        {uint32_t(s.meshes.size() - 1), uint32_t(i * 5), glm::scale(t, glm::vec3(1.6f))});
  }
  // Exact duplicates: identical depth everywhere, so only the id tie-break decides.
  for (size_t i = 0; i < 10; ++i) {
    Object o = s.objects[i * 3];
    o.material = uint32_t((i * 7) % s.materials.size());
    s.objects.push_back(o);
  }
  return s;
}

TEST_F(Determinism, RenderingTwiceGivesIdenticalBits) {
  Scene scene = crowded_scene();
  Renderer renderer(context());
  renderer.set_scene(scene);
  FrameSettings settings;
  settings.width = 200;
  settings.height = 150;
  renderer.render(settings);
  ImageF first = renderer.read_hdr();
  std::vector<uint64_t> vis_first = renderer.read_visibility();
  renderer.render(settings);
  EXPECT_TRUE(same_bits(first, renderer.read_hdr()));
  EXPECT_EQ(vis_first, renderer.read_visibility());
}

TEST_F(Determinism, ShuffledObjectOrderGivesIdenticalBits) {
  Scene scene = crowded_scene();
  Frame reference = render(scene, 200, 150);
  std::mt19937 rng(1234);
  for (int round = 0; round < 3; ++round) {
    std::shuffle(scene.objects.begin(), scene.objects.end(), rng);
    Frame shuffled = render(scene, 200, 150);
    EXPECT_TRUE(same_bits(reference.hdr, shuffled.hdr)) << "round " << round;
    EXPECT_EQ(reference.ldr.pixels, shuffled.ldr.pixels) << "round " << round;
  }
}

// The tile size (RendererOptions::tile_size) changes how large triangles are binned and which
// workgroup rasterizes a pixel, never the nearest sample's key: the same bits at every size,
// with every triangle binned (small-triangle area 0, so that the tiles see all of them), at 1
// and 4 samples per pixel.
TEST_F(Determinism, TileSizesGiveIdenticalBits) {
  Scene scene = crowded_scene();
  scene.camera.position = {0.0f, 0.0f, 9.0f};  // closer: triangles over many tiles
  for (const uint32_t samples : {1u, 4u}) {
    RendererOptions options;
    options.small_triangle_max_area = 0;
    const Frame base = render(scene, 160, 120, options, samples);
    options.tile_size = 8;
    const Frame other = render(scene, 160, 120, options, samples);
    const std::string what = "tile 8, samples " + std::to_string(samples);
    EXPECT_EQ(base.visibility, other.visibility) << what;
    EXPECT_TRUE(same_bits(base.hdr, other.hdr)) << what;
    EXPECT_EQ(base.ldr.pixels, other.ldr.pixels) << what;
  }
}

// A walk of no pixels would divide by zero in small_walks.
TEST_F(Determinism, AWalkAreaOfZeroIsRefused) {
  RendererOptions options;
  options.small_triangle_walk_area = 0;
  try {
    Renderer renderer(context(), options);
    ADD_FAILURE() << "accepted a walk area of 0";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("walk area must be at least 1 pixel"), std::string::npos)
        << e.what();
  }
}

// Sizes other than 8 and 16, and images wider than a bin entry's 1024 tiles, are refused.
TEST_F(Determinism, TileSizesOutOfRangeAreRefused) {
  for (const uint32_t bad : {0u, 4u, 12u, 32u}) {
    RendererOptions options;
    options.tile_size = bad;
    try {
      Renderer renderer(context(), options);
      ADD_FAILURE() << "accepted tile size " << bad;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("tile size " + std::to_string(bad) + " is not 8 or 16"),
                std::string::npos)
          << e.what();
    }
  }
  RendererOptions eight;
  eight.tile_size = 8;
  Renderer renderer(context(), eight);
  renderer.set_scene(crowded_scene());
  // 8193 px need 1025 tiles of 8 px.
  try {
    renderer.render({.width = 8193, .height = 1});
    ADD_FAILURE() << "accepted 8193 px at tile size 8";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("largest side of 8192 px that tiles of 8 px hold"),
              std::string::npos)
        << e.what();
  }
}

TEST_F(Determinism, PerTriangleAndPerTilePathsGiveIdenticalVisibility) {
  Scene scene = crowded_scene();
  scene.camera.position = {0.0f, 0.0f, 9.0f};  // closer: triangles of many sizes
  RendererOptions all_small;
  all_small.small_triangle_max_area = 1u << 30;
  // Every box walked whole by one thread, then dealt out among as many walks as it may take:
  // the walks' rows interleave, some boxes in int32 and the cubes' (as large as the image)
  // in int64 (raster_small.comp).
  RendererOptions whole_walks = all_small, short_walks = all_small;
  whole_walks.small_triangle_walk_area = 1u << 30;
  short_walks.small_triangle_walk_area = 1;
  RendererOptions all_binned;
  all_binned.small_triangle_max_area = 0;
  Frame a = render(scene, 160, 120, whole_walks);
  Frame b = render(scene, 160, 120, all_binned);
  Frame c = render(scene, 160, 120);  // the default split
  Frame d = render(scene, 160, 120, short_walks);
  EXPECT_EQ(a.stats.big_triangles, 0u);
  EXPECT_EQ(b.stats.small_triangles, 0u);
  EXPECT_GT(c.stats.small_triangles, 0u);
  EXPECT_GT(c.stats.big_triangles, 0u);
  EXPECT_EQ(d.stats.small_triangles, a.stats.small_triangles);  // triangles, not walks
  EXPECT_EQ(a.visibility, b.visibility);
  EXPECT_EQ(a.visibility, c.visibility);
  EXPECT_EQ(a.visibility, d.visibility);
  EXPECT_TRUE(same_bits(a.hdr, b.hdr));
  EXPECT_TRUE(same_bits(a.hdr, d.hdr));
}

std::string read_file(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

// lavapipe reads LP_NUM_THREADS when its device is created, so each count runs the tool anew.
TEST(DeterminismAcrossThreads, OneAndTwoLavapipeThreadsGiveIdenticalFiles) {
  std::string outputs[2][2];
  for (int threads = 1; threads <= 2; ++threads) {
    const std::string png = test::output_path("threads" + std::to_string(threads) + ".png");
    const std::string pfm = test::output_path("threads" + std::to_string(threads) + ".pfm");
    std::string log;
    const std::string command =
        "LP_NUM_THREADS=" + std::to_string(threads) +
        " " TESSERA_BINARY " render --device lavapipe --validate --size 256x192 --quiet --out " +
        png + " --hdr-out " + pfm;
    ASSERT_EQ(test::run_command(command, log), 0) << log;
    outputs[threads - 1][0] = read_file(png);
    outputs[threads - 1][1] = read_file(pfm);
  }
  EXPECT_GT(outputs[0][1].size(), 256u * 192 * 12);
  EXPECT_TRUE(outputs[0][0] == outputs[1][0]) << "PNG differs between 1 and 2 threads";
  EXPECT_TRUE(outputs[0][1] == outputs[1][1]) << "HDR differs between 1 and 2 threads";
}

}  // namespace
}  // namespace tessera
