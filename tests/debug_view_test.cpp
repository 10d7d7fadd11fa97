// Debug views: interpolated normals and uvs, and id colours, written without tone mapping.
#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>
#include <map>

#include "core/mesh.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

class DebugView : public test::VulkanTest {};

Scene plane_scene() {
  Scene s;
  s.camera.position = {0.0f, 0.0f, 3.0f};
  s.meshes.push_back(make_plane(1, 1));  // uv (0,0) at (-1,-1), (1,1) at (1,1)
  s.materials.push_back({});
  s.objects.push_back({0, 0, glm::mat4(1.0f)});
  return s;
}

TEST_F(DebugView, NormalAndUvViewsShowInterpolatedAttributes) {
  Scene scene = plane_scene();
  Renderer renderer(context());
  renderer.set_scene(scene);
  FrameSettings settings;
  settings.width = settings.height = 64;
  settings.view = View::normal;
  renderer.render(settings);
  ImageF normal = renderer.read_hdr();
  // The plane faces +z: the normal view is (0.5, 0.5, 1) wherever it is covered.
  glm::vec4 centre = normal.at(32, 32);
  EXPECT_NEAR(centre.r, 0.5f, 1e-3f);
  EXPECT_NEAR(centre.g, 0.5f, 1e-3f);
  EXPECT_NEAR(centre.b, 1.0f, 1e-3f);
  Image8 ldr = renderer.read_ldr();
  EXPECT_EQ(ldr.at(32, 32).b, 255) << "debug views skip the tone curve";

  settings.view = View::uv;
  renderer.render(settings);
  ImageF uv = renderer.read_hdr();
  // u grows to the right and v downwards (as the image's y and a texture's rows), linearly:
  // the plane is parallel to the image, so perspective-correct and affine interpolation agree.
  std::vector<uint64_t> vis = renderer.read_visibility();
  float last_u = -1.0f;
  for (uint32_t x = 0; x < 64; ++x) {
    if (vis[32 * 64 + x] == ~0ull) continue;
    EXPECT_GT(uv.at(x, 32).r, last_u);
    last_u = uv.at(x, 32).r;
  }
  EXPECT_LT(uv.at(32, 20).g, uv.at(32, 44).g);
  EXPECT_NEAR(uv.at(32, 32).r, 0.5f, 0.03f);
}

TEST_F(DebugView, TriangleViewGivesOneColourPerTriangle) {
  Scene scene = plane_scene();
  Renderer renderer(context());
  renderer.set_scene(scene);
  FrameSettings settings;
  settings.width = settings.height = 48;
  settings.view = View::triangle;
  renderer.render(settings);
  ImageF image = renderer.read_hdr();
  std::vector<uint64_t> vis = renderer.read_visibility();
  std::map<uint32_t, glm::vec4> colour_of;
  for (size_t i = 0; i < vis.size(); ++i) {
    if (vis[i] == ~0ull) continue;
    uint32_t id = uint32_t(vis[i]);
    auto [it, inserted] = colour_of.emplace(id, image.pixels[i]);
    EXPECT_EQ(it->second, image.pixels[i]) << "pixel " << i;
  }
  ASSERT_EQ(colour_of.size(), 2u);
  EXPECT_NE(colour_of.begin()->second, colour_of.rbegin()->second);
}

}  // namespace
}  // namespace tessera
