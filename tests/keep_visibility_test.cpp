// Frames that do not keep their visibility keys (FrameSettings::keep_visibility off): the
// shading pass empties every key it reads and the next frame skips filling the buffer, so each
// frame must still start from an empty buffer. Checked by rendering scenes one after another
// on one renderer without keeping the keys, where a key left behind would show in the next
// image, against each scene rendered on its own by a fresh renderer.
#include <string>

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "core/builtin_scenes.h"
#include "core/check.h"
#include "tests/support/image_assertions.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

using tessera::test::frame_of;
using tessera::testing::same_bits;

class KeepVisibility : public test::VulkanTest {
 protected:
  // Renders `scenes` in turn on one renderer with `settings` and keep_visibility off, and each
  // on a fresh renderer keeping its keys, and expects the same images.
  void expect_same_sequence(const std::vector<Scene>& scenes, FrameSettings settings,
                            const RendererOptions& options, const std::string& what) {
    SCOPED_TRACE(what);
    Renderer sequence(context(), options);
    for (size_t i = 0; i < scenes.size(); ++i) {
      SCOPED_TRACE("scene " + std::to_string(i));
      settings.keep_visibility = true;
      Renderer fresh(context(), options);
      const Frame expected = render(fresh, scenes[i], settings);
      settings.keep_visibility = false;
      sequence.set_scene(scenes[i]);
      // Twice: the second frame starts from the buffer the first one's shading emptied.
      for (int frame = 0; frame < 2; ++frame) {
        sequence.render(settings);
        EXPECT_TRUE(same_bits(sequence.read_hdr(), expected.hdr)) << "frame " << frame;
        EXPECT_EQ(sequence.read_ldr().pixels, expected.ldr.pixels) << "frame " << frame;
      }
    }
  }
};

// One small triangle facing the default camera, in a corner of the view: most of the pixels
// the scene before it drew are background in its image.
Scene one_triangle() {
  Scene scene;
  Mesh m;
  m.positions = {{0.0f, 0.0f, 0.0f}, {0.5f, 0.0f, 0.0f}, {0.0f, 0.5f, 0.0f}};
  m.normals.assign(3, glm::vec3(0.0f, 0.0f, 1.0f));
  m.uvs = {{0.0f, 0.0f}, {1.0f, 0.0f}, {0.0f, 1.0f}};
  m.indices = {0, 1, 2};
  scene.meshes = {m};
  scene.materials = {Material{}};
  scene.objects = {{0, 0, glm::translate(glm::mat4(1.0f), glm::vec3(0.8f, 0.8f, 0.0f))}};
  return scene;
}

// `scene` with every object moved `distance` further from the default camera: the same
// triangles (a key left behind names a triangle of this scene too, which the shading pass
// would shade; one of a larger id than the scene has would show as background), drawn smaller.
Scene moved_away(Scene scene, float distance) {
  for (Object& o : scene.objects) {
    o.transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, -distance)) * o.transform;
  }
  return scene;
}

TEST_F(KeepVisibility, FramesThatEmptyTheirKeysLeaveNoneBehind) {
  const Scene spheres = make_builtin_scene("spheres");
  const Scene far = moved_away(spheres, 20.0f);
  expect_same_sequence({spheres, far, one_triangle(), make_builtin_scene("textured")},
                       frame_of(96, 72), {}, "1 sample");
  expect_same_sequence({spheres, far}, frame_of(96, 72), {.shade_tiles = false},
                       "every pixel shaded");
  expect_same_sequence({spheres, far}, frame_of(64, 48, 4), {.max_batch_triangles = 2000},
                       "4 samples, batches");
}

TEST_F(KeepVisibility, TheKeysAreReadableOnlyFromFramesThatKeepThem) {
  Renderer renderer(context(), {});
  renderer.set_scene(make_builtin_scene("spheres"));
  FrameSettings settings = frame_of(64, 64);
  settings.keep_visibility = false;
  renderer.render(settings);
  EXPECT_THROW(renderer.read_visibility(), Error);
  EXPECT_THROW(renderer.read_visibility_at(32, 32), Error);
  settings.keep_visibility = true;
  renderer.render(settings);
  const std::vector<uint64_t> keys = renderer.read_visibility();
  EXPECT_NE(keys[32 * 64 + 32], TS_VIS_EMPTY);  // the middle sphere
  // Silhouette coverage's outline pass reads the keys after shading: they are kept anyway.
  settings = frame_of(64, 64, 4);
  settings.aa_coverage = AaCoverage::silhouette;
  settings.keep_visibility = false;
  renderer.render(settings);
  EXPECT_EQ(renderer.read_visibility().size(), 64u * 64u * 4u);
}

}  // namespace
}  // namespace tessera
