// Mirrored objects: a transform with a negative determinant reverses the winding of what it
// places, so its front faces are the clockwise ones (glTF 2.0), and its tangent frames change
// handedness. The expected images come from symmetry, never from Tessera's own output:
// - the cube is symmetric under x -> -x (and y, z), so mirroring it must not change the image;
// - an object placed by R * S * M (M an axis mirror) is the same surface as the mesh whose
//   vertices, normals and tangents are mirrored by M on the CPU, with its winding reversed,
//   placed by R * S. Both give bit-identical clip coordinates (M only negates a column, which
//   is exact), so the visibility buffers must be identical bit for bit. Shading reads the
//   triangle's corners in the opposite order, which changes float rounding only.
// The compute path, the hardware baseline and the reference renderer are each checked on
// their own against these expectations.
#include <cmath>
#include <iterator>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "compute/baselines/hardware_baseline.h"
#include "core/mesh.h"
#include "core/procedural_textures.h"
#include "core/reference_renderer.h"
#include "tests/test_scenes.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

class Mirroring : public test::VulkanTest {};

// Visibility value of an empty pixel (docs/architecture.md).
constexpr uint64_t kEmpty = ~uint64_t(0);

// What the compute path and the hardware baseline make of a scene with one renderer and its
// baseline (building pipelines once per culling mode keeps the test short on lavapipe).
struct Images {
  ImageF hdr, hardware_hdr;
  std::vector<uint64_t> visibility;
  uint64_t culled_backface = 0;
};
Images render_both(Renderer& renderer, HardwareBaseline& baseline, const Scene& scene, uint32_t w,
                   uint32_t h) {
  renderer.set_scene(scene);
  FrameSettings fs;
  fs.width = w;
  fs.height = h;
  Images out;
  out.culled_backface = renderer.render(fs).culled_backface;
  out.hdr = renderer.read_hdr();
  out.visibility = renderer.read_visibility();
  baseline.render(fs);
  out.hardware_hdr = renderer.read_hdr();
  return out;
}

RendererOptions culling(CullMode cull) {
  RendererOptions o;
  o.cull = cull;
  return o;
}

constexpr CullMode kCullModes[] = {CullMode::back, CullMode::front, CullMode::none};

const char* cull_name(CullMode c) {
  return c == CullMode::back ? "cull back" : c == CullMode::front ? "cull front" : "cull none";
}

// One object looked at from `eye` towards the origin, lit by one point light.
Scene lit_object(Mesh mesh, const glm::mat4& transform, glm::vec3 eye, float fov_degrees,
                 glm::vec3 light, float intensity) {
  Scene s;
  s.camera.position = eye;
  s.camera.target = {0.0f, 0.0f, 0.0f};
  s.camera.vertical_fov = glm::radians(fov_degrees);
  s.meshes.push_back(std::move(mesh));
  s.materials.push_back({});
  s.objects.push_back({0, 0, transform});
  Light l;
  l.position = light;
  l.intensity = intensity;
  s.lights.push_back(l);
  return s;
}

// The scene: the cube from -1 to 1, seen from (2.5, 1.8, 3.2), one point light.
Scene cube_scene(const glm::mat4& transform) {
  return lit_object(make_cube(), transform, {2.5f, 1.8f, 3.2f}, 40.0f, {3.0f, 4.0f, 2.0f}, 30.0f);
}

glm::mat4 axis_mirror(int axis) {
  glm::vec3 s(1.0f);
  s[axis] = -1.0f;
  return glm::scale(glm::mat4(1.0f), s);
}

// The same surface as `mesh` placed by `mirror`, as a mesh of its own: positions, normals and
// tangents mirrored (mirror is diagonal with entries +-1, so this is exact), winding reversed,
// and the tangents' handedness flipped (the mirrored frame's bitangent keeps its direction
// while cross(n, t) flips).
Mesh mirrored_mesh(const Mesh& mesh, const glm::mat4& mirror) {
  const glm::mat3 m(mirror);
  Mesh out = mesh;
  for (glm::vec3& p : out.positions) p = m * p;
  for (glm::vec3& n : out.normals) n = m * n;
  for (glm::vec4& t : out.tangents) t = glm::vec4(m * glm::vec3(t), -t.w);
  for (size_t i = 0; i < out.indices.size(); i += 3)
    std::swap(out.indices[i + 1], out.indices[i + 2]);
  return out;
}

