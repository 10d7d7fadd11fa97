// Near-plane and guard-band clipping: a triangle crossing the near plane covers exactly the
// pixels of its clipped polygon, computed here in double precision from the camera model.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "core/pick.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

class NearClip : public test::VulkanTest {};

constexpr uint32_t kW = 160, kH = 120;

// Camera at the origin looking down -z, so view space is world space.
Scene triangle_scene(glm::vec3 a, glm::vec3 b, glm::vec3 c) {
  Scene s;
  s.camera.position = {0, 0, 0};
  s.camera.target = {0, 0, -1};
  s.camera.vertical_fov = glm::radians(60.0f);
  s.camera.near_plane = 0.5f;
  // Wind the triangle counter-clockwise as seen from the camera (its front side).
  if (glm::dot(glm::cross(b - a, c - a), -a) < 0) std::swap(b, c);
  Mesh m;
  m.positions = {a, b, c};
  glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
  m.normals = {n, n, n};
  m.uvs = {{0, 0}, {1, 0}, {0, 1}};
  m.indices = {0, 1, 2};
  s.meshes.push_back(m);
  s.materials.push_back({});
  s.objects.push_back({});
  return s;
}

// The triangle clipped to z <= -near, projected to pixels (y down).
std::vector<glm::dvec2> expected_polygon(const Scene& s) {
  const Mesh& m = s.meshes[0];
  const double near = s.camera.near_plane;
  std::vector<glm::dvec3> poly;
  for (int i = 0; i < 3; ++i) {
    glm::dvec3 p(m.positions[i]), q(m.positions[(i + 1) % 3]);
    double dp = -p.z - near, dq = -q.z - near;  // >= 0: in front of the near plane
    if (dp >= 0) poly.push_back(p);
    if ((dp >= 0) != (dq >= 0)) poly.push_back(p + (q - p) * (dp / (dp - dq)));
  }
  const double t = std::tan(double(s.camera.vertical_fov) / 2);
  std::vector<glm::dvec2> px;
  for (glm::dvec3 p : poly) {
    double ndc_x = p.x / (-p.z * t * double(kW) / kH);
    double ndc_y = -p.y / (-p.z * t);
    px.push_back({(ndc_x + 1) / 2 * kW, (ndc_y + 1) / 2 * kH});
  }
  return px;
}

// Smallest signed distance (pixels) from `p` to the polygon's edges; > 0 inside.
double inside_margin(const std::vector<glm::dvec2>& poly, glm::dvec2 p) {
  double area = 0;
  for (size_t i = 0; i < poly.size(); ++i) {
    glm::dvec2 a = poly[i], b = poly[(i + 1) % poly.size()];
    area += a.x * b.y - a.y * b.x;
  }
  double margin = 1e300;
  for (size_t i = 0; i < poly.size(); ++i) {
    glm::dvec2 a = poly[i], b = poly[(i + 1) % poly.size()];
    glm::dvec2 e = b - a;
    double cross = e.x * (p.y - a.y) - e.y * (p.x - a.x);
    margin = std::min(margin, (area > 0 ? cross : -cross) / glm::length(e));
  }
  return margin;
}

void expect_coverage_matches(const std::vector<glm::dvec2>& poly, const std::vector<uint64_t>& vis,
                             size_t& covered) {
  covered = 0;
  for (uint32_t y = 0; y < kH; ++y) {
    for (uint32_t x = 0; x < kW; ++x) {
      double m = inside_margin(poly, {x + 0.5, y + 0.5});
      bool hit = vis[size_t(y) * kW + x] != ~0ull;
      covered += hit;
      if (m > 0.01) {
        ASSERT_TRUE(hit) << "pixel " << x << "," << y << " should be covered";
      }
      if (m < -0.01) {
        ASSERT_FALSE(hit) << "pixel " << x << "," << y << " should be empty";
      }
    }
  }
}

TEST_F(NearClip, TriangleWithOneVertexBehindTheCameraCoversItsClippedPolygon) {
  Scene s = triangle_scene({-2.0f, -1.5f, -4.0f}, {2.5f, -1.0f, -3.0f}, {0.3f, 0.8f, 1.5f});
  Frame f = render(s, kW, kH);
  EXPECT_EQ(f.stats.clipped, 1u);
  size_t covered = 0;
  expect_coverage_matches(expected_polygon(s), f.visibility, covered);
  EXPECT_GT(covered, 2000u);
}

TEST_F(NearClip, TriangleWithTwoVerticesBehindTheNearPlane) {
  Scene s = triangle_scene({-0.4f, -0.3f, -2.0f}, {3.0f, -2.0f, 0.2f}, {-1.0f, 3.0f, -0.3f});
  Frame f = render(s, kW, kH);
  EXPECT_EQ(f.stats.clipped, 1u);
  size_t covered = 0;
  expect_coverage_matches(expected_polygon(s), f.visibility, covered);
  EXPECT_GT(covered, 500u);
}

// A vertex just in front of the near plane projects thousands of pixels off screen: the guard
// band clips it, and what is on screen is unchanged.
TEST_F(NearClip, VertexNearTheNearPlaneIsClippedByTheGuardBand) {
  Scene s = triangle_scene({-1.0f, -1.0f, -3.0f}, {1.0f, -0.8f, -3.0f}, {400.0f, 300.0f, -0.5001f});
  Frame f = render(s, kW, kH);
  EXPECT_EQ(f.stats.clipped, 1u);
  size_t covered = 0;
  expect_coverage_matches(expected_polygon(s), f.visibility, covered);
  EXPECT_GT(covered, 100u);
}

