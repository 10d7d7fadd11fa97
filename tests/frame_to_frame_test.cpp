// What one frame leaves for the next, and what a frame leaves out. The host zeroes the counters,
// the shading pass resets the tiles' depth bounds (no per-frame fill of either), the background
// pass computes the background's colours only when what they depend on changed, and frames of
// few triangles record no object_clip pass (setup forms each triangle's transform itself).
// Each is checked against a fresh renderer, which computes everything anew: frames rendered
// one after another on one renderer must give its bits.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "core/builtin_scenes.h"
#include "core/mesh.h"
#include "tests/support/image_assertions.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

using tessera::test::frame_of;
using tessera::testing::same_bits;

class FrameToFrame : public test::VulkanTest {
 protected:
  // Renders `scene` with each of `settings` in turn on one renderer, and each on a fresh one,
  // and expects the same images and counts.
  void expect_same_as_fresh(const Scene& scene, const std::vector<FrameSettings>& settings) {
    Renderer sequence(context(), {});
    sequence.set_scene(scene);
    for (size_t i = 0; i < settings.size(); ++i) {
      SCOPED_TRACE("settings " + std::to_string(i));
      Renderer fresh(context(), {});
      const Frame expected = render(fresh, scene, settings[i]);
      const FrameStats stats = sequence.render(settings[i]);
      EXPECT_TRUE(same_bits(sequence.read_hdr(), expected.hdr));
      EXPECT_EQ(sequence.read_ldr().pixels, expected.ldr.pixels);
      // Counters left from the frame before would add up (or overflow the lists).
      EXPECT_EQ(stats.raster_triangles, expected.stats.raster_triangles);
      EXPECT_EQ(stats.tile_entries, expected.stats.tile_entries);
      EXPECT_EQ(stats.culled_backface, expected.stats.culled_backface);
      EXPECT_EQ(stats.attempts, 1u);
    }
  }
};

// The background pass runs again whenever the background's colours would change: after a new
// exposure, tone map, view or HDR format, the background pixels show the new values, not the
// first frame's.
TEST_F(FrameToFrame, TheBackgroundFollowsEveryChangeOfItsInputs) {
  Scene scene = make_builtin_scene("spheres");
  scene.background = glm::vec3(0.3f, 0.05f, 1.7f);  // a colour the tone map bends
  std::vector<FrameSettings> settings(6, frame_of(48, 40));
  settings[1].exposure_ev = 1.5f;
  settings[2].tonemap = ToneMap::reinhard;
  settings[3].view = View::normal;  // written as it is, without exposure or curve
  settings[4].hdr_format = HdrFormat::fp32;
  settings[5] = settings[0];  // and back
  expect_same_as_fresh(scene, settings);

  // And after set_scene with another background.
  Renderer renderer(context(), {});
  render(renderer, scene, frame_of(48, 40));
  scene.background = glm::vec3(0.0f, 2.0f, 0.25f);
  const Frame again = render(renderer, scene, frame_of(48, 40));
  Renderer fresh(context(), {});
  const Frame expected = render(fresh, scene, frame_of(48, 40));
  EXPECT_TRUE(same_bits(again.hdr, expected.hdr));
  EXPECT_EQ(again.ldr.pixels, expected.ldr.pixels);
  EXPECT_NE(again.ldr.pixels[0],
            render(fresh, make_builtin_scene("spheres"), frame_of(48, 40)).ldr.pixels[0]);
}