// Pixels where one image is empty (background) and the other is not, from the visibility
// buffer (compute path) or from the reference's owners.
size_t mask_differences(const std::vector<uint64_t>& a, const std::vector<uint64_t>& b) {
  size_t n = 0;
  for (size_t i = 0; i < a.size(); ++i) n += (a[i] == kEmpty) != (b[i] == kEmpty);
  return n;
}

// Pixels of two HDR images that differ by more than `tolerance` times the larger value (plus
// 1e-5 for values near zero).
size_t hdr_differences(const ImageF& a, const ImageF& b, double tolerance) {
  size_t n = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const double x = a.pixels[i][c], y = b.pixels[i][c];
      if (std::abs(x - y) > tolerance * std::max(std::abs(x), std::abs(y)) + 1e-5) {
        ++n;
        break;
      }
    }
  }
  return n;
}

// The compute path and the baseline store HDR in fp16 (steps of 2^-11 to 2^-10 relative), and
// rounding of shading inputs (the triangle's corners read in another order, the normal matrix
// inverted from another matrix, a texture footprint) can move a value across a step or two:
// up to 1e-3 relative was seen. An inside-out image differs by 100 %.
constexpr double kHalfTolerance = 4e-3;
// The reference shades in double and stores floats.
constexpr double kReferenceTolerance = 1e-6;

ReferenceFrame reference(const Scene& scene, uint32_t w, uint32_t h, CullMode cull) {
  ReferenceSettings rs;
  rs.frame.width = w;
  rs.frame.height = h;
  rs.cull = cull;
  return render_reference(scene, rs);
}

size_t owner_mask_differences(const ReferenceFrame& a, const ReferenceFrame& b) {
  size_t n = 0;
  for (size_t i = 0; i < a.owner.size(); ++i)
    n += (a.owner[i] == kNoTriangle) != (b.owner[i] == kNoTriangle);
  return n;
}

TEST_F(Mirroring, MirroredCubeLooksLikeTheCubeOnEveryPathAndAxis) {
  const uint32_t w = 96, h = 96;
  for (CullMode cull : kCullModes) {
    Renderer renderer(context(), culling(cull));
    HardwareBaseline baseline(renderer);
    for (int axis = 0; axis < 3; ++axis) {
      const std::string what = "mirror axis " + std::to_string(axis) + ", " + cull_name(cull);
      const Scene plain = cube_scene(glm::mat4(1.0f));
      const Scene mirrored = cube_scene(axis_mirror(axis));
      const Images a = render_both(renderer, baseline, plain, w, h);
      const Images b = render_both(renderer, baseline, mirrored, w, h);
      // Seen from outside on every axis, the cube shows 3 faces (6 triangles): culling keeps
      // those (back), the 6 others (front), or all 12 (none).
      const uint64_t culled = cull == CullMode::none ? 0 : 6;
      EXPECT_EQ(a.culled_backface, culled) << what;
      EXPECT_EQ(b.culled_backface, culled) << what;
      EXPECT_EQ(mask_differences(a.visibility, b.visibility), 0u) << what;
      EXPECT_EQ(hdr_differences(a.hdr, b.hdr, kHalfTolerance), 0u) << what;
      EXPECT_EQ(hdr_differences(a.hardware_hdr, b.hardware_hdr, kHalfTolerance), 0u)
          << what << ", hardware";

      const ReferenceFrame ra = reference(plain, w, h, cull);
      const ReferenceFrame rb = reference(mirrored, w, h, cull);
      EXPECT_EQ(owner_mask_differences(ra, rb), 0u) << what << ", reference";
      EXPECT_EQ(hdr_differences(ra.hdr, rb.hdr, kReferenceTolerance), 0u) << what << ", reference";
    }
  }
}

// A non-symmetric closed mesh placed by rotation * non-uniform scale * mirror, against the
// CPU-mirrored mesh placed by rotation * scale: the same surface, the same triangle ids.
Scene bumpy_scene(const Mesh& mesh, const glm::mat4& transform) {
  Scene s = lit_object(mesh, transform, {0.4f, 0.9f, 3.6f}, 45.0f, {2.0f, 3.0f, 2.5f}, 40.0f);
  s.materials[0].roughness = 0.4f;
  return s;
}

