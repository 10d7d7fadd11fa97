// The default scene: not blank, clear colour in the background, lit sphere centres, no NaN or
// Inf, and one pixel checked against the Cook-Torrance formula evaluated by hand.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>
#include <glm/gtc/packing.hpp>

#include "core/builtin_scenes.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr uint32_t kSize = 512;

class DefaultScene : public test::VulkanTest {};

// Pixel (x, y) and the camera ray through its centre, from the camera's definition.
glm::dvec3 ray_through_pixel(const Camera& c, double px, double py, uint32_t w, uint32_t h) {
  glm::dvec3 forward = glm::normalize(glm::dvec3(c.target - c.position));
  glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(c.up)));
  glm::dvec3 up = glm::cross(right, forward);
  double tan_half = std::tan(double(c.vertical_fov) / 2.0);
  double ndc_x = (px + 0.5) / w * 2.0 - 1.0;
  double ndc_y = (py + 0.5) / h * 2.0 - 1.0;  // y down in the image
  return glm::normalize(forward + ndc_x * tan_half * double(w) / h * right - ndc_y * tan_half * up);
}

// Cook-Torrance as written in the issue, from the formulas (not from the shader): GGX D with
// alpha = r^2, Smith G as the product of Schlick-GGX G1 with k = (r + 1)^2 / 8, Schlick F on
// V.H with F0 = mix(0.04, base, metallic), Lambert diffuse weighted by (1 - F)(1 - metallic).
glm::dvec3 cook_torrance_by_hand(glm::dvec3 n, glm::dvec3 v, glm::dvec3 l, glm::dvec3 base,
                                 double metallic, double roughness) {
  glm::dvec3 h = glm::normalize(v + l);
  double nl = glm::dot(n, l), nv = glm::dot(n, v), nh = glm::dot(n, h), vh = glm::dot(v, h);
  if (nl <= 0) return glm::dvec3(0);
  double a = roughness * roughness;
  double d = a * a / (kPi * std::pow(nh * nh * (a * a - 1) + 1, 2));
  double k = (roughness + 1) * (roughness + 1) / 8;
  double g = (nv / (nv * (1 - k) + k)) * (nl / (nl * (1 - k) + k));
  glm::dvec3 f0 = glm::mix(glm::dvec3(0.04), base, metallic);
  glm::dvec3 f = f0 + (1.0 - f0) * std::pow(1 - vh, 5);
  glm::dvec3 specular = d * g * f / (4 * nl * nv);
  glm::dvec3 diffuse = (1.0 - f) * (1 - metallic) * base / kPi;
  return (diffuse + specular) * nl;
}

double aces(double x) {
  return std::clamp(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}
double srgb(double c) {
  return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055;
}

// Projects a world point to pixel coordinates with the scene camera (y down).
glm::dvec2 project(const Camera& c, glm::dvec3 p, uint32_t w, uint32_t h) {
  glm::dvec3 forward = glm::normalize(glm::dvec3(c.target - c.position));
  glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(c.up)));
  glm::dvec3 up = glm::cross(right, forward);
  glm::dvec3 d = p - glm::dvec3(c.position);
  double z = glm::dot(d, forward);
  double tan_half = std::tan(double(c.vertical_fov) / 2.0);
  double ndc_x = glm::dot(d, right) / (z * tan_half * double(w) / h);
  double ndc_y = -glm::dot(d, up) / (z * tan_half);
  return {(ndc_x + 1) / 2 * w, (ndc_y + 1) / 2 * h};
}

