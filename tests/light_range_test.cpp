// Light arithmetic at the ends of the accepted ranges (docs/shading.md, "Accepted ranges"):
// far and strong lights, ranges, classic falloff, spot cones, directional irradiance and the
// normalisation of directions. Every expected value is derived here by hand: a plane lit and
// seen head-on reflects f E with f = ((1 - 0.04) c + 0.04 / 4) / pi (below), so the GPU and the
// reference are each compared with the formula, not with each other.
#include <cmath>
#include <functional>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "core/check.h"
#include "core/mesh.h"
#include "core/reference_renderer.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr uint32_t kSize = 33;  // odd: the centre pixel's ray is the camera's axis

// The classic BRDF of a rough (alpha = 1) dielectric of base colour c with L = V = N: Lambert
// weighted by 1 - F with F = F0 = 0.04 at V.H = 1, plus GGX D = 1 / pi times the folded
// Schlick-GGX visibility 1 / (4 (N.V (1 - k) + k)(N.L (1 - k) + k)) = 1/4 at N.V = N.L = 1.
double head_on_brdf(double c) {
  return ((1.0 - 0.04) * c + 0.04 * 0.25) / kPi;
}

// A 2 x 2 m plane of base colour `c`, roughness 1, at z = 0, seen from (0, 0, 3).
Scene lit_plane(const Light& light, float c = 0.8f) {
  Scene scene;
  scene.camera.position = {0.0f, 0.0f, 3.0f};
  scene.camera.vertical_fov = 0.5f;
  scene.meshes.push_back(make_plane(1, 1));
  scene.materials.push_back({glm::vec3(c), 0.0f, 1.0f});
  scene.objects.push_back({0, 0, glm::mat4(1.0f)});
  scene.lights.push_back(light);
  return scene;
}

Light point_at(float z, float intensity) {
  Light l;
  l.position = {0.0f, 0.0f, z};
  l.intensity = intensity;
  return l;
}

struct Case {
  std::string name;
  Light light;
  double irradiance;  // at the plane's centre, W/m^2, by hand
  float exposure_ev = 0.0f;
};

