// Anti-aliasing (FrameSettings::samples): the same bits whatever the order, agreement with the
// reference at the same sample positions, the edge error against the supersampled truth, and
// where it fails: triangles smaller than a pixel.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <random>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "compute/baselines/hardware_baseline.h"
#include "core/bench_scenes.h"
#include "core/builtin_scenes.h"
#include "core/image_metrics.h"
#include "core/mesh.h"
#include "core/pixel_coverage.h"
#include "core/reference_renderer.h"
#include "tests/support/image_assertions.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

class AntiAliasing : public test::VulkanTest {
 protected:
  Frame render_at(const Scene& scene, uint32_t size, uint32_t samples,
                  RendererOptions options = {}) {
    return render(scene, size, size, options, samples);
  }
  Frame render_with(const Scene& scene, uint32_t size, uint32_t samples, AaCoverage coverage,
                    uint32_t silhouette_steps = 0) {
    Renderer renderer(context());
    FrameSettings fs;
    fs.width = fs.height = size;
    fs.samples = samples;
    fs.aa_coverage = coverage;
    fs.silhouette_steps = silhouette_steps;
    return render(renderer, scene, fs);
  }
};

using tessera::testing::same_bits;

std::vector<uint32_t> ids_of(const std::vector<uint64_t>& keys) {
  std::vector<uint32_t> ids(keys.size());
  for (size_t i = 0; i < keys.size(); ++i) ids[i] = uint32_t(keys[i] & 0xFFFFFFFFu);
  return ids;
}

// The default scene with overlapping copies and cubes big enough for the per-tile rasterizer,
// so that depth ties, both raster paths and pixels shared by several triangles all occur.
Scene crowded_scene() {
  Scene s = make_sphere_grid_scene();
  const size_t n = s.objects.size();
  for (size_t i = 0; i < n; i += 3) {
    Object o = s.objects[i];
    o.transform[3] += glm::vec4(0.3f, 0.2f, 0.1f, 0.0f);
    s.objects.push_back(o);
  }
  for (size_t i = 0; i < 5; ++i) s.objects.push_back(s.objects[i * 4]);  // exact duplicates
  s.meshes.push_back(make_cube());
  glm::mat4 t = glm::translate(glm::mat4(1.0f), glm::vec3(1.0f, 0.5f, 0.5f));
  t = glm::rotate(t, 0.6f, glm::normalize(glm::vec3(1.0f, 2.0f, 0.5f)));
  s.objects.push_back({uint32_t(s.meshes.size() - 1), 2, glm::scale(t, glm::vec3(1.8f))});
  return s;
}

TEST_F(AntiAliasing, SameBitsAcrossRunsObjectOrderAndRasterPaths) {
  Scene scene = crowded_scene();
  for (uint32_t samples : {4u, 16u}) {
    const Frame first = render_at(scene, 96, samples);
    ASSERT_EQ(first.visibility.size(), 96u * 96u * samples);
    const Frame again = render_at(scene, 96, samples);
    EXPECT_TRUE(same_bits(first.hdr, again.hdr)) << samples << " samples";
    EXPECT_EQ(first.visibility, again.visibility);

    Scene shuffled = scene;
    std::mt19937 rng(samples);
    std::shuffle(shuffled.objects.begin(), shuffled.objects.end(), rng);
    const Frame reordered = render_at(shuffled, 96, samples);
    EXPECT_TRUE(same_bits(first.hdr, reordered.hdr)) << samples << " samples, shuffled";
    EXPECT_EQ(first.visibility, reordered.visibility);

    // Everything per tile, then everything per triangle, each box dealt out among as many walks
    // as it may take (small_walks): the same key in every sample.
    RendererOptions tiles, small;
    tiles.small_triangle_max_area = 0;
    small.small_triangle_max_area = 1u << 16;
    small.small_triangle_walk_area = 1;
    // Analytic coverage: the same bits again, whatever the objects' order.
    const Frame analytic = render_with(scene, 96, samples, AaCoverage::analytic);
    const Frame analytic_reordered = render_with(shuffled, 96, samples, AaCoverage::analytic);
    EXPECT_TRUE(same_bits(analytic.hdr, analytic_reordered.hdr)) << samples << " samples, analytic";
    EXPECT_FALSE(same_bits(analytic.hdr, first.hdr)) << samples << " samples, analytic";
    // Silhouette coverage likewise (its walk's order comes from the meshes alone).
    const Frame walked_outline = render_with(scene, 96, samples, AaCoverage::silhouette);
    const Frame walked_reordered = render_with(shuffled, 96, samples, AaCoverage::silhouette);
    EXPECT_TRUE(same_bits(walked_outline.hdr, walked_reordered.hdr)) << samples << " samples";
    EXPECT_FALSE(same_bits(walked_outline.hdr, first.hdr)) << samples << " samples, silhouette";

    const Frame tiled = render_at(scene, 96, samples, tiles);
    const Frame walked = render_at(scene, 96, samples, small);
    EXPECT_EQ(first.visibility, tiled.visibility) << samples << " samples, per tile";
    EXPECT_EQ(first.visibility, walked.visibility) << samples << " samples, per triangle";
    EXPECT_TRUE(same_bits(first.hdr, tiled.hdr));
  }
}

