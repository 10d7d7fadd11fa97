// Huge triangles: edges shared by two triangles whose corners lie far outside the image are
// clipped against the near plane and the guard band by each triangle separately, walking the
// edge in opposite directions. Both must get the same clipped vertices bit for bit, or samples
// along the edge are covered twice or missed. Every scene here covers each pixel of the image
// exactly once (or, for closed meshes, as often by front faces as by back faces), which
// follows from the geometry alone: the expected values need no renderer.
#include <cmath>
#include <map>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "core/mesh.h"
#include "core/reference_renderer.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

class HugeTriangles : public test::VulkanTest {
 protected:
  // Samples covered per pixel, for each of the compute path's raster paths and the reference.
  struct Coverage {
    std::string path;
    std::vector<uint32_t> counts;
  };
  std::vector<Coverage> coverage(const Scene& scene, CullMode cull = CullMode::none) {
    std::vector<Coverage> out;
    // The per-triangle path is left out: one thread walking a box of the whole image is not
    // what it is for (it stops short of 2^16 pixels on lavapipe; see the lead's notes).
    const std::pair<const char*, uint32_t> paths[] = {
        {"default split", RendererOptions{}.small_triangle_max_area}, {"all per-tile", 0u}};
    for (const auto& [name, small] : paths) {
      // One renderer per path and culling mode, kept for the test's scenes.
      std::unique_ptr<Renderer>& renderer = renderers_[{small, cull}];
      if (!renderer) {
        RendererOptions o;
        o.debug_coverage = true;
        o.cull = cull;
        o.small_triangle_max_area = small;
        renderer = std::make_unique<Renderer>(context(), o);
      }
      out.push_back({name, render(*renderer, scene, kSide, kSide, 1, true).coverage});
    }
    ReferenceSettings rs;
    rs.frame.width = rs.frame.height = kSide;
    rs.cull = cull;
    out.push_back({"reference", render_reference(scene, rs).coverage});
    return out;
  }
  static constexpr uint32_t kSide = 256;
  void TearDown() override {
    renderers_.clear();  // before the fixture checks that the device is destroyed cleanly
    VulkanTest::TearDown();
  }

 private:
  std::map<std::pair<uint32_t, CullMode>, std::unique_ptr<Renderer>> renderers_;
};

// Pixels covered twice or more and pixels not covered, and the first of them (x + y * 256).
struct Faults {
  size_t doubled = 0, missed = 0;
  size_t first = 0;
};
Faults faults(const std::vector<uint32_t>& counts) {
  Faults f;
  for (size_t i = counts.size(); i-- > 0;) {
    f.doubled += counts[i] > 1;
    f.missed += counts[i] == 0;
    if (counts[i] != 1) f.first = i;
  }
  return f;
}
std::ostream& operator<<(std::ostream& os, const Faults& f) {
  return os << f.doubled << " doubled, " << f.missed << " missed, first at " << f.first % 256 << ","
            << f.first / 256;
}

// Camera at the origin looking down -z (view space is world space), 60 degrees, near 0.1.
Scene view_space_scene(Mesh mesh) {
  Scene s;
  s.camera.position = {0.0f, 0.0f, 0.0f};
  s.camera.target = {0.0f, 0.0f, -1.0f};
  s.camera.vertical_fov = glm::radians(60.0f);
  s.camera.near_plane = 0.1f;
  mesh.normals.assign(mesh.positions.size(), glm::vec3(0.0f, 0.0f, 1.0f));
  mesh.uvs.assign(mesh.positions.size(), glm::vec2(0.0f));
  s.meshes.push_back(std::move(mesh));
  s.materials.push_back({});
  s.objects.push_back({});
  return s;
}

// World units per pixel at depth 1 (256 px over 2 tan 30 degrees).
const double kUnitsPerPixel = std::tan(glm::radians(30.0)) / 128.0;

// The point (x, y) of the plane z = -1, rotated by `angle` about the view axis.
glm::vec3 at_depth_one(double x, double y, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return glm::vec3(float(c * x - s * y), float(s * x + c * y), -1.0f);
}

