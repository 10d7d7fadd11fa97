// Scene edits and their history (core/scene_edit.h): apply then undo gives back the original
// scene field by field, redo the edited one (built here by hand), material edits copy on
// write, bad edits are refused whole, and the dirty flag follows the saved state.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "core/builtin_scenes.h"
#include "core/check.h"
#include "core/materials.h"
#include "core/mesh.h"
#include "core/scene_edit.h"
#include "tests/support/scene_assertions.h"

namespace tessera {
namespace {

// A small scene whose two objects share material 0.
Scene two_cubes() {
  Scene s;
  s.meshes = {make_cube()};
  s.materials = {Material{.base_color = glm::vec3(0.5f)}};
  s.objects = {
      Object{.mesh = 0, .material = 0},
      Object{.mesh = 0, .material = 0, .transform = glm::translate(glm::mat4(1.0f), {3, 0, 0})}};
  s.lights = {Light{.position = {0, 4, 0}, .intensity = 10.0f}};
  return s;
}

// Applies `edit`, checks the result against `expected`, undoes it (the original again),
// redoes it (`expected` again).
void expect_reversible(const Scene& original, const Edit& edit, const Scene& expected) {
  SCOPED_TRACE(edit.label);
  Scene s = original;
  EditHistory h;
  h.apply(s, edit);
  expect_same_scene(s, expected);
  ASSERT_TRUE(h.undo(s));
  expect_same_scene(s, original);
  ASSERT_TRUE(h.redo(s));
  expect_same_scene(s, expected);
}

TEST(SceneEdit, EachEditIsReversible) {
  const Scene s = two_cubes();
  const glm::mat4 moved = glm::translate(glm::mat4(1.0f), {0, 2, 0});
  {
    Scene e = s;
    e.objects.push_back(Object{.mesh = 0, .material = 0, .transform = moved});
    expect_reversible(s, add_object_copy(s, 1, moved), e);
  }
  {
    Scene e = s;
    e.objects.erase(e.objects.begin());
    expect_reversible(s, delete_object(s, 0), e);
  }
  {
    Scene e = s;
    e.objects[1].transform = moved;
    expect_reversible(s, move_object(s, 1, moved), e);
  }
  {
    Scene e = s;
    e.meshes.push_back(make_uv_sphere(64, 32));
    e.materials.push_back(metal_material("gold", 0.2f));
    e.objects.push_back(Object{
        .mesh = 1,
        .material = 1,
        .transform = glm::scale(glm::translate(glm::mat4(1.0f), {1, 2, 3}), glm::vec3(0.5f))});
    expect_reversible(s, add_sphere(s, {1, 2, 3}, 0.5f, metal_material("gold", 0.2f)), e);
  }
  const Light spot{.kind = LightKind::spot, .position = {1, 1, 1}, .intensity = 3.0f};
  {
    Scene e = s;
    e.lights.push_back(spot);
    expect_reversible(s, add_light(s, spot), e);
  }
  {
    Scene e = s;
    e.lights.clear();
    expect_reversible(s, delete_light(s, 0), e);
  }
  {
    Scene e = s;
    e.lights[0] = spot;
    expect_reversible(s, set_light(s, 0, spot), e);
  }
  {
    Scene e = s;
    e.environment = std::make_shared<const Environment>(make_uniform_environment(glm::vec3(1)));
    expect_reversible(s, set_environment(s, e.environment), e);
  }
}

TEST(SceneEdit, MetalPresetsGiveTheirF0) {
  const Material gold = metal_material("gold", 0.25f);
  EXPECT_EQ(gold.metallic, 1.0f);
  EXPECT_EQ(gold.roughness, 0.25f);
  EXPECT_EQ(gold.base_color, find_metal_preset("gold")->f0);
  try {
    metal_material("unobtainium");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("unobtainium"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("gold"), std::string::npos) << e.what();
  }
}

TEST(SceneEdit, ASharedMaterialIsCopiedOnWrite) {
  const Scene s = two_cubes();  // both objects use material 0
  const Material red{
      .base_color = {1, 0, 0}, .metallic = 0.5f, .roughness = 0.2f, .emissive = {0, 0, 2}};
  Scene e = s;
  e.materials.push_back(red);
  e.objects[1].material = 1;  // object 0 keeps material 0 unchanged
  expect_reversible(s, set_object_material(s, 1, red), e);

  // Sole user: changed in place, no new material.
  Scene alone = s;
  alone.materials.push_back(Material{});
  alone.objects[1].material = 1;
  Scene in_place = alone;
  in_place.materials[1] = red;
  expect_reversible(alone, set_object_material(alone, 1, red), in_place);
}

TEST(SceneEdit, AddedSpheresAndCopiesShareMeshes) {
  Scene s = two_cubes();
  EditHistory h;
  h.apply(s, add_sphere(s, {0, 0, 0}, 1.0f, Material{}));
  h.apply(s, add_sphere(s, {2, 0, 0}, 1.0f, Material{}));
  EXPECT_EQ(s.meshes.size(), 2u);  // the second sphere reuses the first one's mesh
  EXPECT_EQ(s.objects[2].mesh, 1u);
  EXPECT_EQ(s.objects[3].mesh, 1u);
  h.apply(s, add_object_copy(s, 3, glm::mat4(1.0f)));
  EXPECT_EQ(s.meshes.size(), 2u);
  EXPECT_EQ(s.objects[4].mesh, 1u);
  EXPECT_EQ(s.objects[4].material, s.objects[3].material);
}

TEST(SceneEdit, BadEditsAreRefusedWhole) {
  const Scene original = two_cubes();
  Scene s = original;
  EditHistory h;
  auto message = [](auto&& f) -> std::string {
    try {
      f();
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(message([&] { delete_object(s, 2); }).find("object 2 does not exist"),
            std::string::npos);
  EXPECT_NE(message([&] { set_light(s, 5, Light{}); }).find("light 5"), std::string::npos);
  EXPECT_NE(message([&] {
              add_sphere(s, {0, 0, 0}, -1.0f, Material{});
            }).find("radius"),
            std::string::npos);
  glm::mat4 nan(1.0f);
  nan[3][0] = std::numeric_limits<float>::quiet_NaN();
  const std::string m = message([&] { h.apply(s, move_object(s, 0, nan)); });
  EXPECT_NE(m.find("move object 0: "), std::string::npos) << m;
  EXPECT_NE(m.find("object 0"), std::string::npos) << m;
  expect_same_scene(s, original);
  EXPECT_FALSE(h.can_undo());
  EXPECT_FALSE(h.dirty());
  Light bad;
  bad.intensity = -1.0f;
  EXPECT_THROW(h.apply(s, set_light(s, 0, bad)), Error);
  expect_same_scene(s, original);
  // An edit of two operations (a new material, the object pointed at it; the material is
  // shared) that validate_scene refuses: both are rolled back.
  Material nan_colour;
  nan_colour.base_color.g = std::numeric_limits<float>::quiet_NaN();
  const Edit two_ops = set_object_material(s, 1, nan_colour);
  ASSERT_EQ(two_ops.ops.size(), 2u);
  EXPECT_THROW(h.apply(s, two_ops), Error);
  expect_same_scene(s, original);
  EXPECT_FALSE(h.can_undo());
  // An edit built for another scene: the index check at apply time.
  Edit stale = delete_object(two_cubes(), 1);
  Scene small = original;
  small.objects.pop_back();
  EXPECT_THROW(h.apply(small, stale), Error);
  EXPECT_EQ(small.objects.size(), 1u);
}

TEST(SceneEdit, DirtyFollowsTheSavedState) {
  Scene s = two_cubes();
  EditHistory h;
  EXPECT_FALSE(h.dirty());
  h.apply(s, move_object(s, 0, glm::translate(glm::mat4(1.0f), {0, 1, 0})));
  EXPECT_TRUE(h.dirty());
  h.undo(s);
  EXPECT_FALSE(h.dirty());  // back at the saved state
  h.redo(s);
  EXPECT_TRUE(h.dirty());
  h.mark_saved();
  EXPECT_FALSE(h.dirty());
  h.undo(s);
  EXPECT_TRUE(h.dirty());
  h.redo(s);
  EXPECT_FALSE(h.dirty());
  // Undo past the saved state, then a new edit: redo is gone and so is the saved state.
  h.undo(s);
  h.apply(s, delete_light(s, 0));
  EXPECT_FALSE(h.can_redo());
  EXPECT_TRUE(h.dirty());
  h.undo(s);
  EXPECT_TRUE(h.dirty());  // the state before the saved edit, not the saved one
  EXPECT_FALSE(h.redo(s) && h.redo(s));
}

TEST(SceneEdit, LongSequencesUndoAndRedoStepByStep) {
  Scene s = make_builtin_scene("spheres");
  std::vector<Scene> states{s};
  EditHistory h;
  for (uint32_t i = 0; i < 24; ++i) {
    const uint32_t o = i % uint32_t(s.objects.size());
    Edit e;
    switch (i % 6) {
      case 0:
        e = add_object_copy(s, o, glm::translate(glm::mat4(1.0f), {float(i), 0, 0}));
        break;
      case 1:
        e = move_object(s, o, glm::scale(s.objects[o].transform, glm::vec3(1.5f)));
        break;
      case 2:
        e = set_object_material(s, o, Material{.base_color = glm::vec3(0.1f * float(i % 10))});
        break;
      case 3:
        e = add_sphere(s, {0, float(i), 0}, 0.25f, metal_material("copper"));
        break;
      case 4:
        e = delete_object(s, o);
        break;
      default:
        e = add_light(s, Light{.position = {0, float(i), 2}});
        break;
    }
    h.apply(s, e);
    states.push_back(s);
  }
  for (size_t i = states.size() - 1; i > 0; --i) {
    ASSERT_TRUE(h.undo(s));
    SCOPED_TRACE("after undoing to state " + std::to_string(i - 1));
    expect_same_scene(s, states[i - 1]);
  }
  EXPECT_FALSE(h.undo(s));
  for (size_t i = 1; i < states.size(); ++i) {
    ASSERT_TRUE(h.redo(s));
    SCOPED_TRACE("after redoing to state " + std::to_string(i));
    expect_same_scene(s, states[i]);
  }
  EXPECT_FALSE(h.redo(s));
}

}  // namespace
}  // namespace tessera