// lavapipe reads LP_NUM_THREADS when its device is created, so each count runs the tool anew.
TEST(AntiAliasingAcrossThreads, OneAndTwoLavapipeThreadsGiveIdenticalFiles) {
  std::string outputs[2];
  for (int threads = 1; threads <= 2; ++threads) {
    const std::string pfm = test::output_path("aa" + std::to_string(threads) + ".pfm");
    std::string log;
    const std::string command = "LP_NUM_THREADS=" + std::to_string(threads) +
                                " " TESSERA_BINARY
                                " render --device lavapipe --validate --size 128x96 --samples 8 "
                                "--quiet --out " +
                                test::output_path("aa.png") + " --hdr-out " + pfm;
    ASSERT_EQ(test::run_command(command, log), 0) << log;
    std::ifstream f(pfm, std::ios::binary);
    outputs[threads - 1] = std::string(std::istreambuf_iterator<char>(f), {});
  }
  EXPECT_GT(outputs[0].size(), 128u * 96 * 12);
  EXPECT_TRUE(outputs[0] == outputs[1]) << "HDR differs between 1 and 2 threads";
}

// Both forms of the code that clips polygons to the view and cuts them by a pixel's edges
// (Context::polygons_in_registers: queues indexed by constants, which CPU devices get, or
// arrays indexed by corner, which GPUs get) give the same bits: analytic and silhouette coverage
// at 4 samples, over the crowded scene with a wall beside the camera that runs behind it,
// so that the clip pass clips it (near plane and guard band) and the coverage code cuts
// polygons of more than three corners.
TEST_F(AntiAliasing, PolygonsInRegistersAndIndexedByCornerGiveTheSameBits) {
  Scene scene = crowded_scene();
  scene.meshes.push_back(make_plane(4, 4));
  // A strip 80 long and 6 high at x = 0.3, turned to face -x (the camera).
  glm::mat4 wall = glm::translate(glm::mat4(1.0f), glm::vec3(0.3f, 0.0f, 0.0f));
  wall = glm::rotate(wall, -glm::half_pi<float>(), glm::vec3(0.0f, 1.0f, 0.0f));
  scene.objects.push_back(
      {uint32_t(scene.meshes.size() - 1), 1, glm::scale(wall, glm::vec3(40.0f, 3.0f, 1.0f))});
  ASSERT_LT(scene.camera.position.z, 40.0f);  // the wall reaches behind the camera

  Context& ctx = context();
  struct Restore {
    Context& ctx;
    bool form;
    ~Restore() { ctx.polygons_in_registers = form; }
  } restore{ctx, ctx.polygons_in_registers};
  std::vector<Frame> frames[2];
  for (int form = 0; form < 2; ++form) {
    ctx.polygons_in_registers = form == 1;
    for (AaCoverage coverage : {AaCoverage::analytic, AaCoverage::silhouette})
      frames[form].push_back(render_with(scene, 64, 4, coverage));
  }
  EXPECT_GT(frames[0][0].stats.clipped, 0u);
  for (size_t i = 0; i < frames[0].size(); ++i) {
    EXPECT_TRUE(same_bits(frames[0][i].hdr, frames[1][i].hdr)) << "frame " << i;
    EXPECT_EQ(frames[0][i].visibility, frames[1][i].visibility) << "frame " << i;
  }
}

TEST_F(AntiAliasing, EveryPixelOfAClosedMeshCountsEachSampleOnce) {
  // Disjoint closed meshes: every sample's ray enters each mesh as often as it leaves it, and
  // snapping keeps the meshes closed (a shared vertex snaps once), so with nothing culled every
  // sample is covered by as many back faces as front ones: the coverage with nothing culled is
  // twice the coverage with back faces culled, pixel by pixel. A sample covered twice along a
  // shared edge, or dropped, breaks that. With back faces culled the covered samples are the
  // non-empty keys, except where snapping folds the outline (a front face pushed over its
  // neighbour, a nearly edge-on face whose winding snapping flipped, with back faces under
  // both): a fold covers a sample with two front faces, only at the outline, so such a pixel has
  // an empty sample. (The reference, in double, finds the same fold: docs/tradeoffs.md.)
  Scene scene = make_sphere_grid_scene();
  RendererOptions back, none;
  back.debug_coverage = none.debug_coverage = true;
  none.cull = CullMode::none;
  for (uint32_t samples : {4u, 8u, 16u}) {
    const Frame f = render_at(scene, 64, samples, back);
    const Frame g = render_at(scene, 64, samples, none);
    size_t folded = 0;
    for (size_t p = 0; p < f.coverage.size(); ++p) {
      ASSERT_EQ(g.coverage[p], 2 * f.coverage[p]) << "pixel " << p << ", " << samples << " samples";
      uint32_t covered = 0;
      for (uint32_t s = 0; s < samples; ++s)
        covered += f.visibility[p * samples + s] != TS_VIS_EMPTY ? 1 : 0;
      ASSERT_GE(f.coverage[p], covered) << "pixel " << p << ", " << samples << " samples";
      if (f.coverage[p] == covered) continue;
      ++folded;
      EXPECT_LT(covered, samples) << "a fold inside the outline at pixel " << p;
    }
    EXPECT_LE(folded, 2u) << samples << " samples";
  }
}

