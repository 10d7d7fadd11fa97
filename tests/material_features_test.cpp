// Material features glTF 2.0 asks for: double-sided materials (never culled by facing, back
// faces shaded with the normal flipped toward the viewer) and emissive texture maps (sRGB,
// times the emissive factor). Expected values are computed by hand here; the compute path, the
// hardware baseline and the reference renderer are each checked on their own.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include <gtest/gtest.h>
#include <glm/glm.hpp>

#include "compute/baselines/hardware_baseline.h"
#include "core/check.h"
#include "core/mesh.h"
#include "core/reference_renderer.h"
#include "core/scene.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

class MaterialFeatures : public test::VulkanTest {};

constexpr uint32_t kSide = 101;  // odd: the centre pixel looks along the axis
constexpr uint32_t kCentre = kSide / 2;
constexpr double kGpuTolerance = 2e-3;        // fp16 texels and HDR image: 2^-11 each
constexpr double kReferenceTolerance = 1e-5;  // float material values

// The z = 0 plane (front +z) seen from behind, from (0, 0, -3), lit head-on from the camera's
// side by a directional light of irradiance 2 travelling +z; no ambient.
Scene plane_from_behind(bool double_sided) {
  Scene s;
  s.camera.position = {0.0f, 0.0f, -3.0f};
  s.camera.vertical_fov = glm::radians(40.0f);
  s.meshes.push_back(make_plane(1, 1));
  Material m;
  m.base_color = {0.6f, 0.3f, 0.2f};
  m.metallic = 0.0f;
  m.roughness = 0.8f;
  m.double_sided = double_sided;
  s.materials.push_back(m);
  s.objects.push_back({0, 0, glm::mat4(1.0f)});
  Light sun;
  sun.kind = LightKind::directional;
  sun.direction = {0.0f, 0.0f, 1.0f};
  sun.intensity = 2.0f;
  s.lights.push_back(sun);
  s.background = glm::vec3(0.125f);
  return s;
}

// Radiance of the centre pixel when the shading normal is flipped to (0, 0, -1): then
// N = V = L = H, so D = 1 / (pi alpha^2), G = 1, F = F0 = 0.04 (metallic 0), and the
// Lambert term is (1 - F0) albedo / pi; times E cos = 2 * 1. Unflipped, N.L = -1: black.
glm::dvec3 expected_back_radiance(const Material& m) {
  const double pi = std::numbers::pi;
  const double alpha = double(m.roughness) * m.roughness;
  const double f0 = 0.04;
  const double specular = (1.0 / (pi * alpha * alpha)) * f0 / 4.0;
  glm::dvec3 out;
  for (int c = 0; c < 3; ++c) out[c] = ((1.0 - f0) * m.base_color[c] / pi + specular) * 2.0;
  return out;
}

void expect_near(glm::vec4 got, glm::dvec3 want, double relative, const char* what) {
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(got[c], want[c], relative * std::max(want[c], 1e-3)) << what << " channel " << c;
  }
}

TEST_F(MaterialFeatures, DoubleSidedPlaneSeenFromBehindIsShadedWithTheFlippedNormal) {
  const Scene s = plane_from_behind(true);
  const glm::dvec3 want = expected_back_radiance(s.materials[0]);
  const glm::dvec3 flipped_normal_view(0.5, 0.5, 0.0);  // N = (0, 0, -1) as N * 0.5 + 0.5
  FrameSettings fs;
  fs.width = fs.height = kSide;
  Renderer renderer(context());
  renderer.set_scene(s);
  EXPECT_EQ(renderer.render(fs).culled_backface, 0u);
  expect_near(renderer.read_hdr().at(kCentre, kCentre), want, kGpuTolerance, "compute");
  HardwareBaseline(renderer).render(fs);
  expect_near(renderer.read_hdr().at(kCentre, kCentre), want, kGpuTolerance, "hardware");
  FrameSettings normals = fs;
  normals.view = View::normal;
  renderer.render(normals);
  expect_near(renderer.read_hdr().at(kCentre, kCentre), flipped_normal_view, kGpuTolerance,
              "compute normal view");

  ReferenceSettings rs;
  rs.frame = fs;
  expect_near(render_reference(s, rs).hdr.at(kCentre, kCentre), want, kReferenceTolerance,
              "reference");
  rs.frame = normals;
  expect_near(render_reference(s, rs).hdr.at(kCentre, kCentre), flipped_normal_view,
              kReferenceTolerance, "reference normal view");
}

TEST_F(MaterialFeatures, DoubleSidedIgnoresEveryCullMode) {
  const Scene s = plane_from_behind(true);
  const glm::dvec3 want = expected_back_radiance(s.materials[0]);
  FrameSettings fs;
  fs.width = fs.height = kSide;
  for (CullMode cull : {CullMode::back, CullMode::front, CullMode::none}) {
    RendererOptions options;
    options.cull = cull;
    Renderer renderer(context(), options);
    renderer.set_scene(s);
    EXPECT_EQ(renderer.render(fs).culled_backface, 0u) << int(cull);
    expect_near(renderer.read_hdr().at(kCentre, kCentre), want, kGpuTolerance, "compute");
    ReferenceSettings rs;
    rs.frame = fs;
    rs.cull = cull;
    expect_near(render_reference(s, rs).hdr.at(kCentre, kCentre), want, kReferenceTolerance,
                "reference");
  }
}