TEST_F(Mirroring, MirrorWithRotationAndScaleMatchesTheMirroredMesh) {
  const uint32_t w = 80, h = 64;
  const Mesh mesh = test::bumpy_sphere(2, 0.25f, 7);
  const glm::mat4 rs =
      glm::scale(glm::rotate(glm::mat4(1.0f), 0.7f, glm::normalize(glm::vec3(1.0f, 2.0f, 0.5f))),
                 {1.3f, 0.8f, 1.1f});
  // Mirrors about one axis and the point reflection (det -1), and a half turn written as two
  // mirrors (det +1, nothing to flip) as a control.
  const std::pair<const char*, glm::vec3> mirrors[] = {{"x", {-1, 1, 1}},
                                                       {"y", {1, -1, 1}},
                                                       {"z", {1, 1, -1}},
                                                       {"xyz", {-1, -1, -1}},
                                                       {"xy (half turn)", {-1, -1, 1}}};
  // One renderer and baseline per culling mode, for every mirror.
  std::vector<std::unique_ptr<Renderer>> renderers;
  std::vector<std::unique_ptr<HardwareBaseline>> baselines;
  for (CullMode cull : kCullModes) {
    renderers.push_back(std::make_unique<Renderer>(context(), culling(cull)));
    baselines.push_back(std::make_unique<HardwareBaseline>(*renderers.back()));
  }
  for (const auto& [name, diagonal] : mirrors) {
    const glm::mat4 m = glm::scale(glm::mat4(1.0f), diagonal);
    const bool det_negative = diagonal.x * diagonal.y * diagonal.z < 0.0f;
    EXPECT_EQ(is_mirroring(rs * m), det_negative) << name;
    // A mesh without the mirror, placed without it, must not be taken for its mirror image.
    const Mesh reversed = det_negative ? mirrored_mesh(mesh, m) : mesh;
    const Scene a = bumpy_scene(mesh, rs * m);
    const Scene b = bumpy_scene(reversed, det_negative ? rs : rs * m);
    for (size_t c = 0; c < std::size(kCullModes); ++c) {
      const CullMode cull = kCullModes[c];
      const std::string what = std::string("mirror ") + name + ", " + cull_name(cull);
      const Images fa = render_both(*renderers[c], *baselines[c], a, w, h);
      const Images fb = render_both(*renderers[c], *baselines[c], b, w, h);
      EXPECT_EQ(fa.visibility, fb.visibility) << what;
      EXPECT_EQ(fa.culled_backface, fb.culled_backface) << what;
      EXPECT_EQ(hdr_differences(fa.hdr, fb.hdr, kHalfTolerance), 0u) << what;
      EXPECT_EQ(hdr_differences(fa.hardware_hdr, fb.hardware_hdr, kHalfTolerance), 0u)
          << what << ", hardware";
      size_t covered = 0;
      for (uint64_t v : fa.visibility) covered += v != kEmpty;
      EXPECT_GT(covered, 800u) << what;

      const ReferenceFrame ra = reference(a, w, h, cull);
      const ReferenceFrame rb = reference(b, w, h, cull);
      EXPECT_EQ(ra.owner, rb.owner) << what << ", reference";
      EXPECT_EQ(ra.coverage, rb.coverage) << what << ", reference";
      EXPECT_EQ(hdr_differences(ra.hdr, rb.hdr, kReferenceTolerance), 0u) << what << ", reference";
    }
  }
}