std::vector<Case> cases() {
  std::vector<Case> out;
  // Issue 15, fault 2: I / d^2 = 2.5e19 / (5e9)^2 = 1 W/m^2; the range fade's d^4 overflowed.
  out.push_back({"far_point_no_range", point_at(5e9f, 2.5e19f), 1.0});
  out.push_back({"point_2e9", point_at(2e9f, 4e18f), 1.0});
  // The farthest and strongest light accepted: 1e26 / (1e15)^2 = 1e-4 W/m^2.
  out.push_back(
      {"point_at_max_coordinate", point_at(kMaxSceneCoordinate, kMaxLightIntensity), 1e-4, 12.0f});
  // Closer than 1 cm: the squared distance is floored at 1e-4 m^2.
  out.push_back({"point_closer_than_floor", point_at(5e-4f, 1e-4f), 1.0});
  out.push_back({"point_zero_intensity", point_at(2.0f, 0.0f), 0.0});
  {
    // Longest range, half of it away: (1 - (1/2)^4)^2 = (15/16)^2.
    Light l = point_at(5e8f, 2.5e17f);
    l.range = kMaxLightRange;
    out.push_back({"range_max_inside", l, 225.0 / 256.0});
    Light beyond = point_at(2e9f, 4e18f);
    beyond.range = kMaxLightRange;
    out.push_back({"range_max_beyond", beyond, 0.0});
    Light at_edge = point_at(5e9f, 2.5e19f);
    at_edge.range = kMaxLightRange;
    out.push_back({"range_max_far_beyond", at_edge, 0.0});
  }
  {
    // Shortest range, half of it away (inside the 1 cm floor): 1e-4 / 1e-4 * (15/16)^2.
    Light l = point_at(5e-4f, 1e-4f);
    l.range = kMinLightRange;
    out.push_back({"range_min_inside", l, 225.0 / 256.0});
    Light beyond = point_at(1.0f, 1.0f);
    beyond.range = kMinLightRange;
    out.push_back({"range_min_beyond", beyond, 0.0});
  }
  {
    // Classic falloff with every coefficient at its maximum at the farthest distance:
    // 1e26 / (1e6 + 1e6 * 1e15 + 1e6 * 1e30) = 1e-10 (to 1e-9 relative).
    Light l = point_at(kMaxSceneCoordinate, kMaxLightIntensity);
    l.falloff = Falloff::classic;
    l.attenuation = glm::vec3(kMaxAttenuation);
    out.push_back({"classic_max_coefficients_far", l, 1e-10, 33.0f});
    Light kc = point_at(1.0f, 1e6f);
    kc.falloff = Falloff::classic;
    kc.attenuation = {kMaxAttenuation, 0.0f, 0.0f};
    out.push_back({"classic_max_constant", kc, 1.0});
    // Kc = Kl = 0: the denominator Kq d^2 is floored at 1e-4.
    Light kq = point_at(5e-4f, 1e-4f);
    kq.falloff = Falloff::classic;
    kq.attenuation = {0.0f, 0.0f, 1.0f};
    out.push_back({"classic_floor", kq, 1.0});
  }
  {
    // Spots aimed straight down: on the axis the cone factor is 1.
    Light wide = point_at(kMaxSceneCoordinate, kMaxLightIntensity);
    wide.kind = LightKind::spot;
    wide.direction = {0.0f, 0.0f, -1.0f};
    wide.inner_angle = wide.outer_angle = 1.5707f;
    out.push_back({"spot_widest_farthest", wide, 1e-4, 12.0f});
    Light narrow = point_at(1.0f, 1.0f);
    narrow.kind = LightKind::spot;
    narrow.direction = {0.0f, 0.0f, -1e30f};  // normalised without overflow
    narrow.inner_angle = 0.0f;
    narrow.outer_angle = 0.01f;
    // The cone's cosine gap 1 - cos(0.01) = 5e-5 is below the 1e-4 floor, so even on the axis
    // the step reaches only (1 - cos 0.01) / 1e-4.
    const double step = (1.0 - std::cos(0.01)) / 1e-4;
    out.push_back({"spot_narrowest", narrow, step * step});
    Light narrow_ok = narrow;
    narrow_ok.outer_angle = 0.05f;  // gap 1.25e-3: the full intensity on the axis
    out.push_back({"spot_narrow", narrow_ok, 1.0});
  }
  {
    Light sun;
    sun.kind = LightKind::directional;
    sun.direction = {0.0f, 0.0f, -1e-30f};  // |d|^2 underflows fp32: normalised in double
    sun.intensity = 1e5f;
    out.push_back({"directional_tiny_direction", sun, 1e5, -17.0f});
    sun.direction = {0.0f, 0.0f, -3e38f};  // |d|^2 overflows fp32
    sun.intensity = 1.0f;
    out.push_back({"directional_huge_direction", sun, 1.0});
  }
  return out;
}

class LightRange : public test::VulkanTest {};

TEST_F(LightRange, HeadOnPlaneMatchesHandDerivedRadiance) {
  Renderer renderer(context());  // one for every case: its pipelines cost more than the frames
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    const Scene scene = lit_plane(c.light);
    const double expected = head_on_brdf(0.8) * c.irradiance;
    const size_t centre = size_t(kSize / 2) * kSize + kSize / 2;

    renderer.set_scene(scene);
    renderer.render({.width = kSize, .height = kSize, .exposure_ev = c.exposure_ev});
    const ImageF hdr = renderer.read_hdr();
    for (const glm::vec4& p : hdr.pixels) ASSERT_TRUE(std::isfinite(p.r) && p.r >= 0.0f);
    // fp16 keeps 11 significant bits; fp32 light arithmetic adds a few ulps.
    EXPECT_NEAR(hdr.pixels[centre].r, expected, 2e-3 * expected) << "GPU";

    ReferenceSettings rs;
    rs.frame.width = rs.frame.height = kSize;
    rs.frame.exposure_ev = c.exposure_ev;
    const ReferenceFrame ref = render_reference(scene, rs);
    EXPECT_NEAR(ref.hdr.pixels[centre].r, expected, 1e-5 * expected) << "reference";
  }
}