TEST_F(AntiAliasing, AgreesWithTheReferenceAtTheSameSamples) {
  const Scene scene = make_sphere_grid_scene();
  const uint32_t size = 96;
  // Silhouette coverage also with a walk of 2 steps, which at this size (spheres 10 px
  // across, their triangles far below a pixel) stops many walks short.
  struct Mode {
    uint32_t samples;
    AaCoverage coverage;
    uint32_t steps;
  };
  for (const auto& [samples, coverage, steps] :
       {Mode{4u, AaCoverage::count, 0}, Mode{16u, AaCoverage::count, 0},
        Mode{4u, AaCoverage::analytic, 0}, Mode{4u, AaCoverage::silhouette, 0},
        Mode{4u, AaCoverage::silhouette, 2}}) {
    const Frame gpu = render_with(scene, size, samples, coverage, steps);
    ReferenceSettings rs;
    rs.frame.width = rs.frame.height = size;
    rs.frame.samples = samples;
    rs.frame.aa_coverage = coverage;
    rs.frame.silhouette_steps = steps;
    rs.threads = 2;
    const ReferenceFrame ref = render_reference(scene, rs);
    ASSERT_EQ(ref.sample_ids.size(), gpu.visibility.size());
    // Ownership per sample: float and double snapping may disagree by one sub-pixel step where
    // an exact edge passes within 1/256 px of a sample (docs/accuracy.md), so a few may differ.
    const std::vector<uint32_t> gpu_ids = ids_of(gpu.visibility);
    const size_t mismatches = count_mismatches(gpu_ids, ref.sample_ids);
    EXPECT_LE(double(mismatches), 1e-3 * double(gpu_ids.size()))
        << mismatches << " of " << gpu_ids.size() << " samples";
    // 8-bit images within 1 level where every sample agrees, as the other accuracy tests.
    std::vector<uint8_t> agree(size_t(size) * size, 1);
    for (size_t p = 0; p < agree.size(); ++p) {
      for (uint32_t s = 0; s < samples; ++s) {
        if (gpu_ids[p * samples + s] != ref.sample_ids[p * samples + s]) agree[p] = 0;
      }
    }
    const ImageDifference d = compare_images(gpu.ldr, ref.ldr, 1.0, &agree);
    EXPECT_LE(d.max_abs_error, 1.0) << samples << " samples at " << d.worst_x << "," << d.worst_y;
    std::printf(
        "AA %u samples (%s, walk steps %u) vs reference: %zu of %zu samples owned differently, "
        "max %g levels\n",
        samples,
        coverage == AaCoverage::count      ? "count"
        : coverage == AaCoverage::analytic ? "analytic"
                                           : "silhouette",
        steps, mismatches, gpu_ids.size(), d.max_abs_error);
  }
}

// A limit on the silhouette walk's steps stops walks short where triangles are small against a
// pixel, and so changes pixels there (the reference follows it: AgreesWithTheReference...);
// a walk of 1 step is refused, naming the value.
TEST_F(AntiAliasing, SilhouetteWalkStepsStopLongWalks) {
  const Scene scene = make_sphere_grid_scene();
  const Frame whole = render_with(scene, 96, 4, AaCoverage::silhouette);
  const Frame short_walks = render_with(scene, 96, 4, AaCoverage::silhouette, 2);
  size_t changed = 0;
  for (size_t p = 0; p < whole.hdr.pixels.size(); ++p) {
    if (whole.hdr.pixels[p] == short_walks.hdr.pixels[p]) continue;
    ++changed;
    // Only outline pixels change: samples that see the background and some that do not.
    size_t empty = 0;
    for (uint32_t s = 0; s < 4; ++s) empty += whole.visibility[p * 4 + s] == TS_VIS_EMPTY ? 1 : 0;
    EXPECT_TRUE(empty > 0 && empty < 4) << "pixel " << p << " has " << empty << " empty samples";
  }
  EXPECT_GT(changed, 0u);
  std::printf("AA walk of 2 steps: %zu pixels of %zu differ from the whole walk\n", changed,
              whole.hdr.pixels.size());
  Renderer renderer(context());
  FrameSettings fs;
  fs.width = fs.height = 32;
  fs.samples = 4;
  fs.aa_coverage = AaCoverage::silhouette;
  fs.silhouette_steps = 1;
  renderer.set_scene(scene);
  try {
    renderer.render(fs);
    FAIL() << "a walk of 1 step was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("1 step"), std::string::npos) << e.what();
  }
}

// Area of the unit pixel [0, 1]^2 on the side n.p < d of a line (n a unit vector): the pixel
// clipped to a square of side 20 on that side of it (area_in_pixel), exact for the expected
// error of a pattern.
double half_plane_coverage(glm::dvec2 n, double d) {
  const glm::dvec2 on = n * d, along(-n.y, n.x);
  return area_in_pixel({on - 10.0 * along, on + 10.0 * along, on + 10.0 * along - 20.0 * n,
                        on - 10.0 * along - 20.0 * n});
}

// Mean |k / N - c| of a pattern over straight edges crossing a pixel, uniform in angle and in
// offset: what counting N samples can do for edges, with no shading error at all.
double straight_edge_error(const std::vector<glm::ivec2>& pattern) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> angle(0.0, 2.0 * 3.14159265358979), offset(-1.0, 1.0);
  double sum = 0.0;
  int edges = 0;
  while (edges < 20000) {
    const double a = angle(rng);
    const glm::dvec2 n(std::cos(a), std::sin(a));
    const double d = glm::dot(n, glm::dvec2(0.5)) + offset(rng) * 0.75;
    const double c = half_plane_coverage(n, d);
    if (c <= 0.0 || c >= 1.0) continue;  // the line misses the pixel
    int k = 0;
    for (glm::ivec2 s : pattern)
      k += glm::dot(n, glm::dvec2(s) / double(TS_SAMPLE_GRID)) < d ? 1 : 0;
    sum += std::abs(double(k) / double(pattern.size()) - c);
    ++edges;
  }
  return sum / edges;
}

