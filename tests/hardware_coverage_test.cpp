// A second, external check of coverage: the same triangles through lavapipe's graphics pipeline
// (its hardware-style rasterizer, 8 sub-pixel bits) and through the compute path, compared
// pixel by pixel. Vertices are chosen so that both see bit-identical clip coordinates.
#include <random>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "compute/baselines/graphics_baseline.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

class HardwareCoverage : public test::VulkanTest {};

constexpr uint32_t kSize = 128;

// Camera at the origin looking down -z, 90 degrees, square image: the projection is exactly
// x_clip = x, y_clip = -y, w = -z in float, so both pipelines get the same clip coordinates.
Scene camera_scene() {
  Scene s;
  s.camera.position = {0, 0, 0};
  s.camera.target = {0, 0, -1};
  s.camera.vertical_fov = glm::radians(90.0f);
  s.camera.near_plane = 0.1f;
  s.materials.push_back({});
  return s;
}

struct TriangleSet {
  std::vector<glm::vec2> ndc;  // 3 per triangle
  std::vector<float> w;        // 1 per triangle, with a short mantissa: x = ndc * w and x / w exact
};

// Overlapping random triangles of all sizes, each at its own depth. (Overlapping triangles at
// one depth would tie, and both pipelines interpolate a constant depth with rounding noise, so
// such ties are decided by that noise on both sides: docs/accuracy.md.)
TriangleSet random_triangles(uint32_t seed, int count, bool inside_viewport) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> coord(-83, 83);  // multiples of 1/64 in [-1.3, 1.3]
  TriangleSet set;
  for (int t = 0; t < count; ++t) {
    const float span = (t % 4 == 0) ? 1.0f : 0.15f;  // a quarter large, the rest small
    glm::vec2 centre(coord(rng) / 64.0f, coord(rng) / 64.0f);
    for (int k = 0; k < 3; ++k) {
      glm::vec2 p = centre + span * glm::vec2(coord(rng), coord(rng)) / 64.0f;
      if (inside_viewport) p = glm::clamp(p, -63.0f / 64.0f, 63.0f / 64.0f);
      set.ndc.push_back(p);
    }
    set.w.push_back(2.0f + float(t) / 16.0f);
  }
  return set;
}

// A grid of triangles whose vertices sit on pixel centres, so that many samples lie exactly on
// shared edges and the tie rule decides who owns them.
TriangleSet pixel_centre_grid() {
  TriangleSet set;
  auto ndc = [](int px, int py) {
    return glm::vec2((px + 0.5f) / kSize * 2.0f - 1.0f, (py + 0.5f) / kSize * 2.0f - 1.0f);
  };
  for (int gy = 0; gy < 8; ++gy) {
    for (int gx = 0; gx < 8; ++gx) {
      const int x0 = gx * 15 + 3, y0 = gy * 15 + 3, x1 = x0 + 15, y1 = y0 + 15;
      const int mx = x0 + (gx * 7 + gy * 3) % 15;  // a skewed split: edges of many slopes
      set.ndc.insert(set.ndc.end(), {ndc(x0, y0), ndc(x1, y0), ndc(mx, y1)});
      set.ndc.insert(set.ndc.end(), {ndc(x0, y0), ndc(mx, y1), ndc(x0, y1)});
      set.ndc.insert(set.ndc.end(), {ndc(x1, y0), ndc(x1, y1), ndc(mx, y1)});
      set.w.insert(set.w.end(), {4.0f, 4.0f, 4.0f});
    }
  }
  return set;
}

struct Comparison {
  size_t covered = 0;                      // pixels either pipeline covers
  size_t mismatches = 0;                   // pixels whose owner differs
  size_t mismatches_without_crossing = 0;  // ... where neither owner leaves the viewport
};

bool leaves_viewport(const TriangleSet& set, uint32_t id) {
  if (id == 0xFFFFFFFFu) return false;
  for (int k = 0; k < 3; ++k) {
    glm::vec2 n = set.ndc[id * 3 + k];
    if (std::abs(n.x) > 1.0f || std::abs(n.y) > 1.0f) return true;
  }
  return false;
}

