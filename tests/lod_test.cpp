// Level of detail (core/lod.h, shaders/lod*.comp): chord errors and chosen levels against hand
// computations, the GPU's choice against the double-precision one, determinism, silhouettes
// against analytic spheres, the triangle count at many objects, and popping at a switch.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "compute/readback.h"
#include "compute/renderer_internal.h"
#include "core/bench_scenes.h"
#include "core/builtin_scenes.h"
#include "core/image_metrics.h"
#include "core/lod.h"
#include "core/mesh.h"
#include "core/reference_renderer.h"
#include "tests/support/image_assertions.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

constexpr double kPi = std::numbers::pi;

class Lod : public test::VulkanTest {};

// Chord error of make_uv_sphere(s, s / 2) by hand (core/lod.cpp has the derivation): the
// nearest facet plane is that of the ring of stacks nearest the equator. With s / 2 odd that
// ring is centred on it and the distance is cos^2(pi/s); with s / 2 even it is centred at
// pi/2 - pi/s, where cos m = sin(pi/s): cos^2(pi/s) / sqrt(1 - sin^4(pi/s)).
double hand_chord_error(uint32_t s) {
  const double c = std::cos(kPi / s), sn = std::sin(kPi / s);
  return (s / 2) % 2 == 1 ? 1.0 - c * c : 1.0 - c * c / std::sqrt(1.0 - sn * sn * sn * sn);
}

// 1 - the smallest distance from the centre to a facet's plane, measured on the mesh.
double measured_chord_error(const Mesh& m) {
  double nearest = 1.0;
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    const glm::dvec3 a(m.positions[m.indices[3 * t]]), b(m.positions[m.indices[3 * t + 1]]),
        c(m.positions[m.indices[3 * t + 2]]);
    const glm::dvec3 n = glm::cross(b - a, c - a);
    if (glm::length(n) == 0.0) continue;
    nearest = std::min(nearest, std::abs(glm::dot(a, glm::normalize(n))));
  }
  return 1.0 - nearest;
}

TEST(LodChain, UvSphereChordErrorIsTheHandDerivedOneAndTheMeshes) {
  for (uint32_t s : kSphereLodSegments) {
    const double formula = uv_sphere_chord_error(s, s / 2);
    EXPECT_NEAR(formula, hand_chord_error(s), 1e-12) << s;
    // Float vertices: the planes move by ~1e-7.
    EXPECT_NEAR(measured_chord_error(make_uv_sphere(s, s / 2)), formula, 2e-6) << s;
    // (1 + cos(pi / s)) times the sagitta of the outline seen along the equator,
    // r (1 - cos(pi / s)), for odd s / 2: about twice it for fine spheres.
    if (s >= 12) {
      EXPECT_GT(formula, 1.9 * (1.0 - std::cos(kPi / s))) << s;
    }
  }
  // Other ring counts too: the formula is not only for rings = segments / 2.
  EXPECT_NEAR(measured_chord_error(make_uv_sphere(12, 5)), uv_sphere_chord_error(12, 5), 2e-6);
  EXPECT_NEAR(uv_sphere_chord_error(12, 5), 1.0 - std::cos(kPi / 12) * std::cos(kPi / 10), 1e-12);
}

TEST(LodChain, SphereChainKeepsTheBaseMeshAndOrdersTheLevels) {
  const Mesh base = make_uv_sphere(32, 16);
  const LodChain chain = build_lod_chain(base);
  ASSERT_EQ(chain.levels.size(), std::size(kSphereLodSegments));
  EXPECT_TRUE(chain.levels[chain.base_level].is_base);
  EXPECT_EQ(*chain.levels[chain.base_level].mesh, base);
  for (size_t l = 1; l < chain.levels.size(); ++l) {
    EXPECT_GT(chain.levels[l].error, chain.levels[l - 1].error);
    EXPECT_LT(chain.levels[l].mesh->triangle_count(), chain.levels[l - 1].mesh->triangle_count());
    EXPECT_TRUE(chain.levels[l].mesh->analytic_sphere.has_value());
  }
  EXPECT_EQ(chain.levels.back().mesh->triangle_count(), 8u);  // 4 segments
  EXPECT_EQ(chain.levels.front().mesh->triangle_count(), 2u * 256 * 127);
}