TEST_F(AntiAliasing, FourSamplesCutTheEdgeErrorAsTheirPatternAllows) {
  // Edge error: the mean relative radiance error (radiance_error) over the pixels an outline
  // crosses (outline_pixels of the truth's ownership), against the 16 x 16 supersampled
  // truth of the same triangles. Issue 12 asks 4 samples to cut it 3x from 1 sample.
  // Counting 4 samples cannot: over straight edges of every angle and offset, the standard
  // 4-sample pattern's coverage error is 1/2.74 of one centre sample's (straight_edge_error,
  // computed here exactly per edge), an ordered 2x2 grid's 1/2.87, and the best 4 points found
  // by a search over positions 1/2.88 (docs/tradeoffs.md, "Anti-aliasing"). Asserted for the
  // count (the default): the scene gets at least 90 % of the pattern's straight-edge factor
  // (the rest is curvature, and the relative error weighing pixels that are mostly dark
  // background, where a sliver of sphere is missed by 1 and 4 samples alike), below 3x, the
  // point-sample limit, and more samples keep improving it. Analytic coverage does worse here
  // (docs/tradeoffs.md): the triangles at a sphere's outline are nearly edge-on slivers the
  // samples miss, so the edge it cuts along is one the surface continues across. Asserted:
  // its figures stay between the count's and 1 sample's at 4 samples, better than 1 sample at
  // each count, and fall with more samples. Silhouette coverage takes in those slivers (the
  // area of the pixel inside the surface's outline, not a count): at 4 samples it reaches
  // issue 12's 3x.
  const double one = straight_edge_error({TS_SAMPLES_1(glm::ivec2)});
  const double four = straight_edge_error({TS_SAMPLES_4(glm::ivec2)});
  std::printf("AA straight edges: coverage error %.4f (1 sample), %.4f (4): factor %.2f\n", one,
              four, one / four);
  const Scene scene = make_sphere_grid_scene();
  const uint32_t size = 128;
  ReferenceSettings rs;
  rs.frame.width = rs.frame.height = size;
  rs.ground_truth.supersampling = 16;
  rs.threads = 2;
  const ReferenceFrame truth = render_reference(scene, rs);
  const std::vector<uint8_t> edges = outline_pixels(truth.ownership);
  const size_t edge_pixels = size_t(std::count(edges.begin(), edges.end(), uint8_t(1)));
  ASSERT_GT(edge_pixels, 500u);
  double count[17] = {}, analytic[17] = {};
  for (uint32_t samples : {1u, 4u, 8u, 16u}) {
    count[samples] =
        radiance_error(render_at(scene, size, samples).hdr, truth.hdr, &edges).mean_relative;
    analytic[samples] = radiance_error(render_with(scene, size, samples, AaCoverage::analytic).hdr,
                                       truth.hdr, &edges)
                            .mean_relative;
    std::printf(
        "AA edge error, %u sample(s): %.4f counted, %.4f analytic (%.2fx, %.2fx less "
        "than 1 sample) over %zu pixels\n",
        samples, count[samples], analytic[samples], count[1] / count[samples],
        count[1] / analytic[samples], edge_pixels);
  }
  EXPECT_EQ(count[1], analytic[1]);  // one sample has nothing to weigh
  EXPECT_GE(count[1] / count[4], 0.9 * one / four);
  EXPECT_LT(count[1] / count[4], 3.0);
  EXPECT_LT(count[8], count[4]);
  EXPECT_LT(count[16], count[8]);
  EXPECT_GT(analytic[4], count[4]);
  EXPECT_LT(analytic[4], 0.5 * analytic[1]);
  EXPECT_LT(analytic[8], analytic[4]);
  EXPECT_LT(analytic[16], analytic[8]);
  const double silhouette =
      radiance_error(render_with(scene, size, 4, AaCoverage::silhouette).hdr, truth.hdr, &edges)
          .mean_relative;
  std::printf("AA edge error, 4 samples, silhouette coverage: %.4f (%.2fx less than 1 sample)\n",
              silhouette, count[1] / silhouette);
  EXPECT_GE(count[1] / silhouette, 3.0);
}

// The 16 x 16 supersampled truth of `scene`'s own triangles, width x height pixels.
ReferenceFrame supersampled_truth(const Scene& scene, uint32_t width, uint32_t height) {
  ReferenceSettings rs;
  rs.frame.width = width;
  rs.frame.height = height;
  rs.ground_truth.supersampling = 16;
  rs.threads = 2;
  return render_reference(scene, rs);
}

// The edge error of the test above at other sizes, for docs/tradeoffs.md's table (disabled:
// its truths take minutes; run with --gtest_also_run_disabled_tests). AA_W x AA_H pixels
// (default 128 x 128); with AA_FULLH, the central AA_W x AA_H of an image AA_FULLH pixels high
// (the field of view narrowed to it, so sizes on screen and the pixel grid are that image's,
// for even sizes); AA_SCENE another built-in scene than the default; AA_STEPS silhouette walk
// step limits to measure too (e.g. 3,4).
uint32_t size_from_environment(const char* name, uint32_t otherwise) {
  const char* value = std::getenv(name);
  return value ? uint32_t(std::strtoul(value, nullptr, 10)) : otherwise;
}

