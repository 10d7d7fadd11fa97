#include "tests/support/scene_assertions.h"

#include <gtest/gtest.h>

namespace tessera {

void expect_same_scene(const Scene& a, const Scene& b) {
  EXPECT_EQ(a.camera.position, b.camera.position);
  EXPECT_EQ(a.camera.target, b.camera.target);
  EXPECT_EQ(a.camera.up, b.camera.up);
  EXPECT_EQ(a.camera.vertical_fov, b.camera.vertical_fov);
  EXPECT_EQ(a.camera.near_plane, b.camera.near_plane);
  EXPECT_EQ(a.background, b.background);
  EXPECT_EQ(a.ambient, b.ambient);
  ASSERT_EQ(a.meshes.size(), b.meshes.size());
  for (size_t i = 0; i < a.meshes.size(); ++i) {
    EXPECT_EQ(a.meshes[i].positions, b.meshes[i].positions) << "mesh " << i;
    EXPECT_EQ(a.meshes[i].normals, b.meshes[i].normals) << "mesh " << i;
    EXPECT_EQ(a.meshes[i].uvs, b.meshes[i].uvs) << "mesh " << i;
    EXPECT_EQ(a.meshes[i].indices, b.meshes[i].indices) << "mesh " << i;
    EXPECT_EQ(a.meshes[i].tangents, b.meshes[i].tangents) << "mesh " << i;
  }
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (size_t i = 0; i < a.materials.size(); ++i) {
    const Material &x = a.materials[i], &y = b.materials[i];
    EXPECT_EQ(x.base_color, y.base_color) << "material " << i;
    EXPECT_EQ(x.metallic, y.metallic) << "material " << i;
    EXPECT_EQ(x.roughness, y.roughness) << "material " << i;
    EXPECT_EQ(x.emissive, y.emissive) << "material " << i;
    EXPECT_EQ(x.occlusion, y.occlusion) << "material " << i;
    EXPECT_EQ(x.base_color_map, y.base_color_map) << "material " << i;
    EXPECT_EQ(x.metallic_roughness_map, y.metallic_roughness_map) << "material " << i;
    EXPECT_EQ(x.normal_map, y.normal_map) << "material " << i;
    EXPECT_EQ(x.occlusion_map, y.occlusion_map) << "material " << i;
    EXPECT_EQ(x.normal_scale, y.normal_scale) << "material " << i;
    EXPECT_EQ(x.emissive_map, y.emissive_map) << "material " << i;
    EXPECT_EQ(x.double_sided, y.double_sided) << "material " << i;
  }
  ASSERT_EQ(a.objects.size(), b.objects.size());
  for (size_t i = 0; i < a.objects.size(); ++i) {
    EXPECT_EQ(a.objects[i].mesh, b.objects[i].mesh) << "object " << i;
    EXPECT_EQ(a.objects[i].material, b.objects[i].material) << "object " << i;
    EXPECT_EQ(a.objects[i].transform, b.objects[i].transform) << "object " << i;
  }
  ASSERT_EQ(a.lights.size(), b.lights.size());
  for (size_t i = 0; i < a.lights.size(); ++i) {
    const Light &x = a.lights[i], &y = b.lights[i];
    EXPECT_EQ(x.kind, y.kind) << "light " << i;
    EXPECT_EQ(x.position, y.position) << "light " << i;
    EXPECT_EQ(x.direction, y.direction) << "light " << i;
    EXPECT_EQ(x.color, y.color) << "light " << i;
    EXPECT_EQ(x.intensity, y.intensity) << "light " << i;
    EXPECT_EQ(x.falloff, y.falloff) << "light " << i;
    EXPECT_EQ(x.range, y.range) << "light " << i;
    EXPECT_EQ(x.attenuation, y.attenuation) << "light " << i;
    EXPECT_EQ(x.inner_angle, y.inner_angle) << "light " << i;
    EXPECT_EQ(x.outer_angle, y.outer_angle) << "light " << i;
  }
  ASSERT_EQ(a.textures.size(), b.textures.size());
  for (size_t i = 0; i < a.textures.size(); ++i) {
    EXPECT_EQ(a.textures[i].width, b.textures[i].width) << "texture " << i;
    EXPECT_EQ(a.textures[i].height, b.textures[i].height) << "texture " << i;
    EXPECT_EQ(a.textures[i].srgb, b.textures[i].srgb) << "texture " << i;
    EXPECT_TRUE(a.textures[i].texels == b.textures[i].texels) << "texture " << i;
  }
  ASSERT_EQ(a.environment == nullptr, b.environment == nullptr);
  if (a.environment) {
    EXPECT_EQ(a.environment->radiance.width, b.environment->radiance.width);
    EXPECT_TRUE(a.environment->radiance.pixels == b.environment->radiance.pixels);
  }
}

}  // namespace tessera