TEST(LodChain, MeshoptimizerChainHalvesTheTrianglesWithGrowingError) {
  // A plane of 64 x 64 quads bent into a wave, so simplifying it costs some error.
  Mesh m = make_plane(64, 64);
  for (glm::vec3& p : m.positions) p.z = 0.2f * std::sin(3.0f * p.x) * std::cos(2.0f * p.y);
  const LodChain chain = build_lod_chain(m);
  ASSERT_GE(chain.levels.size(), 4u);
  EXPECT_TRUE(chain.levels[0].is_base);
  EXPECT_EQ(chain.levels[0].error, 0.0);
  for (size_t l = 1; l < chain.levels.size(); ++l) {
    EXPECT_TRUE(chain.levels[l].shares_base_vertices);
    EXPECT_GE(chain.levels[l].error, chain.levels[l - 1].error);
    EXPECT_LE(chain.levels[l].mesh->triangle_count() * 10,
              chain.levels[l - 1].mesh->triangle_count() * 9);
  }
  EXPECT_GT(chain.levels.back().error, 0.0);
  // The bounding sphere holds every vertex.
  for (const glm::vec3& p : m.positions)
    EXPECT_LE(glm::length(glm::dvec3(p) - chain.centre), chain.radius * (1 + 1e-12));
}

// A unit uv sphere (32 segments) at `distance` along the view axis, 512 x 512, 45 degrees.
Scene sphere_at(float distance) {
  Scene s;
  s.camera.position = {0.0f, 0.0f, distance};
  s.camera.near_plane = 0.05f;
  s.meshes.push_back(make_uv_sphere(32, 16));
  s.materials.push_back(Material{});
  s.objects.push_back({0, 0, glm::mat4(1.0f)});
  s.lights.push_back(Light{.position = {3.0f, 4.0f, distance}, .intensity = 20.0f});
  return s;
}

// The triangles of the coarsest sphere of kSphereLodSegments whose hand-computed chord error,
// seen at view depth `near_side` under the 45-degree 512 x 512 camera, is at most `bound` px;
// `margin` is how far (relative) the nearest level is from its bound.
uint32_t hand_chosen_triangles(double near_side, double bound, double* margin) {
  const double t = std::tan(kPi / 8.0);
  const double k = 256.0 / t * std::sqrt(1.0 + 2.0 * t * t);  // aspect 1
  uint32_t chosen = 256;
  *margin = 1.0;
  for (uint32_t s : kSphereLodSegments) {
    const double px = hand_chord_error(s) * k / near_side;
    *margin = std::min(*margin, std::abs(px / bound - 1.0));
    if (px <= bound) chosen = std::min(chosen, s);
  }
  return 2 * chosen * (chosen / 2 - 1);
}

TEST_F(Lod, ChosenLevelMatchesHandComputationOnCpuAndGpu) {
  Renderer renderer(context());
  FrameSettings fs;
  fs.lod = tessera::Lod::automatic;
  for (float distance : {2.5f, 6.0f, 15.0f, 50.0f, 180.0f, 2000.0f}) {
    const Scene scene = sphere_at(distance);
    double margin = 0.0;
    const uint32_t expected = hand_chosen_triangles(distance - 1.0, 0.5, &margin);
    ASSERT_GT(margin, 1e-4) << "distance " << distance << " is too near a level's switch";
    const LodChain chain = build_lod_chain(scene.meshes[0]);
    const uint32_t level =
        select_lod_level(chain, glm::mat4(1.0f), scene.camera, fs.width, fs.height, 0.5);
    EXPECT_EQ(chain.levels[level].mesh->triangle_count(), expected) << "distance " << distance;
    renderer.set_scene(scene);
    const FrameStats stats = renderer.render(fs);
    EXPECT_EQ(stats.triangles_submitted, expected) << "distance " << distance;
    EXPECT_EQ(stats.triangles_without_lod, 960u);
    // A level finer than the scene's own mesh (up to 65,024 triangles against 960) still fits
    // one batch: batches are sized for the levels, not for the mesh (each batch is a whole
    // sequence of passes; the H200 took 1.56 ms for one sphere in 17 batches against 0.17 ms).
    EXPECT_EQ(stats.batches, 1u) << "distance " << distance;
  }
  // Far away: the 4-segment octahedron (8 triangles) is within half a pixel.
  double margin = 0.0;
  EXPECT_EQ(hand_chosen_triangles(1999.0, 0.5, &margin), 8u);
}