TEST_F(AntiAliasing, DISABLED_EdgeErrorAtOtherSizes) {
  const uint32_t w = size_from_environment("AA_W", 128), h = size_from_environment("AA_H", 128);
  const uint32_t full_h = size_from_environment("AA_FULLH", h);
  const char* scene_name = std::getenv("AA_SCENE");
  Scene scene = make_builtin_scene(scene_name ? scene_name : "spheres");
  scene.camera.vertical_fov = float(
      2.0 * std::atan(std::tan(double(scene.camera.vertical_fov) / 2.0) * h / double(full_h)));
  const ReferenceFrame truth = supersampled_truth(scene, w, h);
  const std::vector<uint8_t> edges = outline_pixels(truth.ownership);
  double one = 0.0;
  Renderer renderer(context());
  struct Mode {
    uint32_t samples;
    AaCoverage coverage;
    uint32_t steps;
  };
  std::vector<Mode> modes = {{1u, AaCoverage::count, 0},
                             {4u, AaCoverage::count, 0},
                             {4u, AaCoverage::analytic, 0},
                             {4u, AaCoverage::silhouette, 0}};
  // AA_STEPS: silhouette walk step limits to measure too, comma-separated (FrameSettings::
  // silhouette_steps).
  if (const char* steps = std::getenv("AA_STEPS")) {
    for (const char* p = steps; *p != '\0';) {
      char* end = nullptr;
      modes.push_back({4u, AaCoverage::silhouette, uint32_t(std::strtoul(p, &end, 10))});
      p = *end == ',' ? end + 1 : end;
      if (end == p && *p != '\0') break;
    }
  }
  for (const Mode& m : modes) {
    FrameSettings fs;
    fs.width = w;
    fs.height = h;
    fs.samples = m.samples;
    fs.aa_coverage = m.coverage;
    fs.silhouette_steps = m.steps;
    const double e =
        radiance_error(render(renderer, scene, fs).hdr, truth.hdr, &edges).mean_relative;
    if (m.samples == 1) one = e;
    std::printf(
        "AA edge error %ux%u of %u rows, %u sample(s), mode %d, walk steps %u: %.4f (%.2fx) over "
        "%zu px\n",
        w, h, full_h, m.samples, int(m.coverage), m.steps, e, one / e,
        size_t(std::count(edges.begin(), edges.end(), uint8_t(1))));
  }
}

// Emissive shapes of radiance 1 on black, seen head-on: the camera looks down -z at the plane
// z = 0 from 10 units, so a point given in pixels of a size x size image lies where
// add_corner puts it, and areas in that plane scale by px_per_unit^2 exactly. Corners are
// added to `mesh` (the scene's only one, added by the caller) in triangle order.
struct HeadOnPlane {
  Scene scene;
  uint32_t size = 0;
  double px_per_unit = 0.0;
  Mesh mesh;
  void add_corner(glm::dvec2 p) {
    // Pixels (y down) to the plane z = 0 (y up).
    mesh.positions.push_back(glm::vec3(float((p.x - size / 2.0) / px_per_unit),
                                       float((size / 2.0 - p.y) / px_per_unit), 0.0f));
    mesh.normals.push_back({0.0f, 0.0f, 1.0f});
    mesh.uvs.push_back({0.0f, 0.0f});
  }
  // The scene with `mesh` as its one object.
  Scene finish() {
    Scene s = scene;
    s.meshes.push_back(mesh);
    s.objects.push_back({0, 0, glm::mat4(1.0f)});
    return s;
  }
};

HeadOnPlane head_on_plane(uint32_t size) {
  const float distance = 10.0f, fov = glm::radians(30.0f);
  HeadOnPlane h;
  h.size = size;
  h.px_per_unit = (size / 2.0) / std::tan(double(fov) / 2.0) / distance;
  Scene& s = h.scene;
  s.camera.position = {0.0f, 0.0f, distance};
  s.camera.vertical_fov = fov;
  s.camera.near_plane = 0.1f;
  s.ambient = glm::vec3(0.0f);
  s.background = glm::vec3(0.0f);
  Material m;
  m.base_color = glm::vec3(0.0f);
  m.emissive = glm::vec3(1.0f);
  m.double_sided = true;
  s.materials.push_back(m);
  return h;
}

// A pixel a straight edge crosses at a known offset: under analytic coverage its weight is the
// area the edge leaves, computed by hand. A square of emissive radiance 1 on black, seen
// head-on, ends at x = 8 + 5/16 px (on the 1/256 px grid, so snapping keeps it there): pixel
// column 8 is covered 5/16 = 0.3125, which analytic coverage gives (the compute path and the
// reference), where counting the 4-sample pattern (x offsets 1/8, 3/8, 5/8, 7/8) finds 1
// sample of 4. Its neighbours are whole.
TEST_F(AntiAliasing, AnEdgeAtAKnownOffsetWeighsItsPixelByTheAreaItLeaves) {
  const uint32_t size = 16;
  HeadOnPlane plane = head_on_plane(size);
  const double edge_x = 8.0 + 5.0 / 16.0;
  for (glm::dvec2 p : {glm::dvec2(-4.0, -4.0), glm::dvec2(edge_x, -4.0),
                       glm::dvec2(edge_x, size + 4.0), glm::dvec2(-4.0, size + 4.0)}) {
    plane.add_corner(p);
  }
  plane.mesh.indices = {0, 1, 2, 0, 2, 3};
  const Scene s = plane.finish();
  for (uint32_t samples : {4u, 16u}) {
    const Frame analytic = render_with(s, size, samples, AaCoverage::analytic);
    const Frame counted = render_at(s, size, samples);
    ReferenceSettings rs;
    rs.frame.width = rs.frame.height = size;
    rs.frame.samples = samples;
    rs.frame.aa_coverage = AaCoverage::analytic;
    const ReferenceFrame ref = render_reference(s, rs);
    // The HDR image is fp16, whose step at 0.3125 is 2^-12: float rounding in the clipping
    // may leave the area a hair below 5/16, which the conversion can take one step down.
    const double fp16_step = std::ldexp(1.0, -12);
    for (uint32_t y = 0; y < size; ++y) {
      const size_t row = size_t(y) * size;
      EXPECT_NEAR(analytic.hdr.pixels[row + 8].r, 0.3125, fp16_step)
          << samples << " samples, row " << y;
      EXPECT_NEAR(ref.hdr.pixels[row + 8].r, 0.3125, fp16_step) << samples << " samples, row " << y;
      EXPECT_NEAR(analytic.hdr.pixels[row + 7].r, 1.0, 1e-6);
      EXPECT_EQ(analytic.hdr.pixels[row + 9].r, 0.0f);
    }
    // Counted: the samples left of 5/16 px, 1 of 4 (x offsets 4, 28, 12, 20 of 32) or 5 of 16.
    EXPECT_EQ(counted.hdr.pixels[8].r, samples == 4 ? 0.25f : 5.0f / 16.0f) << samples;
  }
}