Comparison compare(test::VulkanTest::Frame& frame, const std::vector<uint32_t>& hardware,
                   const TriangleSet& set) {
  Comparison c;
  for (size_t i = 0; i < hardware.size(); ++i) {
    const uint32_t compute =
        frame.visibility[i] == ~0ull ? 0xFFFFFFFFu : uint32_t(frame.visibility[i]);
    c.covered += compute != 0xFFFFFFFFu || hardware[i] != 0xFFFFFFFFu;
    if (compute != hardware[i]) {
      c.mismatches++;
      c.mismatches_without_crossing +=
          !leaves_viewport(set, compute) && !leaves_viewport(set, hardware[i]);
      if (c.mismatches <= 5)
        std::printf("  pixel (%zu, %zu): compute %d%s, hardware %d%s\n", i % kSize, i / kSize,
                    int(compute), leaves_viewport(set, compute) ? " (leaves viewport)" : "",
                    int(hardware[i]),
                    leaves_viewport(set, hardware[i]) ? " (leaves viewport)" : "");
    }
  }
  return c;
}

Comparison run(test::VulkanTest& fixture, Context& ctx, const TriangleSet& set,
               test::VulkanTest::Frame (test::VulkanTest::*render)(const Scene&, uint32_t, uint32_t,
                                                                   RendererOptions)) {
  Scene scene = camera_scene();
  const glm::mat4 proj = projection_matrix(scene.camera, 1.0f);
  Mesh mesh;
  std::vector<glm::vec4> clip;
  for (size_t t = 0; t < set.w.size(); ++t) {
    const float w = set.w[t];
    for (int k = 0; k < 3; ++k) {
      const glm::vec2 n = set.ndc[t * 3 + k];
      const glm::vec3 world(n.x * w, -n.y * w, -w);
      mesh.positions.push_back(world);
      mesh.normals.push_back({0, 0, 1});
      mesh.uvs.push_back({0, 0});
      mesh.indices.push_back(uint32_t(mesh.indices.size()));
      clip.push_back(proj * glm::vec4(world, 1.0f));
      EXPECT_EQ(clip.back().x, world.x);  // the exactness the comparison relies on
      EXPECT_EQ(clip.back().w, w);
    }
  }
  scene.meshes.push_back(mesh);
  scene.objects.push_back({});
  RendererOptions options;
  options.cull = CullMode::none;
  test::VulkanTest::Frame frame = (fixture.*render)(scene, kSize, kSize, options);
  return compare(frame, hardware_triangle_ids(ctx, clip, kSize, kSize), set);
}

TEST_F(HardwareCoverage, TrianglesInsideTheViewportMatchExactly) {
  for (uint32_t seed : {1u, 2u, 3u}) {
    Comparison c =
        run(*this, context(), random_triangles(seed, 200, true), &test::VulkanTest::render);
    std::printf("HARDWARE inside, seed %u: %zu pixels covered, %zu owners differ\n", seed,
                c.covered, c.mismatches);
    EXPECT_GT(c.covered, 5000u);
    EXPECT_EQ(c.mismatches, 0u);
  }
}

// lavapipe clips triangles that leave the viewport, in float, which moves their edges by a
// rounding error; the compute path keeps them whole (its guard band is +-32768 px). Differences
// must involve such a triangle, and stay rare.
TEST_F(HardwareCoverage, TrianglesLeavingTheViewportDifferOnlyWhereLavapipeClips) {
  size_t covered = 0, mismatches = 0;
  for (uint32_t seed : {1u, 2u, 3u}) {
    Comparison c =
        run(*this, context(), random_triangles(seed, 200, false), &test::VulkanTest::render);
    std::printf("HARDWARE crossing, seed %u: %zu pixels covered, %zu owners differ\n", seed,
                c.covered, c.mismatches);
    EXPECT_EQ(c.mismatches_without_crossing, 0u);
    covered += c.covered;
    mismatches += c.mismatches;
  }
  EXPECT_LE(double(mismatches), 0.002 * double(covered));  // measured: 21 of 46,236 (0.05 %)
}

TEST_F(HardwareCoverage, TieRuleOnEdgesThroughPixelCentresMatches) {
  Comparison c = run(*this, context(), pixel_centre_grid(), &test::VulkanTest::render);
  std::printf("HARDWARE pixel-centre grid: %zu pixels covered, %zu owners differ\n", c.covered,
              c.mismatches);
  EXPECT_GT(c.covered, 10000u);
  EXPECT_EQ(c.mismatches, 0u);
}

}  // namespace
}  // namespace tessera