// A scene with more triangles, then a smaller one: the second scene's batches are sized for its
// own levels, not for the first scene's (the H200's grid sweep measured one sphere at 1.55 ms in
// 17 batches after a million spheres, against 0.22 ms in one batch before them).
TEST_F(Lod, BatchesOfANewSceneAreSizedForItsOwnLevels) {
  Renderer renderer(context());
  FrameSettings fs;
  fs.lod = tessera::Lod::automatic;
  double margin = 0.0;
  Scene many = sphere_at(2.5f);
  for (int i = 0; i < 7; ++i) many.objects.push_back(many.objects[0]);
  renderer.set_scene(many);
  EXPECT_EQ(renderer.render(fs).triangles_submitted, 8u * hand_chosen_triangles(1.5, 0.5, &margin));
  const uint32_t level = hand_chosen_triangles(5.0, 0.5, &margin);
  ASSERT_GT(level, 960u);  // finer than the mesh: batches sized by the mesh would be several
  renderer.set_scene(sphere_at(6.0f));
  for (int frame = 0; frame < 2; ++frame) {
    const FrameStats stats = renderer.render(fs);
    EXPECT_EQ(stats.triangles_submitted, level) << "frame " << frame;
    EXPECT_EQ(stats.batches, 1u) << "frame " << frame;
  }
}

std::vector<uint32_t> gpu_object_triangles(Renderer& r, size_t objects) {
  const std::vector<gpu::GpuObject> o = download_buffer<gpu::GpuObject>(
      RendererInternal::context(r), RendererInternal::buffer(r, TS_BINDING_OBJECTS), objects);
  std::vector<uint32_t> out;
  for (const gpu::GpuObject& g : o) out.push_back(g.triangle_count);
  return out;
}

using tessera::testing::same_bits;

TEST_F(Lod, GpuChoiceIsTheCpuChoiceAndDeterministic) {
  // The grid family at 400 objects plus spheres scattered in depth, some scaled unevenly.
  Scene scene = make_bench_scene("grid", 400, 32, 4.0f / 3.0f);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (int i = 0; i < 200; ++i) {
    glm::mat4 t = glm::translate(glm::mat4(1.0f), glm::vec3(u(rng) * 20, u(rng) * 12, u(rng) * 30));
    t = glm::scale(t, glm::vec3(1.0f + 0.5f * u(rng), 1.0f, 1.0f + 0.3f * u(rng)));
    scene.objects.push_back({0, uint32_t(i % scene.materials.size()), t});
  }
  FrameSettings fs;
  fs.width = 320;
  fs.height = 240;
  fs.lod = tessera::Lod::automatic;
  Renderer renderer(context());
  renderer.set_scene(scene);
  const FrameStats stats = renderer.render(fs);
  const ImageF hdr = renderer.read_hdr();
  const std::vector<uint64_t> vis = renderer.read_visibility();
  const std::vector<uint32_t> gpu = gpu_object_triangles(renderer, scene.objects.size());

  const std::vector<LodChain> chains = build_lod_chains(scene);
  const ObjectNumbering numbering = number_objects(scene);
  size_t differ = 0;
  uint64_t cpu_total = 0;
  for (size_t slot = 0; slot < numbering.objects.size(); ++slot) {
    const Object& o = scene.objects[numbering.objects[slot]];
    const uint32_t l = select_lod_level(chains[o.mesh], o.transform, scene.camera, fs.width,
                                        fs.height, fs.lod_error_px);
    const uint32_t t = uint32_t(chains[o.mesh].levels[l].mesh->triangle_count());
    cpu_total += t;
    differ += t != gpu[slot];
  }
  // Float against double can differ only where a level's error is within rounding of the
  // bound; none of these 600 objects is.
  EXPECT_EQ(differ, 0u);
  EXPECT_EQ(stats.triangles_submitted, cpu_total);
  EXPECT_EQ(cpu_total, lod_triangle_count(scene, chains, fs));
  EXPECT_LT(cpu_total, stats.triangles_without_lod);

  // Same bits again, and with the objects submitted in other orders.
  renderer.render(fs);
  EXPECT_TRUE(same_bits(hdr, renderer.read_hdr()));
  EXPECT_EQ(vis, renderer.read_visibility());
  std::mt19937 shuffle_rng(11);
  for (int round = 0; round < 2; ++round) {
    Scene shuffled = scene;
    std::shuffle(shuffled.objects.begin(), shuffled.objects.end(), shuffle_rng);
    renderer.set_scene(shuffled);
    renderer.render(fs);
    EXPECT_TRUE(same_bits(hdr, renderer.read_hdr())) << "round " << round;
    EXPECT_EQ(vis, renderer.read_visibility()) << "round " << round;
  }
}