// A straight edge at an angle across a 16 x 16 image, the side left of the line through
// (6, -4) and (10, 20) px emissive 1 on black: every pixel's exact covered area is
// area_in_pixel of that side (independent of the renderer). Analytic coverage gives it where
// a pixel's samples see the edge; counting is off by up to 1/N. At 4 samples some pixels the
// line clips have no sample on the covered side; both miss those alike.
TEST_F(AntiAliasing, AnalyticCoverageFollowsAStraightEdgeCountingCannot) {
  const uint32_t size = 16;
  HeadOnPlane plane = head_on_plane(size);
  const std::vector<glm::dvec2> corners = {{-4.0, -4.0}, {6.0, -4.0}, {10.0, 20.0}, {-4.0, 20.0}};
  for (glm::dvec2 p : corners) plane.add_corner(p);
  plane.mesh.indices = {0, 1, 2, 0, 2, 3};
  const Scene s = plane.finish();
  for (uint32_t samples : {4u, 16u}) {
    const Frame analytic = render_with(s, size, samples, AaCoverage::analytic);
    const Frame counted = render_at(s, size, samples);
    double analytic_error = 0.0, count_error = 0.0;
    for (uint32_t y = 0; y < size; ++y) {
      for (uint32_t x = 0; x < size; ++x) {
        std::vector<glm::dvec2> local;
        for (glm::dvec2 p : corners) local.push_back(p - glm::dvec2(x, y));
        const double area = area_in_pixel(local);
        analytic_error += std::abs(analytic.hdr.pixels[y * size + x].r - area);
        count_error += std::abs(counted.hdr.pixels[y * size + x].r - area);
      }
    }
    std::printf(
        "AA straight edge at an angle, %u samples: summed coverage error %.4f analytic, "
        "%.4f counted\n",
        samples, analytic_error, count_error);
    EXPECT_LT(analytic_error, 0.5 * count_error) << samples << " samples";
  }
}