TEST_F(MaterialFeatures, SingleSidedPlaneSeenFromBehindIsCulled) {
  const Scene s = plane_from_behind(false);
  const glm::dvec3 background(s.background);
  FrameSettings fs;
  fs.width = fs.height = kSide;
  Renderer renderer(context());
  renderer.set_scene(s);
  EXPECT_EQ(renderer.render(fs).culled_backface, 2u);  // both triangles of the plane
  expect_near(renderer.read_hdr().at(kCentre, kCentre), background, 0.0, "compute");
  HardwareBaseline(renderer).render(fs);
  expect_near(renderer.read_hdr().at(kCentre, kCentre), background, 0.0, "hardware");
  ReferenceSettings rs;
  rs.frame = fs;
  const ReferenceFrame f = render_reference(s, rs);
  EXPECT_EQ(f.owner[size_t(kCentre) * kSide + kCentre], kNoTriangle);
  EXPECT_EQ(f.raster_triangles, 0u);
}

// IEC 61966-2-1 decoding, written out here rather than taken from core/texture.h.
double srgb_decode(uint8_t byte) {
  const double c = byte / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

TEST_F(MaterialFeatures, EmissiveMapIsDecodedFromSrgbAndScaledByTheFactor) {
  // A 4 x 4 texture of 2 x 2 cells, each cell 2 x 2 texels of one colour, so that bilinear
  // filtering anywhere in a cell's middle half returns its colour exactly. Rows top to
  // bottom: texel row r holds v in [r / 4, (r + 1) / 4).
  const glm::u8vec4 a(200, 100, 50, 255), b(30, 180, 255, 255);
  Texture t;
  t.width = t.height = 4;
  t.srgb = true;
  for (uint32_t y = 0; y < 4; ++y)
    for (uint32_t x = 0; x < 4; ++x) t.texels.push_back((x / 2 + y / 2) % 2 ? b : a);
  // The plane fills the 64 x 64 image exactly: camera 2 away, tan(fov / 2) = 1 / 2, so pixel
  // column px sees x = (px + 0.5) / 32 - 1, row py sees y = 1 - (py + 0.5) / 32, and the plane's
  // uv is ((x + 1) / 2, (1 - y) / 2): pixel (px, py) sees uv ((px + 0.5) / 64, (py + 0.5) / 64),
  // the texture as it is stored. Pixels 16 and 48 see uv 0.26 and 0.76.
  Scene s;
  s.camera.position = {0.0f, 0.0f, 2.0f};
  s.camera.vertical_fov = 2.0f * std::atan(0.5f);
  s.meshes.push_back(make_plane(1, 1));
  Material m;
  m.emissive = {2.0f, 1.0f, 0.5f};
  m.emissive_map = 0;
  s.materials.push_back(m);
  s.textures.push_back(t);
  s.objects.push_back({0, 0, glm::mat4(1.0f)});
  struct Probe {
    uint32_t px, py;
    glm::u8vec4 texel;
  };
  // (16, 16): uv (0.26, 0.26), cell (0, 0) = a; (48, 16): cell (1, 0) = b; (16, 48): cell
  // (0, 1) = b; (48, 48): cell (1, 1) = a.
  const Probe probes[] = {{16, 16, a}, {48, 16, b}, {16, 48, b}, {48, 48, a}};
  auto expected = [&](glm::u8vec4 texel) {
    return glm::dvec3(srgb_decode(texel.r), srgb_decode(texel.g), srgb_decode(texel.b)) *
           glm::dvec3(m.emissive);
  };
  FrameSettings fs;
  fs.width = fs.height = 64;
  Renderer renderer(context());
  renderer.set_scene(s);
  renderer.render(fs);
  const ImageF compute = renderer.read_hdr();
  HardwareBaseline(renderer).render(fs);
  const ImageF hardware = renderer.read_hdr();
  ReferenceSettings rs;
  rs.frame = fs;
  const ImageF reference = render_reference(s, rs).hdr;
  for (const Probe& p : probes) {
    SCOPED_TRACE("pixel " + std::to_string(p.px) + ", " + std::to_string(p.py));
    expect_near(compute.at(p.px, p.py), expected(p.texel), kGpuTolerance, "compute");
    expect_near(hardware.at(p.px, p.py), expected(p.texel), kGpuTolerance, "hardware");
    expect_near(reference.at(p.px, p.py), expected(p.texel), kReferenceTolerance, "reference");
  }
}

TEST(MaterialFeaturesValidation, EmissiveMapIndexIsChecked) {
  Scene s;
  s.meshes.push_back(make_plane(1, 1));
  Material m;
  m.emissive_map = 3;
  s.materials.push_back(m);
  s.objects.push_back({0, 0, glm::mat4(1.0f)});
  try {
    validate_scene(s);
    FAIL() << "an emissive map naming a missing texture was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("as its emissive map"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tessera
