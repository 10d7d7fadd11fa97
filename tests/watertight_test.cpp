// Watertightness: shared edges are covered exactly once (top-left rule), closed meshes have no
// holes, on both rasterizer paths. Expected coverage comes from the analytic shapes.
#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "core/mesh.h"
#include "core/reference_renderer.h"
#include "tests/test_scenes.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

class Watertight : public test::VulkanTest {};

RendererOptions paths[] = {
    [] {
      RendererOptions o;
      o.debug_coverage = true;
      return o;
    }(),
    [] {
      RendererOptions o;
      o.debug_coverage = true;
      o.small_triangle_max_area = 1u << 30;
      return o;
    }(),
    [] {
      RendererOptions o;
      o.debug_coverage = true;
      o.small_triangle_max_area = 0;
      return o;
    }(),
};
const char* path_names[] = {"default split", "all per-triangle", "all per-tile"};

Scene single_object_scene(Mesh mesh, glm::mat4 transform) {
  Scene s;
  s.camera.position = {0.0f, 0.0f, 3.0f};
  s.camera.target = {0.0f, 0.0f, 0.0f};
  s.camera.vertical_fov = glm::radians(50.0f);
  s.background = {0.0f, 0.0f, 1.0f};
  s.meshes.push_back(std::move(mesh));
  s.materials.push_back({});
  s.objects.push_back({0, 0, transform});
  s.lights.push_back({});
  s.lights[0].position = {0.0f, 2.0f, 4.0f};
  return s;
}

// Angle between the view axis and the ray through the centre of pixel (x, y).
double pixel_angle(const Camera& c, uint32_t x, uint32_t y, uint32_t w, uint32_t h) {
  double t = std::tan(double(c.vertical_fov) / 2);
  double nx = ((x + 0.5) / w * 2 - 1) * t * double(w) / h;
  double ny = ((y + 0.5) / h * 2 - 1) * t;
  return std::atan(std::sqrt(nx * nx + ny * ny));
}

TEST_F(Watertight, ClosedSphereHasNoHolesAndNoDoubleCoverage) {
  const uint32_t w = 200, h = 160;
  // Level 4 icosphere: every face lies farther than 0.995 from the centre (edge ~0.075 rad)
  // and within the unit sphere, so its silhouette lies between the two circles below.
  Scene scene = single_object_scene(make_icosphere(4), glm::mat4(1.0f));
  const double inner = std::asin(0.99 / 3.0), outer = std::asin(1.0 / 3.0);
  for (size_t p = 0; p < std::size(paths); ++p) {
    Frame f = render(scene, w, h, paths[p]);
    size_t inside = 0;
    for (uint32_t y = 0; y < h; ++y) {
      for (uint32_t x = 0; x < w; ++x) {
        uint32_t hits = f.coverage[size_t(y) * w + x];
        double a = pixel_angle(scene.camera, x, y, w, h);
        ASSERT_LE(hits, 1u) << path_names[p] << ": pixel " << x << "," << y << " covered twice";
        if (a < inner) {
          ++inside;
          ASSERT_EQ(hits, 1u) << path_names[p] << ": hole at " << x << "," << y;
        }
        if (a > outer) {
          ASSERT_EQ(hits, 0u) << path_names[p] << ": stray pixel at " << x << "," << y;
        }
      }
    }
    EXPECT_GT(inside, 5000u);
  }
}

// A plane split into many triangles whose inner vertices are jittered, so shared edges run at
// arbitrary slopes; seen head-on, it must cover its screen rectangle exactly once.
TEST_F(Watertight, JitteredPlaneCoversItsRectangleExactlyOnce) {
  const uint32_t nx = 37, ny = 23, w = 256, h = 192;
  Mesh plane = make_plane(nx, ny);
  std::mt19937 rng(99);
  std::uniform_real_distribution<float> jitter(-0.24f, 0.24f);
  for (uint32_t y = 1; y < ny; ++y) {
    for (uint32_t x = 1; x < nx; ++x) {
      glm::vec3& p = plane.positions[y * (nx + 1) + x];
      p.x += jitter(rng) * 2.0f / nx;
      p.y += jitter(rng) * 2.0f / ny;
    }
  }
  const float sx = 1.3f, sy = 0.9f;
  Scene scene = single_object_scene(plane, glm::scale(glm::mat4(1.0f), glm::vec3(sx, sy, 1.0f)));
  // The rectangle's corners in pixels: x = (X / (3 tan(fov/2) aspect) + 1) / 2 * w.
  const double t = std::tan(double(scene.camera.vertical_fov) / 2) * 3.0;
  const double x0 = (-sx / (t * w / h) + 1) / 2 * w, x1 = (sx / (t * w / h) + 1) / 2 * w;
  const double y0 = (-sy / t + 1) / 2 * h, y1 = (sy / t + 1) / 2 * h;
  for (size_t p = 0; p < std::size(paths); ++p) {
    Frame f = render(scene, w, h, paths[p]);
    for (uint32_t y = 0; y < h; ++y) {
      for (uint32_t x = 0; x < w; ++x) {
        const double cx = x + 0.5, cy = y + 0.5;
        const double margin = std::min({cx - x0, x1 - cx, cy - y0, y1 - cy});
        const uint32_t hits = f.coverage[size_t(y) * w + x];
        if (margin > 0.01) {
          ASSERT_EQ(hits, 1u) << path_names[p] << ": pixel " << x << "," << y;
        }
        if (margin < -0.01) {
          ASSERT_EQ(hits, 0u) << path_names[p] << ": pixel " << x << "," << y;
        }
      }
    }
  }
}