TEST_F(NearClip, TriangleEntirelyBehindTheCameraDrawsNothing) {
  Scene s = triangle_scene({-1.0f, -1.0f, 2.0f}, {1.0f, -1.0f, 2.0f}, {0.0f, 1.0f, 0.3f});
  Frame f = render(s, kW, kH);
  EXPECT_EQ(f.stats.culled_frustum, 1u);
  EXPECT_EQ(f.stats.raster_triangles, 0u);
  for (uint64_t v : f.visibility) ASSERT_EQ(v, ~0ull);
}

// Extreme depth ratios (issue 12, where methods fail): the same triangles scaled up by `scale`
// with the near plane at `near`, far / near up to 1e11. Clipping happens in homogeneous clip
// space in fp32, whose error is relative, so the clipped polygon stays exact to the snapping.
TEST_F(NearClip, ExtremeDepthRatiosClipExactly) {
  Renderer renderer(context());
  FrameSettings fs;
  fs.width = kW;
  fs.height = kH;
  for (auto [near, scale] :
       {std::pair{1e-6f, 1e5f}, std::pair{1e-3f, 1e3f}, std::pair{1e2f, 1e7f}}) {
    SCOPED_TRACE("near " + std::to_string(near) + ", scale " + std::to_string(scale));
    Scene s =
        triangle_scene(glm::vec3{-2.0f, -1.5f, -4.0f} * scale,
                       glm::vec3{2.5f, -1.0f, -3.0f} * scale, glm::vec3{0.3f, 0.8f, 1.5f} * scale);
    s.camera.near_plane = near;
    renderer.set_scene(s);
    EXPECT_EQ(renderer.render(fs).clipped, 1u);
    size_t covered = 0;
    expect_coverage_matches(expected_polygon(s), renderer.read_visibility(), covered);
    EXPECT_GT(covered, 2000u);
  }
}

// A square at depth d * (1 - gap) in front of a larger one at depth d. The visibility key's
// depth is near / w in fp32 (24-bit significand, relative step 2^-24 = 6e-8 whatever near and
// d are), interpolated per pixel, so the order of two surfaces depends on their relative gap
// alone, not on far / near. Documented bound (docs/tradeoffs.md): gaps of 1e-5 order exactly
// at far / near from 1e-2 to 1e11; the smallest gap that still orders is printed.
Scene two_squares(float near, float depth, float gap) {
  Scene s;
  s.camera.position = {0, 0, 0};
  s.camera.target = {0, 0, -1};
  s.camera.vertical_fov = glm::radians(60.0f);
  s.camera.near_plane = near;
  Mesh m;  // the unit square at z = 0, facing +z
  m.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  m.normals.assign(4, {0, 0, 1});
  m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  m.indices = {0, 1, 2, 0, 2, 3};
  s.meshes.push_back(m);
  s.materials.resize(2);
  s.materials[1].base_color = {1, 0, 0};
  const float far_half = depth, near_depth = depth * (1.0f - gap);
  // Object 0: the far square, twice the view; object 1: the near one, a quarter of the view's
  // height on each side of the centre.
  s.objects.push_back({0, 0,
                       glm::scale(glm::translate(glm::mat4(1), {0, 0, -depth}),
                                  glm::vec3(far_half * 2, far_half * 2, 1))});
  const float half = near_depth * std::tan(glm::radians(30.0f)) * 0.5f;
  s.objects.push_back(
      {0, 1,
       glm::scale(glm::translate(glm::mat4(1), {0, 0, -near_depth}), glm::vec3(half, half, 1))});
  return s;
}

// Pixels whose owner is not the expected square (the near one inside its projection, which
// spans the middle half of the image's height, by more than a margin; the far one outside).
size_t misordered_pixels(const Scene& s, const std::vector<uint64_t>& vis) {
  const ObjectNumbering numbering = number_objects(s);
  size_t wrong = 0;
  for (uint32_t y = 0; y < kH; ++y) {
    for (uint32_t x = 0; x < kW; ++x) {
      const double dx = std::abs(x + 0.5 - kW / 2.0), dy = std::abs(y + 0.5 - kH / 2.0);
      const double half = kH / 4.0;  // the near square's half side in pixels
      const std::optional<uint32_t> o = pick_object(numbering, vis[size_t(y) * kW + x]);
      if (dx < half - 0.01 && dy < half - 0.01) {
        wrong += o != 1u;
      } else if (dx > half + 0.01 || dy > half + 0.01) {
        wrong += o != 0u;
      }
    }
  }
  return wrong;
}

TEST_F(NearClip, DepthOrderHoldsAtExtremeDepthRatios) {
  Renderer renderer(context());
  FrameSettings fs;
  fs.width = kW;
  fs.height = kH;
  auto misordered = [&](const Scene& s) {
    renderer.set_scene(s);
    renderer.render(fs);
    return misordered_pixels(s, renderer.read_visibility());
  };
  for (auto [near, depth] : {std::pair{1e-6f, 1e5f}, std::pair{1e-3f, 1.0f}, std::pair{1e2f, 1e7f},
                             std::pair{0.5f, 0.6f}}) {
    SCOPED_TRACE("near " + std::to_string(near) + ", depth " + std::to_string(depth));
    EXPECT_EQ(misordered(two_squares(near, depth, 1e-5f)), 0u);
    float smallest = 1e-5f;
    for (float gap : {3e-6f, 1e-6f, 3e-7f, 1e-7f}) {
      if (misordered(two_squares(near, depth, gap)) != 0) break;
      smallest = gap;
    }
    std::printf("DEPTH_ORDER near %g depth %g (far/near %.0e): ordered down to a gap of %.0e\n",
                near, depth, depth / near, smallest);
  }
}

}  // namespace
}  // namespace tessera