// Convex hull of points (Andrew's monotone chain), counter-clockwise.
std::vector<glm::dvec2> convex_hull(std::vector<glm::dvec2> p) {
  std::sort(p.begin(), p.end(),
            [](glm::dvec2 a, glm::dvec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  const auto turn = [](glm::dvec2 o, glm::dvec2 a, glm::dvec2 b) {
    return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
  };
  std::vector<glm::dvec2> hull(2 * p.size());
  size_t k = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && turn(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  for (size_t i = p.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && turn(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  hull.resize(k - 1);
  return hull;
}

// A tessellated sphere's outline is made of nearly edge-on slivers: silhouette coverage
// follows it where the samples see the sphere, counting and analytic coverage cannot. The
// sphere is convex, so the front faces' union on screen is the convex hull of its projected
// corners: each pixel's exact coverage is that hull's area in it (area_in_pixel), computed here
// from the camera's projection by hand. An emissive sphere (radiance 1, on black), a 24 x 12
// uv sphere about 16 px across in a 24 x 24 image, turned so that its outline crosses the
// pixels at every angle.
TEST_F(AntiAliasing, SilhouetteCoverageFollowsASphereOutlineOfSlivers) {
  const uint32_t size = 24;
  HeadOnPlane plane = head_on_plane(size);
  plane.scene.materials[0].double_sided = false;
  Scene s = plane.scene;
  s.meshes.push_back(make_uv_sphere(24, 12));
  const float radius = float(8.0 / plane.px_per_unit);  // about 8 px on screen
  glm::mat4 t = glm::translate(glm::mat4(1.0f), glm::vec3(0.13f, -0.07f, 0.0f));
  t = glm::rotate(t, 0.7f, glm::normalize(glm::vec3(1.0f, 0.4f, 0.2f)));
  t = glm::scale(t, glm::vec3(radius));
  s.objects.push_back({0, 0, t});
  // The corners on screen, as the camera (at z = 10 looking down -z, head_on_plane) projects
  // them: x_px = size / 2 + f x / (10 - z), y_px = size / 2 - f y / (10 - z), f the focal
  // length in pixels (px_per_unit times the distance).
  std::vector<glm::dvec2> projected;
  const double f = plane.px_per_unit * 10.0;
  for (const glm::vec3& p : s.meshes[0].positions) {
    const glm::dvec3 w = glm::dvec3(t * glm::vec4(p, 1.0f));
    projected.push_back({size / 2.0 + f * w.x / (10.0 - w.z), size / 2.0 - f * w.y / (10.0 - w.z)});
  }
  const std::vector<glm::dvec2> hull = convex_hull(projected);
  ReferenceSettings rs;
  rs.frame.width = rs.frame.height = size;
  rs.frame.samples = 4;
  rs.frame.aa_coverage = AaCoverage::silhouette;
  const ReferenceFrame ref = render_reference(s, rs);
  double error[3] = {}, worst = 0.0, worst_ref = 0.0;
  size_t outline = 0;
  const AaCoverage modes[3] = {AaCoverage::count, AaCoverage::analytic, AaCoverage::silhouette};
  Renderer renderer(context());  // one for the three: building pipelines costs lavapipe most
  for (int m = 0; m < 3; ++m) {
    FrameSettings fs;
    fs.width = fs.height = size;
    fs.samples = 4;
    fs.aa_coverage = modes[m];
    const Frame frame = render(renderer, s, fs);
    for (uint32_t y = 0; y < size; ++y) {
      for (uint32_t x = 0; x < size; ++x) {
        std::vector<glm::dvec2> local;
        for (glm::dvec2 p : hull) local.push_back(p - glm::dvec2(x, y));
        const double area = area_in_pixel(local);
        if (area <= 0.0 || area >= 1.0) continue;
        // Only pixels where a sample sees the sphere and one does not: where no sample sees it
        // every mode gives 0.
        uint32_t seen = 0;
        for (uint32_t k = 0; k < 4; ++k)
          seen += frame.visibility[(size_t(y) * size + x) * 4 + k] != TS_VIS_EMPTY ? 1 : 0;
        if (seen == 0 || seen == 4) continue;
        const double e = std::abs(frame.hdr.pixels[y * size + x].r - area);
        error[m] += e;
        if (m != 2) continue;
        ++outline;
        worst = std::max(worst, e);
        worst_ref = std::max(worst_ref, std::abs(ref.hdr.pixels[y * size + x].r - area));
      }
    }
  }
  std::printf(
      "AA sphere outline, %zu pixels: summed coverage error %.4f counted, %.4f analytic, %.4f "
      "silhouette (worst pixel %.4f, reference %.4f)\n",
      outline, error[0], error[1], error[2], worst, worst_ref);
  ASSERT_GT(outline, 30u);
  // Snapping moves corners by up to 1/512 px, fp16 rounds to 2^-11 of the value: 0.01 covers
  // both many times over, where a count of 4 samples is off by up to 1/4 or more.
  EXPECT_LT(worst, 0.01);
  EXPECT_LT(worst_ref, 0.01);
  EXPECT_LT(error[2], 0.1 * error[0]);
  EXPECT_LT(error[2], 0.1 * error[1]);
}

TEST_F(AntiAliasing, InteriorErrorOfSubPixelTrianglesFallsWithSamples) {
  // The grid family's spheres about 10 px across at 192 x 108 (960 triangles each, most far
  // below a pixel: the H200 chart's 10^4 spheres at 1920 x 1080 scaled down), against the
  // 16 x 16 supersampled truth of the same triangles, over the interior: pixels the truth
  // shows one object (or only the background) in, in all its samples. Shading each distinct
  // triangle once at the mean of its samples is a stratified estimate of the pixel's integral,
  // so more samples must not be worse than one. Before the 16-sample pattern was centred
  // (constants.h) its 1/32 px offset made 16 samples 1.7x worse than 8 here.
  // Roughness is raised to at least 1/3: below that, a point light's highlight on these
  // spheres is far smaller than the truth's sample spacing (perceptual roughness 0.045, the
  // clamp, is a lobe of about 0.002 rad), so neither the render nor the truth resolves it, and
  // the interior mean follows a few pixels where one of them happens to hit it
  // (docs/tradeoffs.md, "Where it fails").
  Scene scene = make_bench_scene("grid", 100, 32, 192.0f / 108.0f);
  for (Material& m : scene.materials) m.roughness = std::max(m.roughness, 1.0f / 3.0f);
  const uint32_t width = 192, height = 108;
  const ReferenceFrame truth = supersampled_truth(scene, width, height);
  std::vector<uint8_t> interior(size_t(width) * height);
  for (size_t i = 0; i < interior.size(); ++i)
    interior[i] = truth.ownership.first[i + 1] - truth.ownership.first[i] == 1 ? 1 : 0;
  double error[17] = {};
  for (uint32_t samples : {1u, 4u, 8u, 16u}) {
    const Frame f = render(scene, width, height, {}, samples);
    if (samples == 1) {
      // The triangles really are sub-pixel: more front faces than covered pixels, most of
      // them holding no pixel centre.
      size_t covered = 0;
      for (uint64_t key : f.visibility) covered += key != TS_VIS_EMPTY ? 1 : 0;
      const uint64_t front = f.stats.triangles_submitted - f.stats.culled_backface;
      std::printf("AA sub-pixel grid: %llu front faces over %zu covered pixels\n",
                  (unsigned long long)front, covered);
      ASSERT_GT(front, 2 * covered);
    }
    error[samples] = radiance_error(f.hdr, truth.hdr, &interior).mean_relative;
    std::printf("AA interior error of sub-pixel triangles, %u sample(s): %.4f\n", samples,
                error[samples]);
  }
  for (uint32_t samples : {4u, 8u, 16u}) EXPECT_LT(error[samples], 0.5 * error[1]) << samples;
  // Measured on lavapipe: 0.0142 at 1 sample, 0.0045, 0.0051 and 0.0051 at 4, 8 and 16 (0.0082
  // at 16 with the standard, off-centre pattern); the small step from 4 to 8 is the patterns'.
  EXPECT_LT(error[8], 1.25 * error[4]);
  EXPECT_LT(error[16], 1.1 * error[8]);
}

// Triangles smaller than a pixel, each alone in a 3 x 3 block of pixels and moved by a random
// fraction of a pixel, of uniform radiance 1 on black, seen head-on (head_on_plane): the
// radiance summed over its block is the area its samples see, in px^2.
struct TriangleField {
  Scene scene;
  std::vector<double> areas;  // px^2, analytic, per block
  uint32_t blocks_per_side;
};

TriangleField triangle_field(uint32_t blocks_per_side, uint32_t seed) {
  HeadOnPlane plane = head_on_plane(3 * blocks_per_side);
  TriangleField field;
  field.blocks_per_side = blocks_per_side;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (uint32_t by = 0; by < blocks_per_side; ++by) {
    for (uint32_t bx = 0; bx < blocks_per_side; ++bx) {
      // Corners within 0.6 px of the centre of the block's middle pixel (so an area of at most
      // 3 sqrt(3) / 4 * 0.6^2 = 0.47 px^2), moved by up to a pixel: inside the block.
      const glm::dvec2 shift(unit(rng), unit(rng));
      glm::dvec2 px[3];
      for (glm::dvec2& p : px) {
        const double r = 0.6 * std::sqrt(unit(rng)), a = 2.0 * 3.14159265358979 * unit(rng);
        p = glm::dvec2(3.0 * bx + 1.0, 3.0 * by + 1.0) + shift +
            r * glm::dvec2(std::cos(a), std::sin(a));
      }
      field.areas.push_back(0.5 * std::abs((px[1].x - px[0].x) * (px[2].y - px[0].y) -
                                           (px[1].y - px[0].y) * (px[2].x - px[0].x)));
      for (const glm::dvec2& p : px) {
        plane.add_corner(p);
        plane.mesh.indices.push_back(uint32_t(plane.mesh.indices.size()));
      }
    }
  }
  field.scene = plane.finish();
  return field;
}

TEST_F(AntiAliasing, SubPixelTrianglesCoverTheirAreaWithinTheSamplingBand) {
  // Where anti-aliasing fails: a triangle smaller than a pixel is seen by the few samples it
  // happens to hold. Moved uniformly over a pixel, each sample lies in it with probability
  // equal to its area a (px^2), so the measured area is unbiased; with N independent uniform
  // samples per pixel it would have variance a (1 - a) / N. The stated band: the field's mean
  // within 4 standard errors of the analytic mean, and the RMS error per triangle within
  // 1.25 sqrt(mean a (1 - a) / N): well-spread fixed patterns do no worse than independent
  // samples, and 1.25 allows for the field's size (576 triangles of ~0.1 px^2 give the RMS
  // at one sample, where it equals the band on average, a spread of about 7 %).
  const TriangleField field = triangle_field(24, 5);
  const uint32_t size = 3 * field.blocks_per_side;
  double mean_area = 0.0, variance = 0.0;
  for (double a : field.areas) {
    mean_area += a;
    variance += a * (1.0 - a);
  }
  mean_area /= double(field.areas.size());
  variance /= double(field.areas.size());
  double previous_rms = 1e9;
  for (uint32_t samples : {1u, 4u, 8u, 16u}) {
    const Frame f = render_at(field.scene, size, samples);
    double sum_error = 0.0, sum_squared = 0.0;
    for (uint32_t by = 0; by < field.blocks_per_side; ++by) {
      for (uint32_t bx = 0; bx < field.blocks_per_side; ++bx) {
        double seen = 0.0;
        for (uint32_t y = 3 * by; y < 3 * by + 3; ++y) {
          for (uint32_t x = 3 * bx; x < 3 * bx + 3; ++x) seen += f.hdr.pixels[y * size + x].r;
        }
        const double e = seen - field.areas[by * field.blocks_per_side + bx];
        sum_error += e;
        sum_squared += e * e;
      }
    }
    const double n = double(field.areas.size());
    const double bias = sum_error / n, rms = std::sqrt(sum_squared / n);
    const double band = std::sqrt(variance / samples);
    std::printf(
        "AA sub-pixel field, %u sample(s): mean area %.4f px^2, bias %+.4f (4 sigma "
        "%.4f), rms %.4f (band %.4f)\n",
        samples, mean_area, bias, 4.0 * band / std::sqrt(n), rms, band);
    EXPECT_LE(std::abs(bias), 4.0 * band / std::sqrt(n)) << samples << " samples";
    EXPECT_LE(rms, 1.25 * band) << samples << " samples";
    EXPECT_LT(rms, previous_rms);
    previous_rms = rms;
  }
}

TEST_F(AntiAliasing, BadSampleCountsAreErrorsNamingTheValue) {
  const Scene scene = make_sphere_grid_scene();
  Renderer renderer(context());
  renderer.set_scene(scene);
  for (uint32_t bad : {0u, 2u, 3u, 5u, 32u}) {
    FrameSettings fs;
    fs.width = fs.height = 16;
    fs.samples = bad;
    try {
      renderer.render(fs);
      ADD_FAILURE() << bad << " samples rendered";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("samples per pixel " + std::to_string(bad)),
                std::string::npos)
          << e.what();
    }
    ReferenceSettings rs;
    rs.frame = fs;
    EXPECT_THROW(render_reference(scene, rs), Error);
  }
  ReferenceSettings truth;
  truth.frame.width = truth.frame.height = 8;
  truth.frame.samples = 4;
  truth.ground_truth.supersampling = 4;
  EXPECT_THROW(render_reference(scene, truth), Error);
  FrameSettings four;
  four.width = four.height = 16;
  four.samples = 4;
  HardwareBaseline hardware(renderer);
  EXPECT_THROW(hardware.render(four), Error);
}

}  // namespace
}  // namespace tessera