TEST_F(Lod, OffAfterAutoRendersAsWithoutLevelsOfDetail) {
  const Scene scene = make_sphere_grid_scene();
  FrameSettings fs;
  fs.width = 160;
  fs.height = 120;
  Renderer plain(context());
  plain.set_scene(scene);
  plain.render(fs);
  Renderer mixed(context());
  mixed.set_scene(scene);
  fs.lod = tessera::Lod::automatic;
  const FrameStats with_lod = mixed.render(fs);
  EXPECT_LT(with_lod.triangles_submitted, with_lod.triangles_without_lod);
  // Picking follows the levels the frame chose.
  const std::vector<uint64_t> vis = mixed.read_visibility();
  const ObjectNumbering numbering = number_objects(scene);
  const uint64_t centre = vis[60 * 160 + 80];
  ASSERT_NE(centre, ~0ull);
  const uint32_t picked = mixed.object_of_triangle(uint32_t(centre));
  fs.lod = tessera::Lod::off;
  const FrameStats without = mixed.render(fs);
  EXPECT_EQ(without.triangles_submitted, without.triangles_without_lod);
  EXPECT_TRUE(same_bits(plain.read_hdr(), mixed.read_hdr()));
  EXPECT_EQ(plain.read_visibility(), mixed.read_visibility());
  EXPECT_EQ(picked, mixed.object_of_triangle(uint32_t(mixed.read_visibility()[60 * 160 + 80])));
  (void)numbering;
}

// The sphere grid under --lod auto at `fs` on the GPU and in the reference.
struct AgainstReference {
  FrameStats stats;
  ReferenceFrame ref;
  size_t entries = 0;  // visibility entries: pixels times samples
  size_t differ = 0;   // entries whose triangle differs from the reference's
};

AgainstReference render_against_reference(Context& ctx, FrameSettings fs) {
  const Scene scene = make_sphere_grid_scene();
  fs.lod = tessera::Lod::automatic;
  Renderer renderer(ctx);
  renderer.set_scene(scene);
  AgainstReference a;
  a.stats = renderer.render(fs);
  const std::vector<uint64_t> vis = renderer.read_visibility();
  ReferenceSettings rs;
  rs.frame = fs;
  rs.threads = 2;
  a.ref = render_reference(scene, rs);
  // One sample: the owner per pixel; more: every sample's triangle.
  const std::vector<uint32_t>& ids = fs.samples == 1 ? a.ref.owner : a.ref.sample_ids;
  EXPECT_EQ(ids.size(), vis.size());
  a.entries = std::min(ids.size(), vis.size());
  for (size_t i = 0; i < a.entries; ++i) {
    const uint32_t id = vis[i] == ~0ull ? kNoTriangle : uint32_t(vis[i]);
    a.differ += id != ids[i];
  }
  return a;
}