// Frames one after another at one setting: the counters start from zero and the tiles' depth
// bounds from "nothing drawn" in each. A wall fills the view behind the default scene, so every
// tile's bound is lowered to the wall's depth; the scene then moves away from the camera, and a
// bound left from the frame before would reject all of it (at 160 x 120 the wall's triangles
// are binned, also on lavapipe, whose small-triangle limit is 4,096 px).
TEST_F(FrameToFrame, CountersAndDepthBoundsStartAfreshEachFrame) {
  Scene scene = make_builtin_scene("spheres");
  Mesh wall;
  wall.positions = {
      {-1.0f, -1.0f, 0.0f}, {1.0f, -1.0f, 0.0f}, {1.0f, 1.0f, 0.0f}, {-1.0f, 1.0f, 0.0f}};
  wall.normals.assign(4, glm::vec3(0.0f, 0.0f, 1.0f));
  wall.uvs.assign(4, glm::vec2(0.0f));
  wall.indices = {0, 1, 2, 0, 2, 3};
  scene.meshes.push_back(wall);
  scene.objects.push_back({uint32_t(scene.meshes.size() - 1), 0,
                           glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, -2.0f)),
                                      glm::vec3(40.0f))});
  Renderer sequence(context(), {});
  for (int step = 0; step < 3; ++step) {
    SCOPED_TRACE("step " + std::to_string(step));
    Renderer fresh(context(), {});
    const Frame expected = render(fresh, scene, frame_of(160, 120));
    EXPECT_GT(expected.stats.tile_entries, 0u);
    for (int frame = 0; frame < 2; ++frame) {
      const Frame got = render(sequence, scene, frame_of(160, 120));
      EXPECT_TRUE(same_bits(got.hdr, expected.hdr)) << "frame " << frame;
      EXPECT_EQ(got.stats.raster_triangles, expected.stats.raster_triangles);
      EXPECT_EQ(got.stats.tile_entries, expected.stats.tile_entries);
      EXPECT_EQ(got.stats.rejected_entries, expected.stats.rejected_entries);
      EXPECT_EQ(got.stats.rejected_small, expected.stats.rejected_small);
    }
    for (Object& o : scene.objects)
      o.transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, -4.0f)) * o.transform;
  }
}

// A frame of at most 2^17 triangle instances records no object_clip pass: setup forms each
// triangle's view_proj * model itself, with the expression the pass uses, so the same bits. One
// sphere alone (the variant), and the same sphere with enough small spheres hidden behind it to
// pass 2^17 triangles (the pass): the same image.
TEST_F(FrameToFrame, SetupFormsTheTransformsOfFewTrianglesWithTheSameBits) {
  Scene alone;
  alone.meshes = {make_uv_sphere(32, 16)};
  alone.materials = {Material{}};
  const glm::mat4 tilted =
      glm::scale(glm::rotate(glm::mat4(1.0f), 0.4f, glm::vec3(0.3f, 1.0f, 0.2f)), glm::vec3(0.8f));
  alone.objects = {{0, 0, tilted}};
  Scene hidden = alone;
  const uint64_t sphere = alone.meshes[0].indices.size() / 3;
  const uint64_t behind = (uint64_t(1) << 17) / sphere + 1;
  for (uint64_t i = 0; i < behind; ++i) {
    const glm::vec3 at(0.05f * float(i % 8) - 0.2f, 0.05f * float(i / 8 % 8) - 0.2f,
                       -2.0f - 0.01f * float(i / 64));
    hidden.objects.push_back(
        {0, 0, glm::scale(glm::translate(glm::mat4(1.0f), at), glm::vec3(0.1f))});
  }
  Renderer renderer(context(), {});
  const Frame one = render(renderer, alone, frame_of(64, 64));
  const Frame many = render(renderer, hidden, frame_of(64, 64));
  ASSERT_TRUE(one.stats.has_timestamps);
  EXPECT_EQ(one.stats.pass_ms[size_t(Pass::object_clip)], 0.0);  // not recorded
  EXPECT_GT(many.stats.pass_ms[size_t(Pass::object_clip)], 0.0);
  EXPECT_GT(many.stats.triangles_submitted, uint64_t(1) << 17);
  // The keys' depths, from the clip-space positions: the same bits. (Their triangle ids differ:
  // the upload orders the objects by their own rules, here the sphere after the hidden ones.)
  ASSERT_EQ(one.visibility.size(), many.visibility.size());
  size_t drawn = 0;
  for (size_t i = 0; i < one.visibility.size(); ++i) {
    EXPECT_EQ(one.visibility[i] >> 32, many.visibility[i] >> 32) << "pixel " << i;
    drawn += one.visibility[i] != TS_VIS_EMPTY;
  }
  EXPECT_GT(drawn, 400u);  // the sphere, about 25 px across
  EXPECT_TRUE(same_bits(one.hdr, many.hdr));
  EXPECT_EQ(one.ldr.pixels, many.ldr.pixels);
}

}  // namespace
}  // namespace tessera