TEST_F(DefaultScene, ImageIsPlausibleAndFinite) {
  Scene scene = make_sphere_grid_scene();
  Frame f = render(scene, kSize, kSize);
  ASSERT_EQ(f.hdr.pixels.size(), size_t(kSize) * kSize);

  size_t background = 0;
  for (size_t i = 0; i < f.hdr.pixels.size(); ++i) {
    glm::vec4 p = f.hdr.pixels[i];
    for (int c = 0; c < 4; ++c) ASSERT_TRUE(std::isfinite(p[c])) << "pixel " << i;
    if (f.visibility[i] == ~0ull) {
      ++background;
      // The clear colour, as stored in fp16: Vulkan lets a device round to nearest or toward
      // zero when it converts to fp16, so allow one fp16 step (2^-10 relative).
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(p[c], scene.background[c], scene.background[c] * 0x1p-10f) << "pixel " << i;
      }
    }
  }
  // 49 spheres of projected radius ~29 px cover about 49 * pi * 29^2 = 130k of 262k pixels.
  EXPECT_GT(background, f.hdr.pixels.size() / 4);
  EXPECT_LT(background, f.hdr.pixels.size() * 3 / 4) << "image is nearly blank";

  // Every sphere centre is covered by that sphere and lit above the ambient term alone.
  for (size_t o = 0; o < scene.objects.size(); ++o) {
    glm::dvec3 centre = glm::dvec3(scene.objects[o].transform[3]);
    glm::dvec2 px = project(scene.camera, centre, kSize, kSize);
    uint32_t x = uint32_t(px.x), y = uint32_t(px.y);
    uint64_t key = f.visibility[size_t(y) * kSize + x];
    ASSERT_NE(key, ~0ull) << "sphere " << o << " centre is background";
    glm::vec4 p = f.hdr.at(x, y);
    float ambient_only = scene.ambient.r * scene.materials[scene.objects[o].material].base_color.r;
    EXPECT_GT(p.r, ambient_only) << "sphere " << o << " centre is unlit";
  }
}

TEST_F(DefaultScene, SphereCentrePixelMatchesHandComputedBrdf) {
  Scene scene = make_sphere_grid_scene();
  // The centre sphere (row 3, column 3): metallic 0.5, roughness 0.5, at the origin.
  const Object& sphere = scene.objects[3 * 7 + 3];
  const Material& m = scene.materials[sphere.material];
  ASSERT_EQ(glm::vec3(sphere.transform[3]), glm::vec3(0.0f));
  ASSERT_FLOAT_EQ(m.metallic, 0.5f);
  ASSERT_FLOAT_EQ(m.roughness, 0.5f);
  Frame f = render(scene, kSize, kSize);

  // Pixel (256, 256): its ray passes within 0.1 degrees of the sphere centre. Intersect the
  // analytic unit sphere; the 64x32 tessellation differs from it by < 0.2% there.
  const uint32_t x = 256, y = 256;
  glm::dvec3 o(scene.camera.position);
  glm::dvec3 d = ray_through_pixel(scene.camera, x, y, kSize, kSize);
  double b = glm::dot(o, d);
  double t = -b - std::sqrt(b * b - (glm::dot(o, o) - 1.0));
  glm::dvec3 p = o + t * d;
  glm::dvec3 n = glm::normalize(p);
  glm::dvec3 v = -d;
  glm::dvec3 base(m.base_color);
  glm::dvec3 expected = glm::dvec3(scene.ambient) * base;
  for (const Light& light : scene.lights) {
    glm::dvec3 to_light = glm::dvec3(light.position) - p;
    double d2 = glm::dot(to_light, to_light);
    glm::dvec3 radiance = glm::dvec3(light.color) * double(light.intensity) / d2;
    expected +=
        cook_torrance_by_hand(n, v, glm::normalize(to_light), base, m.metallic, m.roughness) *
        radiance;
  }
  glm::vec4 actual = f.hdr.at(x, y);
  // Tolerance: 1% relative covers the tessellation (normals within 0.1 degree of the analytic
  // sphere here) and fp16 storage (0.05%).
  EXPECT_NEAR(actual.r, expected.r, 0.01 * expected.r);
  EXPECT_NEAR(actual.g, expected.g, 0.01 * expected.r + 1e-4);
  EXPECT_NEAR(actual.b, expected.b, 0.01 * expected.r + 1e-4);
  EXPECT_GT(expected.r, 0.05) << "the check should look at a lit pixel";

  // And the display value: ACES, then sRGB, in 8 bits, within one level.
  glm::u8vec4 ldr = f.ldr.at(x, y);
  for (int c = 0; c < 3; ++c) {
    double want = 255.0 * srgb(aces(expected[c]));
    EXPECT_NEAR(double(ldr[c]), want, 1.0) << "channel " << c;
  }
}

TEST_F(DefaultScene, MetalsSceneRendersFinite) {
  Frame f = render(make_metals_scene(), 320, 180);
  for (const glm::vec4& p : f.hdr.pixels) {
    for (int c = 0; c < 4; ++c) ASSERT_TRUE(std::isfinite(p[c]));
  }
  EXPECT_GT(f.stats.raster_triangles, 0u);
}

}  // namespace
}  // namespace tessera