TEST_F(Lod, GpuMatchesTheReferenceWithTheSameLevels) {
  FrameSettings fs;
  fs.width = 200;
  fs.height = 200;
  const AgainstReference a = render_against_reference(context(), fs);
  // Snapping in float against double moves a sample's owner only where it lies within a
  // sub-pixel step of an edge (docs/accuracy.md): a few pixels in 40,000.
  EXPECT_LT(a.differ, a.entries / 500) << a.differ << " pixels differ";
  EXPECT_LT(a.ref.numbering.triangle_count,
            number_objects(make_sphere_grid_scene()).triangle_count);
}

TEST_F(Lod, AntiAliasedFramesMatchTheReferenceSampleBySample) {
  // With more than one sample per pixel setup's level-of-detail variant is a pipeline built on
  // first use (sampled_pipeline); without TS_SPEC_LOD it would read the batch's count without
  // level of detail and set up triangles past the GPU's total.
  FrameSettings fs;
  fs.width = 96;
  fs.height = 96;
  fs.samples = 4;
  const AgainstReference a = render_against_reference(context(), fs);
  fs.lod = tessera::Lod::automatic;
  const Scene scene = make_sphere_grid_scene();
  EXPECT_EQ(a.stats.triangles_submitted, lod_triangle_count(scene, build_lod_chains(scene), fs));
  EXPECT_LT(a.stats.triangles_submitted, a.stats.triangles_without_lod);
  // As without anti-aliasing: float and double snapping differ only within a sub-pixel step
  // of an edge (docs/accuracy.md).
  EXPECT_LE(a.differ, a.entries / 1000) << a.differ << " of " << a.entries << " samples differ";
}

// The silhouette error of the levels chosen at 0.5 px against analytic spheres, both through
// the reference with 4 x 4 samples per pixel (so that what is measured is the geometry, not
// the single sample of the compute path).
double lod_silhouette_error(const Scene& scene, uint32_t w, uint32_t h) {
  ReferenceSettings rs;
  rs.frame.width = w;
  rs.frame.height = h;
  rs.frame.lod = tessera::Lod::automatic;
  rs.threads = 2;
  rs.ground_truth.supersampling = 4;
  const ReferenceFrame tess = render_reference(scene, rs);
  rs.ground_truth.analytic_spheres = true;
  const ReferenceFrame truth = render_reference(scene, rs);
  return silhouette_error(tess.ownership, truth.ownership).mean_px;
}

TEST(LodSilhouette, DefaultSceneAndGridFamilyStayWithinHalfAPixel) {
  const double spheres = lod_silhouette_error(make_sphere_grid_scene(), 512, 512);
  std::printf("LOD silhouette: spheres scene 512x512 %.4f px\n", spheres);
  EXPECT_LE(spheres, 0.5);
  // The grid family at 1920 x 1080 with N objects has spheres of the same size in pixels as at
  // 192 x 108 with N / 100: N = 100 ... 10^6 there are N = 1 ... 10^4 here.
  for (uint32_t n : {1u, 100u, 10000u}) {
    const double e = lod_silhouette_error(make_bench_scene("grid", n, 32, 16.0f / 9.0f), 192, 108);
    std::printf("LOD silhouette: grid %u objects 192x108 %.4f px\n", n, e);
    EXPECT_LE(e, 0.5) << n << " objects";
  }
}

TEST(LodTriangles, GridOfAMillionSpheresFallsTwentyfold) {
  const Scene scene = make_bench_scene("grid", 1000000, 32, 16.0f / 9.0f);
  FrameSettings fs;
  fs.width = 1920;
  fs.height = 1080;
  const uint64_t without = lod_triangle_count(scene, {}, fs);
  fs.lod = tessera::Lod::automatic;
  const uint64_t with = lod_triangle_count(scene, build_lod_chains(scene), fs);
  std::printf("LOD triangles: grid 10^6 at 1920x1080: %llu -> %llu (%.1fx)\n",
              (unsigned long long)without, (unsigned long long)with, double(without) / with);
  EXPECT_EQ(without, 960000000u);
  EXPECT_GE(double(without) / double(with), 20.0);
}