// The issue's quad: triangles (A, B, C) and (A, C, D) sharing the diagonal A-C, which passes
// 0.013 units off the image centre, corners about `pixels` pixels beyond the image. Rotated
// by `angle`, the diagonal crosses other sides of the guard band.
Mesh issue_quad(double pixels, double angle) {
  const double x = pixels * kUnitsPerPixel;
  Mesh m;
  m.positions = {at_depth_one(-x, -0.7 * x, angle), at_depth_one(x, -3.0 * x, angle),
                 at_depth_one(x, 0.7 * x + 0.013, angle), at_depth_one(-x, 3.0 * x, angle)};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

// A convex polygon of `n` corners on a circle of `pixels` pixels around the image centre,
// triangulated as a fan from corner 0: every shared edge runs from a far corner to another.
Mesh far_fan(double pixels, uint32_t n, double angle) {
  Mesh m;
  for (uint32_t k = 0; k < n; ++k) {
    const double a = angle + 2.0 * glm::pi<double>() * k / n;
    m.positions.push_back(at_depth_one(pixels * kUnitsPerPixel * std::cos(a),
                                       pixels * kUnitsPerPixel * std::sin(a), 0.0));
  }
  for (uint32_t k = 1; k + 1 < n; ++k) m.indices.insert(m.indices.end(), {0, k, k + 1});
  return m;
}

// The same polygon as a fan around a vertex near the image centre: every shared edge runs from
// inside the image to a far corner.
Mesh centred_fan(double pixels, uint32_t n, double angle) {
  Mesh m = far_fan(pixels, n, angle);
  m.positions.push_back(at_depth_one(0.37 * kUnitsPerPixel, -0.21 * kUnitsPerPixel, 0.0));
  m.indices.clear();
  for (uint32_t k = 0; k < n; ++k) m.indices.insert(m.indices.end(), {n, k, (k + 1) % n});
  return m;
}

// Corner distances in pixels beyond the image: the issue's 10^7 and 10^6, and up to the limit
// stated in docs/architecture.md.
constexpr double kDistances[] = {1e6, 1e7, 1e10};
// Angles that make the shared edges cross the left and right sides of the guard band (0), the
// top and bottom (pi / 2), and corners.
constexpr double kAngles[] = {0.0, 1.5707963267948966, 2.33};

TEST_F(HugeTriangles, QuadsCoverEveryPixelOnce) {
  for (double d : kDistances) {
    for (double angle : kAngles) {
      for (const Coverage& c : coverage(view_space_scene(issue_quad(d, angle)))) {
        const Faults f = faults(c.counts);
        EXPECT_TRUE(f.doubled == 0 && f.missed == 0)
            << c.path << ", corners " << d << " px, angle " << angle << ": " << f;
      }
    }
  }
}

TEST_F(HugeTriangles, FansCoverEveryPixelOnce) {
  for (double d : kDistances) {
    for (double angle : {0.0, 1.1}) {
      for (const Mesh& mesh : {far_fan(d, 9, angle), centred_fan(d, 7, angle)}) {
        for (const Coverage& c : coverage(view_space_scene(mesh))) {
          const Faults f = faults(c.counts);
          EXPECT_TRUE(f.doubled == 0 && f.missed == 0)
              << c.path << ", corners " << d << " px, angle " << angle << ": " << f;
        }
      }
    }
  }
}

// A plane through the view that reaches behind the camera: z = -1 - u in its own axes (u, v),
// rotated by `angle` about the view axis. Every pixel's ray meets it at a depth between 0.55
// and 5.5 (|u| along a ray is at most tan 30 deg * (|cos| + |sin|) * depth <= 0.82 depth), so
// in front of the near plane, at |u|, |v| < 5; its near-plane crossing, u = -0.9, lies 1,800 px
// or more outside the image. The quad is split along a diagonal through (0.3, 0.1) that
// crosses the near plane and reaches `far` units ahead.
Mesh plane_through_near(double far, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  auto point = [&](double u, double v) {
    return glm::vec3(float(c * u - s * v), float(s * u + c * v), float(-1.0 - u));
  };
  const double behind = -50.0;  // u: 49 units behind the camera
  const double slope = 0.7;
  const double v_behind = 0.1 + slope * (behind - 0.3), v_far = 0.1 + slope * (far - 0.3);
  const double wide = 3.0 * (std::abs(v_far) + 100.0);
  Mesh m;
  m.positions = {point(behind, v_behind), point(far, -wide), point(far, v_far),
                 point(behind, wide)};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

TEST_F(HugeTriangles, QuadsCrossingTheNearPlaneCoverEveryPixelOnce) {
  for (double far : {1e2, 1e6}) {
    for (double angle : kAngles) {
      for (const Coverage& c : coverage(view_space_scene(plane_through_near(far, angle)))) {
        const Faults f = faults(c.counts);
        EXPECT_TRUE(f.doubled == 0 && f.missed == 0)
            << c.path << ", far " << far << ", angle " << angle << ": " << f;
      }
    }
  }
}

// Closed meshes whose vertices lie far outside the image, in front of the camera: a box and a
// flattened icosphere that cover the whole image. Each pixel's ray enters and leaves once:
// front faces (culling back faces) and back faces (culling front faces) each cover it once.
TEST_F(HugeTriangles, ClosedMeshesFarOutsideAreWatertight) {
  for (double d : {1e7, 1e10}) {
    const float x = float(d * kUnitsPerPixel * 3.0);  // at depth 3
    const glm::mat4 place = glm::translate(glm::mat4(1.0f), {0.0f, 0.0f, -3.0f});
    const std::pair<const char*, Mesh> meshes[] = {{"box", make_cube()},
                                                   {"icosphere", make_icosphere(2)}};
    for (const auto& [name, mesh] : meshes) {
      for (float turn : {0.0f, 0.4f}) {
        Scene scene = view_space_scene(mesh);
        scene.meshes[0].normals = mesh.normals;
        scene.objects[0].transform =
            glm::scale(glm::rotate(place, turn, {0.0f, 0.0f, 1.0f}), {x, x, 0.9f});
        const std::vector<Coverage> front = coverage(scene, CullMode::back);
        const std::vector<Coverage> back = coverage(scene, CullMode::front);
        for (size_t p = 0; p < front.size(); ++p) {
          const std::string what = front[p].path + ", " + name + ", " + std::to_string(d) +
                                   " px, turn " + std::to_string(turn);
          EXPECT_EQ(front[p].counts, back[p].counts) << what;
          const Faults f = faults(front[p].counts);
          EXPECT_TRUE(f.doubled == 0 && f.missed == 0) << what << ": " << f;
        }
      }
    }
  }
}

}  // namespace
}  // namespace tessera