// The strongest directional light accepted, exposed as far down as the renderer goes (-64 EV),
// still saturates the fp16 HDR image: the stored value is the clamp 65504, read back as
// 65504 * 2^64, and displayed white; nothing becomes NaN or 0.
TEST_F(LightRange, StrongestDirectionalSaturatesTheHdrClamp) {
  Light sun;
  sun.kind = LightKind::directional;
  sun.direction = {0.0f, 0.0f, -1.0f};
  sun.intensity = kMaxLightIntensity;
  const Scene scene = lit_plane(sun, 1.0f);
  Renderer renderer(context());
  renderer.set_scene(scene);
  renderer.render({.width = kSize, .height = kSize, .exposure_ev = -64.0f});
  const size_t centre = size_t(kSize / 2) * kSize + kSize / 2;
  EXPECT_FLOAT_EQ(renderer.read_hdr().pixels[centre].r, float(65504.0 * std::exp2(64.0)));
  EXPECT_EQ(renderer.read_ldr().pixels[centre].r, 255);
  ReferenceSettings rs;
  rs.frame.width = rs.frame.height = kSize;
  rs.frame.exposure_ev = -64.0f;
  const ReferenceFrame ref = render_reference(scene, rs);
  EXPECT_FLOAT_EQ(ref.hdr.pixels[centre].r, float(65504.0 * std::exp2(64.0)));
  EXPECT_EQ(ref.ldr.pixels[centre].r, 255);
}

// Values outside the accepted ranges are refused with a message naming the light and field.
TEST(LightRangeValidation, RefusesValuesOutsideTheRanges) {
  struct Bad {
    std::string what;
    std::function<void(Light&)> edit;
  };
  const std::vector<Bad> bad = {
      {"position", [](Light& l) { l.position.x = 2e15f; }},
      {"intensity", [](Light& l) { l.intensity = 2e26f; }},
      {"intensity",
       [](Light& l) {
         l.color = {0.0f, 3.0f, 0.0f}, l.intensity = 5e25f;
       }},
      {"negative color or intensity", [](Light& l) { l.intensity = -1.0f; }},
      {"negative color or intensity", [](Light& l) { l.color.g = -0.5f; }},
      {"range", [](Light& l) { l.range = 2e9f; }},
      {"range", [](Light& l) { l.range = 5e-4f; }},
      {"attenuation",
       [](Light& l) {
         l.attenuation = {0.0f, 2e6f, 0.0f};
       }},
      {"zero direction", [](Light& l) { l.kind = LightKind::spot, l.direction = glm::vec3(0.0f); }},
  };
  for (const Bad& b : bad) {
    Light light = point_at(2.0f, 1.0f);
    b.edit(light);
    Scene scene = lit_plane(light);
    scene.lights.insert(scene.lights.begin(), point_at(1.0f, 1.0f));  // the bad one is light 1
    try {
      validate_scene(scene);
      ADD_FAILURE() << "accepted a light with a bad " << b.what;
    } catch (const Error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("light 1"), std::string::npos) << message;
      EXPECT_NE(message.find(b.what), std::string::npos) << message;
    }
  }
  // The ends themselves are accepted.
  Light edge = point_at(kMaxSceneCoordinate, kMaxLightIntensity);
  edge.range = kMinLightRange;
  edge.attenuation = glm::vec3(kMaxAttenuation);
  EXPECT_NO_THROW(validate_scene(lit_plane(edge)));
  edge.range = kMaxLightRange;
  EXPECT_NO_THROW(validate_scene(lit_plane(edge)));
  // Geometry and the camera are held to the same coordinates.
  Scene far = lit_plane(point_at(1.0f, 1.0f));
  far.objects[0].transform[3][0] = 2e15f;
  EXPECT_THROW(validate_scene(far), Error);
  Scene far_camera = lit_plane(point_at(1.0f, 1.0f));
  far_camera.camera.position.z = 2e15f;
  EXPECT_THROW(validate_scene(far_camera), Error);
}

}  // namespace
}  // namespace tessera