// Pixel centres exactly on shared edges: a plane whose vertices land on pixel centres.
TEST_F(Watertight, EdgesThroughPixelCentresAreOwnedOnce) {
  const uint32_t w = 64, h = 64;
  Scene scene = single_object_scene(make_plane(8, 8), glm::mat4(1.0f));
  // Choose the field of view so that x = +-1 at distance 3 maps to pixel centres 8.5 and 55.5.
  scene.camera.vertical_fov = float(2.0 * std::atan(1.0 / 3.0 * 32.0 / 23.5));
  for (size_t p = 0; p < std::size(paths); ++p) {
    Frame f = render(scene, w, h, paths[p]);
    for (uint32_t y = 0; y < h; ++y) {
      for (uint32_t x = 0; x < w; ++x) {
        ASSERT_LE(f.coverage[size_t(y) * w + x], 1u) << path_names[p] << ": " << x << "," << y;
        if (x > 8 && x < 55 && y > 8 && y < 55) {
          ASSERT_EQ(f.coverage[size_t(y) * w + x], 1u) << path_names[p] << ": " << x << "," << y;
        }
      }
    }
  }
}

}  // namespace
}  // namespace tessera

namespace tessera {
namespace {

// A ray enters a closed surface as often as it leaves it: per pixel, the samples covered by
// front faces equal those covered by back faces. A hole or a doubly covered sample on a shared
// edge breaks the equality. Random non-convex closed meshes, random poses, both renderers.
class WatertightRandom : public test::VulkanTest, public ::testing::WithParamInterface<uint32_t> {};

TEST_P(WatertightRandom, FrontAndBackCoverageAgreeOnEveryPixel) {
  const uint32_t seed = GetParam();
  const uint32_t w = 160, h = 120;
  Scene scene = single_object_scene(test::bumpy_sphere(3, 0.3f, seed), glm::mat4(1.0f));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  glm::mat4 t = glm::translate(glm::mat4(1.0f), {u(rng) * 0.3f, u(rng) * 0.3f, u(rng) * 0.3f});
  t = glm::rotate(t, u(rng) * 3.0f, glm::normalize(glm::vec3(u(rng), u(rng), 1.0f)));
  scene.objects[0].transform = glm::scale(t, {1.0f + 0.3f * u(rng), 1.0f + 0.3f * u(rng), 1.0f});
  size_t inside = 0;
  for (size_t p = 0; p < std::size(paths); ++p) {
    RendererOptions front = paths[p], back = paths[p];
    front.cull = CullMode::back;
    back.cull = CullMode::front;
    Frame f = render(scene, w, h, front);
    Frame b = render(scene, w, h, back);
    for (size_t i = 0; i < f.coverage.size(); ++i) {
      ASSERT_EQ(f.coverage[i], b.coverage[i])
          << path_names[p] << ": pixel " << i % w << "," << i / w;
      inside += f.coverage[i] > 0;
    }
  }
  EXPECT_GT(inside, 3000u);
  ReferenceSettings rs;
  rs.frame.width = w;
  rs.frame.height = h;
  rs.cull = CullMode::back;
  ReferenceFrame rf = render_reference(scene, rs);
  rs.cull = CullMode::front;
  ReferenceFrame rb = render_reference(scene, rs);
  EXPECT_EQ(rf.coverage, rb.coverage) << "reference";
}

INSTANTIATE_TEST_SUITE_P(Seeds, WatertightRandom, ::testing::Values(11u, 12u, 13u, 14u, 15u, 16u));

}  // namespace
}  // namespace tessera
