// The reference renderer on its own: values computed by hand, coverage rules, thread counts.
#include <cmath>
#include <cstring>
#include <numbers>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "core/builtin_scenes.h"
#include "core/check.h"
#include "core/mesh.h"
#include "core/reference_renderer.h"

namespace tessera {
namespace {

// A plane facing the camera, lit head-on by a directional light.
Scene facing_plane(float roughness, float metallic) {
  Scene s;
  s.camera.position = {0.0f, 0.0f, 3.0f};
  s.camera.vertical_fov = glm::radians(40.0f);
  s.meshes.push_back(make_plane(2, 2));
  s.materials.push_back({glm::vec3(0.6f, 0.3f, 0.2f), metallic, roughness});
  s.objects.push_back({0, 0, glm::mat4(1.0f)});
  Light sun;
  sun.kind = LightKind::directional;
  sun.direction = {0.0f, 0.0f, -1.0f};
  sun.intensity = 2.0f;
  s.lights.push_back(sun);
  s.ambient = glm::vec3(0.05f);
  return s;
}

TEST(Reference, HeadOnPlaneMatchesTheFormulaByHand) {
  // With N = V = L = H: D = 1 / (pi alpha^2), G = 1, F = F0; the centre pixel of an odd-sized
  // image looks straight down the axis.
  for (float roughness : {0.3f, 0.8f}) {
    for (float metallic : {0.0f, 1.0f}) {
      Scene s = facing_plane(roughness, metallic);
      ReferenceSettings rs;
      rs.frame.width = rs.frame.height = 101;
      ReferenceFrame f = render_reference(s, rs);
      const double pi = std::numbers::pi;
      const double alpha = double(roughness) * roughness;
      const glm::dvec3 base(s.materials[0].base_color);
      for (int c = 0; c < 3; ++c) {
        const double f0 = 0.04 * (1 - metallic) + base[c] * metallic;
        const double specular = (1 / (pi * alpha * alpha)) * f0 / 4;
        const double diffuse = (1 - f0) * (1 - metallic) * base[c] / pi;
        const double expected = (diffuse + specular) * 2.0 + 0.05 * base[c];
        EXPECT_NEAR(f.hdr.at(50, 50)[c], expected, 1e-5 * expected)
            << "roughness " << roughness << " metallic " << metallic << " channel " << c;
      }
    }
  }
}

TEST(Reference, ToneCurveAndEncodingByHand) {
  Scene s = facing_plane(0.5f, 0.0f);
  s.camera.vertical_fov = glm::radians(90.0f);  // the plane covers the middle third only
  ReferenceSettings rs;
  rs.frame.width = rs.frame.height = 11;
  rs.frame.tonemap = ToneMap::reinhard;
  rs.frame.exposure_ev = 1.0f;
  ReferenceFrame f = render_reference(s, rs);
  const double x = 2.0 * f.hdr.at(5, 5).r;  // one stop up
  const double mapped = x / (1 + x);
  const double encoded =
      mapped <= 0.0031308 ? 12.92 * mapped : 1.055 * std::pow(mapped, 1 / 2.4) - 0.055;
  EXPECT_EQ(f.ldr.at(5, 5).r, uint8_t(std::floor(encoded * 255 + 0.5)));
  // The background keeps its colour in HDR.
  EXPECT_EQ(f.hdr.at(0, 0), glm::vec4(s.background, 1.0f));
}

TEST(Reference, ThreadCountDoesNotChangeABit) {
  Scene s = make_sphere_grid_scene();
  ReferenceSettings rs;
  rs.frame.width = 128;
  rs.frame.height = 96;
  rs.threads = 1;
  ReferenceFrame one = render_reference(s, rs);
  rs.threads = 5;
  ReferenceFrame five = render_reference(s, rs);
  EXPECT_EQ(one.owner, five.owner);
  EXPECT_EQ(one.depth, five.depth);
  EXPECT_EQ(one.ldr.pixels, five.ldr.pixels);
  EXPECT_EQ(0,
            std::memcmp(one.hdr.pixels.data(), five.hdr.pixels.data(), one.hdr.pixels.size() * 16));
}

TEST(Reference, SharedEdgesAreCoveredOnce) {
  Scene s = facing_plane(0.5f, 0.0f);
  s.meshes[0] = make_plane(13, 7);
  ReferenceSettings rs;
  rs.frame.width = 120;
  rs.frame.height = 90;
  ReferenceFrame f = render_reference(s, rs);
  size_t covered = 0;
  for (uint32_t c : f.coverage) {
    ASSERT_LE(c, 1u);
    covered += c;
  }
  EXPECT_GT(covered, 1000u);
}

TEST(Reference, ProbeMeasuresEdgeDistanceAndDepth) {
  Scene s = facing_plane(0.5f, 0.0f);
  s.meshes[0] = make_plane(1, 1);  // triangle 0: (-1,-1), (1,-1), (1,1): the part with y < x
  ReferenceSettings rs;
  rs.frame.width = rs.frame.height = 101;
  // Pixel (60, 70) sees the plane z = 0 at world (x, y); its nearest edge is the diagonal.
  const double pixel_size = 3.0 * std::tan(double(s.camera.vertical_fov) / 2) / 50.5;
  const double x = (60.5 - 50.5) * pixel_size, y = -(70.5 - 50.5) * pixel_size;
  const ReferenceProbe p = probe_reference(s, rs, 0, 60, 70);
  EXPECT_NEAR(p.edge_distance_px, (x - y) / std::sqrt(2.0) / pixel_size, 1e-9);
  // The plane is perpendicular to the view axis: w = 3 everywhere on it.
  EXPECT_NEAR(p.depth, double(s.camera.near_plane) / 3.0, 1e-15);
}

TEST(Reference, RejectsBadInput) {
  Scene s = facing_plane(0.5f, 0.0f);
  ReferenceSettings rs;
  rs.frame.width = 0;
  EXPECT_THROW(render_reference(s, rs), Error);
  rs.frame.width = 16;
  s.meshes[0].positions[0].x = std::nanf("");
  EXPECT_THROW(render_reference(s, rs), Error);
}

}  // namespace
}  // namespace tessera
