// The numeric guards of the shading pass: the places where the BRDF divides by zero or takes
// 0/0 (roughness 0, N.V = 0 at silhouettes and edge-on planes, a light on the surface, no
// lights) give finite pixels. Non-finite vertices cannot reach the GPU.
#include <cmath>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "core/check.h"
#include "core/mesh.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

class Guards : public test::VulkanTest {};

void expect_all_finite(const ImageF& image) {
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    for (int c = 0; c < 4; ++c) {
      ASSERT_TRUE(std::isfinite(image.pixels[i][c])) << "pixel " << i << " channel " << c;
    }
  }
}

Scene guard_scene(float roughness, float metallic) {
  Scene s;
  s.camera.position = {0.0f, 0.3f, 3.0f};
  s.meshes.push_back(make_uv_sphere(48, 24));
  s.meshes.push_back(make_plane(4, 4));
  s.materials.push_back({glm::vec3(0.9f, 0.5f, 0.2f), metallic, roughness});
  s.objects.push_back({0, 0, glm::mat4(1.0f)});
  // A plane seen exactly edge-on (its normal is perpendicular to the view direction).
  s.objects.push_back({1, 0,
                       glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(1.5f, 0.3f, 0.0f)),
                                   glm::radians(90.0f), glm::vec3(0, 1, 0))});
  Light on_surface;
  on_surface.position = {0.0f, 0.0f, 1.0f};  // exactly on the sphere (a vertex)
  on_surface.intensity = 5.0f;
  Light behind;
  behind.position = {0.0f, 0.0f, -3.0f};
  behind.intensity = 50.0f;
  Light grazing;
  grazing.kind = LightKind::directional;
  grazing.direction = {0.0f, 0.0f, -1.0f};  // along the view: N.L = N.V at silhouettes
  grazing.intensity = 3.0f;
  Light zero;
  zero.intensity = 0.0f;
  s.lights = {on_surface, behind, grazing, zero};
  return s;
}

TEST_F(Guards, RoughnessAndMetallicExtremesStayFinite) {
  for (float roughness : {0.0f, 1.0f}) {
    for (float metallic : {0.0f, 1.0f}) {
      Frame f = render(guard_scene(roughness, metallic), 128, 96);
      expect_all_finite(f.hdr);
    }
  }
}

TEST_F(Guards, NoLightsGiveAmbientOnly) {
  Scene s = guard_scene(0.5f, 0.0f);
  s.lights.clear();
  s.ambient = glm::vec3(0.25f);
  Frame f = render(s, 64, 48);
  expect_all_finite(f.hdr);
  for (size_t i = 0; i < f.hdr.pixels.size(); ++i) {
    if (f.visibility[i] == ~0ull) continue;
    EXPECT_NEAR(f.hdr.pixels[i].r, 0.25f * 0.9f, 1e-3f);
  }
}

TEST_F(Guards, NonFiniteVerticesAreRejectedAtUpload) {
  Renderer renderer(context());
  Scene s = guard_scene(0.5f, 0.0f);
  s.meshes[0].positions[5].x = std::nanf("");
  EXPECT_THROW(renderer.set_scene(s), Error);
}

}  // namespace
}  // namespace tessera