// Two mirrored copies of one mesh and an unmirrored one in one scene: the hardware baseline
// draws them instanced, so mirrored and unmirrored instances of a mesh must not share a draw
// with one front face. Compared against the same scene built from CPU-mirrored meshes.
TEST_F(Mirroring, MixedInstancesOfOneMesh) {
  const uint32_t w = 96, h = 64;
  const Mesh mesh = test::bumpy_sphere(2, 0.3f, 3);
  const glm::mat4 mx = axis_mirror(0);
  const glm::mat4 places[3] = {glm::translate(glm::mat4(1.0f), {-1.6f, 0.0f, 0.0f}),
                               glm::translate(glm::mat4(1.0f), {0.0f, 0.2f, 0.0f}),
                               glm::translate(glm::mat4(1.0f), {1.6f, -0.1f, 0.0f})};
  Scene a = bumpy_scene(mesh, places[0] * mx);
  a.camera.position = {0.0f, 1.0f, 6.0f};
  a.objects.push_back({0, 0, places[1]});
  a.objects.push_back({0, 0, places[2] * mx});
  Scene b = a;
  b.meshes.push_back(mirrored_mesh(mesh, mx));
  b.objects = {{1, 0, places[0]}, {0, 0, places[1]}, {1, 0, places[2]}};
  for (CullMode cull : kCullModes) {
    Renderer renderer(context(), culling(cull));
    HardwareBaseline baseline(renderer);
    const Images fa = render_both(renderer, baseline, a, w, h);
    const Images fb = render_both(renderer, baseline, b, w, h);
    EXPECT_EQ(mask_differences(fa.visibility, fb.visibility), 0u) << cull_name(cull);
    EXPECT_EQ(hdr_differences(fa.hdr, fb.hdr, kHalfTolerance), 0u) << cull_name(cull);
    EXPECT_EQ(hdr_differences(fa.hardware_hdr, fb.hardware_hdr, kHalfTolerance), 0u)
        << cull_name(cull) << ", hardware";
  }
}

// A normal-mapped plane seen at an angle, mirrored with a rotation: the tangent frame's
// handedness must flip with the determinant, or the map's slopes along v are inverted. The
// comparison mesh has no tangents, so Tessera generates them from its own (mirrored) uvs and
// positions, independently of the mirrored transform.
TEST_F(Mirroring, NormalMapsOfMirroredObjectsKeepTheirRelief) {
  const uint32_t w = 96, h = 96;
  const TileMaps maps = make_tile_maps(64, 4, {0.8f, 0.7f, 0.6f}, 3.0f);
  const glm::mat4 r = glm::rotate(glm::mat4(1.0f), -1.0f, glm::vec3(1.0f, 0.0f, 0.0f));
  // Mirrors about x and y flip the tangent and the bitangent respectively; a mirror about z
  // would only turn this plane (at z = 0) away from the camera.
  Renderer renderer(context(), culling(CullMode::back));
  HardwareBaseline baseline(renderer);
  for (int axis = 0; axis < 2; ++axis) {
    const glm::mat4 m = axis_mirror(axis);
    auto scene = [&](const Mesh& mesh, const glm::mat4& transform) {
      Scene s = bumpy_scene(mesh, transform);
      s.camera.position = {0.3f, 0.2f, 3.0f};
      s.textures = {maps.base_color, maps.normal};
      s.materials[0].base_color_map = 0;
      s.materials[0].normal_map = 1;
      s.materials[0].roughness = 0.35f;
      s.lights[0].position = {-1.0f, 2.5f, 1.5f};
      return s;
    };
    Mesh plane = make_plane(4, 4);
    plane.tangents.clear();
    const Scene a = scene(plane, r * m);
    const Mesh cpu = mirrored_mesh(plane, m);
    const Scene b = scene(cpu, r);
    const std::string what = "mirror axis " + std::to_string(axis);
    const Images fa = render_both(renderer, baseline, a, w, h);
    const Images fb = render_both(renderer, baseline, b, w, h);
    size_t covered = 0;
    for (uint64_t v : fa.visibility) covered += v != kEmpty;
    EXPECT_GT(covered, 1500u) << what;
    EXPECT_EQ(mask_differences(fa.visibility, fb.visibility), 0u) << what;
    EXPECT_EQ(hdr_differences(fa.hdr, fb.hdr, kHalfTolerance), 0u) << what;
    EXPECT_EQ(hdr_differences(fa.hardware_hdr, fb.hardware_hdr, kHalfTolerance), 0u)
        << what << ", hardware";
    const ReferenceFrame ra = reference(a, w, h, CullMode::back);
    const ReferenceFrame rb = reference(b, w, h, CullMode::back);
    EXPECT_EQ(owner_mask_differences(ra, rb), 0u) << what << ", reference";
    EXPECT_EQ(hdr_differences(ra.hdr, rb.hdr, kReferenceTolerance), 0u) << what << ", reference";
  }
}

}  // namespace
}  // namespace tessera