TEST_F(Lod, TriangleCountFallsOnTheGpuAtManyObjects) {
  const Scene scene = make_bench_scene("grid", 10000, 32, 1.0f);
  FrameSettings fs;
  fs.width = fs.height = 512;
  fs.lod = tessera::Lod::automatic;
  Renderer renderer(context());
  renderer.set_scene(scene);
  const FrameStats s = renderer.render(fs);
  std::printf("LOD triangles: grid 10^4 at 512x512 on the GPU: %llu -> %llu (%.1fx)\n",
              (unsigned long long)s.triangles_without_lod,
              (unsigned long long)s.triangles_submitted,
              double(s.triangles_without_lod) / double(s.triangles_submitted));
  EXPECT_EQ(s.triangles_submitted, lod_triangle_count(scene, build_lod_chains(scene), fs));
  EXPECT_GE(double(s.triangles_without_lod) / double(s.triangles_submitted), 10.0);
}

// Popping: a camera moving slowly away from one sphere across the distance where the level
// switches. Both levels are within 0.5 px of the true sphere, so the outline moves by at most
// 1 px at the switch (plus the motion of one step), and only pixels within that band of the
// outline can change owner.
TEST_F(Lod, PoppingAtALevelSwitchStaysWithinTheBound) {
  const uint32_t size = 256;
  const double t = std::tan(kPi / 8.0), k = 128.0 / t * std::sqrt(1.0 + 2.0 * t * t);
  // The switch from 32 to 24 segments: where hand_chord_error(24) * k / (d - 1) = 0.5.
  const double switch_distance = 1.0 + hand_chord_error(24) * k / 0.5;
  FrameSettings fs;
  fs.width = fs.height = size;
  fs.lod = tessera::Lod::automatic;
  Renderer renderer(context());
  std::vector<uint64_t> previous;
  Image8 previous_ldr;
  uint64_t previous_triangles = 0;
  bool switched = false;
  const double step = 0.0005 * switch_distance;  // the sphere shrinks by 0.05 % a frame
  for (int frame = -3; frame <= 3; ++frame) {
    const float distance = float(switch_distance + (frame - 0.5) * step);
    Scene scene = sphere_at(distance);
    renderer.set_scene(scene);
    const FrameStats stats = renderer.render(fs);
    const std::vector<uint64_t> vis = renderer.read_visibility();
    const Image8 ldr = renderer.read_ldr();
    if (!previous.empty()) {
      size_t flips = 0;
      for (size_t i = 0; i < vis.size(); ++i) flips += (vis[i] == ~0ull) != (previous[i] == ~0ull);
      const ImageDifference d = compare_images(ldr, previous_ldr, 8.0);
      const double radius_px = (size / 2.0) / t / std::sqrt(double(distance) * distance - 1.0);
      const double outline = 2.0 * kPi * radius_px;
      const bool at_switch = stats.triangles_submitted != previous_triangles;
      switched |= at_switch;
      std::printf(
          "LOD popping: frame %d, %.3f m, %llu triangles, radius %.2f px: %zu pixels changed "
          "owner (outline %.0f px), 8-bit RMSE %.3f, max %.0f levels, %zu pixels over 8%s\n",
          frame, distance, (unsigned long long)stats.triangles_submitted, radius_px, flips, outline,
          d.rmse, d.max_abs_error, d.pixels_over, at_switch ? "  <- switch" : "");
      // The band of pixel centres the outline sweeps: at most 1 px + the step's motion wide.
      const double motion = radius_px * step / distance;
      EXPECT_LE(double(flips), outline * (1.0 + motion) + 4.0) << "frame " << frame;
    }
    previous = vis;
    previous_ldr = ldr;
    previous_triangles = stats.triangles_submitted;
  }
  EXPECT_TRUE(switched);
}

}  // namespace
}  // namespace tessera
