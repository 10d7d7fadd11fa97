// `tessera tradeoff`: the Pareto front by hand, the knobs' settings, and a short run on lavapipe
// whose errors must order as physics says (the truth's own BRDF is the most accurate) and whose
// speed-only knob must not change the image. No timing is asserted.
#include <cmath>
#include <fstream>
#include <iterator>
#include <tuple>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/check.h"
#include "core/environment.h"
#include "core/mesh.h"
#include "core/pareto.h"
#include "host/cli.h"
#include "host/tradeoff.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

TEST(Tradeoff, ParetoFrontByHand) {
  // (1, 5) and (2, 3) and (4, 1) are each best at something; (3, 4) is beaten by (2, 3);
  // (4, 2) by (4, 1) on error alone; the duplicate (2, 3) stays with its twin; NaN never counts.
  const std::vector<CostError> points = {{1, 5}, {2, 3}, {3, 4},    {4, 1},
                                         {4, 2}, {2, 3}, {0.5, NAN}};
  const std::vector<bool> expected = {true, true, false, true, false, true, false};
  EXPECT_EQ(pareto_front(points), expected);
  EXPECT_EQ(pareto_front({}), std::vector<bool>{});
}

TEST(Tradeoff, KnobsListTheirSettingsAndMarkTheDefault) {
  FrameSettings frame;
  frame.brdf = Brdf::filament;
  // Every choice made, as tuned_for_device leaves the options the tool gives knob_settings.
  RendererOptions options{.shade_tiles = false, .raster_shade = false};
  for (const KnobInfo& k : knobs()) {
    const std::vector<KnobSetting> settings = knob_settings(k.name, frame, options);
    EXPECT_GE(settings.size(), 2u) << k.name;
    EXPECT_EQ(std::count_if(settings.begin(), settings.end(),
                            [](const KnobSetting& s) { return s.is_default; }),
              1)
        << k.name << ": exactly one setting is the command line's";
  }
  const std::vector<KnobSetting> brdf = knob_settings("brdf", frame, options);
  EXPECT_EQ(brdf[3].label, "filament");
  EXPECT_TRUE(brdf[3].is_default);
  EXPECT_TRUE(brdf[4].frame.energy_compensation);
  // Level of detail: off, then auto at bounds from a quarter pixel to 4 px.
  const std::vector<KnobSetting> lod = knob_settings("lod", frame, options);
  ASSERT_EQ(lod.size(), 6u);
  EXPECT_EQ(lod[0].frame.lod, Lod::off);
  EXPECT_TRUE(lod[0].is_default);
  EXPECT_EQ(lod[2].label, "auto 0.5 px");
  EXPECT_EQ(lod[2].frame.lod, Lod::automatic);
  EXPECT_EQ(lod[2].frame.lod_error_px, 0.5f);
  EXPECT_EQ(lod[5].frame.lod_error_px, 4.0f);
  // The silhouette walk's steps: silhouette coverage at 4 samples, no limit the default.
  const std::vector<KnobSetting> walk = knob_settings("aa-walk-steps", frame, options);
  ASSERT_EQ(walk.size(), 5u);
  EXPECT_EQ(walk[1].label, "4 samples, 3 steps");
  EXPECT_EQ(walk[1].frame.silhouette_steps, 3u);
  EXPECT_EQ(walk[1].frame.aa_coverage, AaCoverage::silhouette);
  EXPECT_EQ(walk[1].frame.samples, 4u);
  EXPECT_TRUE(walk[4].is_default);
  const std::vector<KnobSetting> hdr = knob_settings("hdr", frame, options);
  ASSERT_EQ(hdr.size(), 2u);
  EXPECT_EQ(hdr[1].frame.hdr_format, HdrFormat::fp32);
  EXPECT_TRUE(hdr[0].is_default);
  // The tile size trades speed only, like the small-triangle threshold.
  const std::vector<KnobSetting> tiles = knob_settings("tile-size", frame, options);
  ASSERT_EQ(tiles.size(), 2u);
  for (const KnobSetting& t : tiles) EXPECT_TRUE(t.speed_only) << t.label;
  EXPECT_EQ(tiles[0].renderer.tile_size, 8u);
  EXPECT_TRUE(tiles[1].is_default);
  // So does depth rejection: off, then on (the default).
  const std::vector<KnobSetting> rejection = knob_settings("depth-rejection", frame, options);
  ASSERT_EQ(rejection.size(), 2u);
  for (const KnobSetting& r : rejection) EXPECT_TRUE(r.speed_only) << r.label;
  EXPECT_FALSE(rejection[0].renderer.depth_rejection);
  EXPECT_TRUE(rejection[1].renderer.depth_rejection);
  EXPECT_TRUE(rejection[1].is_default);
  // And shading by tiles: off, then on, the default that tuned_for_device gives lavapipe.
  RendererOptions tiled = options;
  tiled.shade_tiles = true;
  const std::vector<KnobSetting> shading = knob_settings("shade-tiles", frame, tiled);
  ASSERT_EQ(shading.size(), 2u);
  for (const KnobSetting& s : shading) EXPECT_TRUE(s.speed_only) << s.label;
  EXPECT_EQ(shading[0].renderer.shade_tiles, false);
  EXPECT_EQ(shading[1].renderer.shade_tiles, true);
  EXPECT_FALSE(shading[0].is_default);
  EXPECT_TRUE(shading[1].is_default);
  // And small frames in one pass: off, then on (a GPU's default).
  RendererOptions one_pass = options;
  one_pass.raster_shade = true;
  const std::vector<KnobSetting> raster = knob_settings("raster-shade", frame, one_pass);
  ASSERT_EQ(raster.size(), 2u);
  for (const KnobSetting& r : raster) EXPECT_TRUE(r.speed_only) << r.label;
  EXPECT_EQ(raster[0].renderer.raster_shade, false);
  EXPECT_EQ(raster[1].renderer.raster_shade, true);
  EXPECT_FALSE(raster[0].is_default);
  EXPECT_TRUE(raster[1].is_default);
  // From a CPU device's options (shading by tiles on, which the one pass does not go with),
  // "on" turns shading by tiles off, so that it measures the one pass; "off" is the default.
  RendererOptions cpu = options;
  cpu.shade_tiles = true;
  const std::vector<KnobSetting> from_cpu = knob_settings("raster-shade", frame, cpu);
  EXPECT_EQ(from_cpu[1].renderer.shade_tiles, false);
  EXPECT_EQ(from_cpu[0].renderer.shade_tiles, true);
  EXPECT_TRUE(from_cpu[0].is_default);
  EXPECT_FALSE(from_cpu[1].is_default);
  try {
    knob_settings("msaa", frame, options);
    FAIL() << "an unknown knob must throw";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("unknown knob 'msaa' (known: brdf, tessellation"),
              std::string::npos)
        << e.what();
  }
}

// A scene of one object: a single triangle (no sphere, no level of detail but its own) or a
// sphere, with a plain material, nothing to light it.
Scene one_object_scene(bool sphere) {
  Scene scene;
  Mesh triangle;
  triangle.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  triangle.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  triangle.indices = {0, 1, 2};
  scene.meshes = {sphere ? make_uv_sphere(16, 8) : triangle};
  scene.materials = {Material{}};
  scene.objects = {Object{}};
  return scene;
}

TEST(Tradeoff, KnobsThatCannotMatterForTheSceneSayWhy) {
  FrameSettings frame;
  auto why = [&](const char* knob, const Scene& scene) {
    return knob_cannot_matter(knob, scene, frame);
  };
  Scene bare = one_object_scene(false);
  // No light or environment: ambient and emission reach the image without a BRDF.
  EXPECT_EQ(why("brdf", bare),
            "the scene has no lights and no environment, the only light a BRDF shades");
  EXPECT_EQ(why("tessellation", bare),
            "the scene draws no spheres, the only meshes the knob re-tessellates");
  EXPECT_EQ(why("anisotropy", bare),
            "no material the scene draws with has a texture map, the only thing it filters");
  EXPECT_EQ(why("env-size", bare), "the scene has no environment");
  EXPECT_EQ(why("env-samples", bare), "the scene has no environment");
  // One triangle cannot be halved and keep a triangle: its chain is the base mesh alone.
  EXPECT_EQ(why("lod", bare), "no mesh the scene draws has a level of detail but its own");
  // What matters whatever the scene: visibility samples and their weights, the HDR storage,
  // the speed-only knobs.
  for (const char* knob : {"samples", "aa-coverage", "aa-walk-steps", "hdr", "small-triangle",
                           "tile-size", "depth-rejection", "shade-tiles", "raster-shade"})
    EXPECT_EQ(why(knob, bare), "") << knob;

  // Each reason goes with what it names.
  Scene lit = bare;
  lit.lights = {Light{}};
  EXPECT_EQ(why("brdf", lit), "");
  Scene sky = bare;
  sky.environment = std::make_shared<const Environment>(make_sky_environment(16));
  EXPECT_EQ(why("brdf", sky), "") << "the environment's light goes through the BRDF";
  EXPECT_EQ(why("env-size", sky), "");
  EXPECT_EQ(why("env-samples", sky), "");
  Scene textured = bare;
  textured.materials[0].normal_map = 0;
  EXPECT_EQ(why("anisotropy", textured), "");
  // A material with a map that no object draws with cannot matter either.
  Scene unused_map = bare;
  unused_map.materials.push_back(textured.materials[0]);
  EXPECT_NE(why("anisotropy", unused_map), "");
  const Scene sphere = one_object_scene(true);
  EXPECT_EQ(why("tessellation", sphere), "");
  EXPECT_EQ(why("lod", sphere), "");

  // Only one-sample frames without level of detail take the one pass.
  frame.samples = 4;
  EXPECT_EQ(why("raster-shade", bare),
            "the frames are at 4 samples, and only frames at 1 take the one pass");
  frame.samples = 1;
  frame.lod = Lod::automatic;
  EXPECT_EQ(why("raster-shade", bare),
            "the frames have level of detail, and only frames without take the one pass");
}

// The tessellation knob's default row says what the scene's spheres are, in the terms of the
// knob's other settings ("N slices": N segments, N / 2 stacks), counting only the meshes
// objects draw.
TEST(Tradeoff, TessellationDefaultNamesTheScenesSpheres) {
  const FrameSettings frame;
  const RendererOptions options{.shade_tiles = false, .raster_shade = false};
  auto own = [&](const std::vector<Mesh>& meshes, const std::vector<uint32_t>& drawn) {
    Scene scene;
    scene.meshes = meshes;
    scene.materials = {Material{}};
    for (uint32_t m : drawn) scene.objects.push_back(Object{.mesh = m});
    const std::vector<KnobSetting> settings = knob_settings("tessellation", frame, options, &scene);
    EXPECT_TRUE(settings.at(0).is_default);
    return settings.at(0).label;
  };
  const Mesh uv24 = make_uv_sphere(24, 12), ico2 = make_icosphere(2);
  EXPECT_EQ(own({uv24, uv24}, {0, 1, 0}), "scene's own (24 slices)");
  EXPECT_EQ(own({make_uv_sphere(24, 8)}, {0}), "scene's own (24 slices, 8 stacks)");
  EXPECT_EQ(own({ico2}, {0}), "scene's own (icosphere level 2)");
  // An undrawn mesh does not count.
  EXPECT_EQ(own({uv24, ico2}, {1}), "scene's own (icosphere level 2)");
  EXPECT_EQ(own({uv24, ico2}, {0, 1}), "scene's own (mixed: 24 slices; icosphere level 2)");
  EXPECT_EQ(own({uv24, ico2, make_uv_sphere(8, 4), make_icosphere(1)}, {0, 1, 2, 3}),
            "scene's own (mixed: 24 slices; icosphere level 2; 2 more)");
  // A sphere no builder makes (here one of radius 2): its triangles, 2 * 8 * (4 - 1).
  Mesh big = make_uv_sphere(8, 4);
  for (glm::vec3& p : big.positions) p *= 2.0f;
  big.analytic_sphere->radius = 2.0f;
  EXPECT_EQ(own({big}, {0}), "scene's own (48 triangles)");
  // Without a scene (the command line's checks), the plain label.
  EXPECT_EQ(knob_settings("tessellation", frame, options).at(0).label, "scene's own");
  // Spheres of one of the knob's tessellations are measured once, as the scene's own: 64
  // slices and 32 stacks is the scene's, so the settings are it, 8, 16, 32 and 128 slices.
  Scene sixty_four;
  sixty_four.meshes = {make_uv_sphere(64, 32)};
  sixty_four.materials = {Material{}};
  sixty_four.objects = {Object{}};
  std::vector<std::string> labels;
  for (const KnobSetting& s : knob_settings("tessellation", frame, options, &sixty_four))
    labels.push_back(s.label);
  EXPECT_EQ(labels, (std::vector<std::string>{"scene's own (64 slices)", "8 slices", "16 slices",
                                              "32 slices", "128 slices"}));
  // 24 slices is none of them: all five are measured beside it.
  sixty_four.meshes = {uv24};
  EXPECT_EQ(knob_settings("tessellation", frame, options, &sixty_four).size(), 6u);
}

// The truth has N x N samples per pixel; settings with as many or more are measured against
// a truth as coarse as they are, which is said (16 samples against the default 8 x 8 is not).
TEST(Tradeoff, ATruthNoFinerThanTheSettingsIsWarnedOf) {
  FrameSettings frame;
  EXPECT_EQ(coarse_truth_warning({"samples"}, frame, 8), "");  // 64 > 16
  EXPECT_EQ(coarse_truth_warning({"samples"}, frame, 5), "");  // 25 > 16
  EXPECT_EQ(coarse_truth_warning({"samples"}, frame, 4),
            "the ground truth takes 4 x 4 = 16 samples per pixel, no more than the 16 of the "
            "settings measured at the most: their edge errors are the truth's as much as theirs "
            "(give --truth-samples 5 or more)");
  EXPECT_EQ(coarse_truth_warning({"brdf"}, frame, 1), "");  // one sample a pixel throughout
  frame.samples = 4;                                        // --samples 4 (not a knob)
  EXPECT_NE(coarse_truth_warning({"brdf"}, frame, 2).find("2 x 2 = 4 samples"), std::string::npos);
  EXPECT_NE(coarse_truth_warning({"aa-coverage"}, frame, 2).find("--truth-samples 3"),
            std::string::npos);
}

TEST(Tradeoff, TheTruthIsDescribedAsConfiguredForTheScene) {
  FrameSettings frame;
  frame.brdf = Brdf::classic;
  // Nothing but the samples, the level of detail and the HDR range applies to a bare triangle
  // under ambient light: no spheres, textures, environment or BRDF to name.
  Scene scene = one_object_scene(false);
  scene.ambient = glm::vec3(1.0f);
  EXPECT_EQ(describe_truth(scene, frame, {"samples", "brdf"}, 4, 1024),
            "CPU reference, double precision: 4x4 samples per pixel (box filter), no level of "
            "detail, fp32 HDR range");
  // A sphere, a texture, an environment: each named, and the BRDFs the truths shade with.
  scene.meshes[0] = make_uv_sphere(16, 8);
  scene.materials[0].base_color_map = 0;
  scene.environment = std::make_shared<const Environment>(make_sky_environment(16));
  const std::string full =
      "CPU reference, double precision: analytic spheres, 8x8 samples per pixel (box filter), "
      "16x anisotropic texture filtering, no level of detail, fp32 HDR range, 1024 environment "
      "directions per lobe and pixel";
  EXPECT_EQ(describe_truth(scene, frame, {"samples", "brdf"}, 8, 1024),
            full +
                "; the brdf knob against the filament BRDF with energy compensation, the others "
                "against the classic BRDF (the settings')");
  // Each knob's truth by itself: the brdf knob's the most faithful, the others' the settings'.
  EXPECT_EQ(brdf_label(truth_shading("brdf", frame)), "filament+ec");
  EXPECT_EQ(brdf_label(truth_shading("tessellation", frame)), "classic");
  EXPECT_EQ(describe_truth(scene, frame, {"brdf"}, 8, 1024),
            full + "; the filament BRDF with energy compensation");
  frame.energy_compensation = true;
  EXPECT_EQ(describe_truth(scene, frame, {"samples"}, 8, 1024),
            full + "; the classic BRDF with energy compensation (the settings')");
  EXPECT_EQ(brdf_label(truth_shading("samples", frame)), "classic+ec");
  frame.brdf = Brdf::blinn_phong;  // which has no energy compensation (shaders/lighting.glsl)
  EXPECT_EQ(brdf_label(truth_shading("samples", frame)), "blinn-phong");
}

TEST(Tradeoff, TableColumnsLineUpWhateverTheirWidths) {
  // A setting's label longer than the header's column and a time of four digits before the
  // point: every value must still end where its column's header ends.
  TradeoffResults results;
  results.width = 64;
  results.height = 32;
  results.skipped = {{"anisotropy", "no texture"}};
  TradeoffPoint a;
  a.setting.knob = "aa-coverage";
  a.setting.label = "4 samples, silhouette";
  a.gpu_ms = {1234.5, 1000.25, 2345.125, 2};
  a.error.mean_relative = 0.5;
  TradeoffPoint b;
  b.setting.knob = "samples";
  b.setting.label = "1 sample";
  b.gpu_ms = {1.5, 1.25, 1.75, 2};
  b.error.mean_relative = 0.25;
  results.points = {a, b};
  TradeoffArgs args;
  args.warmup_ms = 0;
  const std::string table = tradeoff_table(results, args);
  std::vector<std::string> lines;
  for (size_t at = 0, end; (end = table.find('\n', at)) != std::string::npos; at = end + 1)
    lines.push_back(table.substr(at, end - at));
  const auto header = std::find_if(lines.begin(), lines.end(),
                                   [](const std::string& l) { return l.rfind("knob", 0) == 0; });
  ASSERT_NE(header, lines.end()) << table;
  ASSERT_GE(lines.end() - header, 3) << table;
  const std::string& row_a = header[1];
  const std::string& row_b = header[2];
  // Where each right-aligned header ends, each row's value ends: (its last character is at
  // that column and a space or the end follows).
  auto ends_at = [](const std::string& line, size_t end, const std::string& text) {
    return end >= text.size() && line.compare(end - text.size(), text.size(), text) == 0 &&
           (end == line.size() || line[end] == ' ');
  };
  for (const auto& [title, value_a, value_b] :
       std::vector<std::tuple<std::string, std::string, std::string>>{
           {"GPU ms", "1234.500", "1.500"},
           {"mean rel", "0.5000", "0.2500"},
           {"silh px", "0.000", "0.000"}}) {
    const size_t end = header->find(title) + title.size();
    EXPECT_TRUE(ends_at(row_a, end, value_a)) << title << "\n" << table;
    EXPECT_TRUE(ends_at(row_b, end, value_b)) << title << "\n" << table;
  }
  // The settings start under "setting"; the ranges' ".." one above the other.
  EXPECT_EQ(row_a.find("4 samples"), header->find("setting")) << table;
  EXPECT_EQ(row_b.find("1 sample"), header->find("setting")) << table;
  EXPECT_EQ(row_a.find(".."), row_b.find("..")) << table;
  // The knob left out is named with its reason, above the table.
  EXPECT_NE(table.find("not measured, as they cannot matter for this scene:\n  anisotropy: "
                       "no texture\n"),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("64x32"), std::string::npos) << table;
}

// The default row is what "image identical to default" compares with: it says so of no one. A
// truth of 12 ms is 12 ms, not "0.0 s".
TEST(Tradeoff, TableMarksAndTruthTime) {
  TradeoffResults results;
  results.truth = "T";
  results.truth_seconds = 0.012;
  TradeoffPoint def;
  def.setting.knob = "tile-size";
  def.setting.label = "16 px";
  def.setting.speed_only = def.setting.is_default = def.identical_to_default = true;
  TradeoffPoint other = def;
  other.setting.label = "8 px";
  other.setting.is_default = false;
  TradeoffPoint differs = other;
  differs.setting.label = "4 px";
  differs.identical_to_default = false;
  results.points = {def, other, differs};
  TradeoffArgs args;
  const std::string table = tradeoff_table(results, args);
  auto row = [&](const std::string& label) {
    const size_t at = table.find("tile-size  " + label);
    return at == std::string::npos ? "" : table.substr(at, table.find('\n', at) - at);
  };
  EXPECT_EQ(row("16 px").find("image identical"), std::string::npos) << table;
  EXPECT_NE(row("16 px").find("default"), std::string::npos) << table;
  EXPECT_NE(row("8 px").find("(image identical to default)"), std::string::npos) << table;
  EXPECT_NE(row("4 px").find("(IMAGE DIFFERS FROM DEFAULT)"), std::string::npos) << table;
  EXPECT_NE(table.find("truth: T (12 ms of CPU wall time)\n"), std::string::npos) << table;
  results.truth_seconds = 0.0004;
  EXPECT_NE(tradeoff_table(results, args).find("truth: T (under 1 ms of CPU wall time)\n"),
            std::string::npos);
  results.truth_seconds = 2.34;
  EXPECT_NE(tradeoff_table(results, args).find("truth: T (2.3 s of CPU wall time)\n"),
            std::string::npos);
  // These rows have no rounds (as if interrupted before any): the header says so, and says
  // nothing of it once every row has all of --rounds.
  EXPECT_NE(table.find("median of 3 rounds (fewer where a row says so) x"), std::string::npos)
      << table;
  EXPECT_NE(row("8 px").find("(0 of 3 rounds)"), std::string::npos) << table;
  for (TradeoffPoint& p : results.points) p.warmups.resize(args.rounds);
  EXPECT_NE(tradeoff_table(results, args).find("median of 3 rounds x"), std::string::npos);
}

// Settings of a knob whose time ranges overlap are named as not told apart by the run, pair by
// pair in time order; a knob whose ranges are apart, and ranges of different knobs, say nothing.
TEST(Tradeoff, TableNamesSettingsWhoseTimesOverlap) {
  TradeoffResults results;
  const auto point = [](const char* knob, const char* label, Summary ms) {
    TradeoffPoint p;
    p.setting.knob = knob;
    p.setting.label = label;
    p.gpu_ms = ms;
    return p;
  };
  results.points = {point("samples", "1 sample", {1.0, 0.9, 1.1, 30}),
                    point("samples", "8 samples", {3.0, 2.0, 4.0, 30}),
                    point("samples", "4 samples", {2.0, 1.5, 2.5, 30}),
                    point("tile-size", "16 px", {5.0, 4.9, 5.1, 30}),
                    point("tile-size", "8 px", {5.5, 5.2, 5.8, 30})};
  TradeoffArgs args;
  std::string table = tradeoff_table(results, args);
  // 4 samples (1.5..2.5) and 8 samples (2.0..4.0) overlap; 1 sample (..1.1) is apart from 4
  // (1.5..); tile-size's 16 px (..5.1) is apart from 8 px (5.2..), and from samples.
  EXPECT_NE(table.find("note: 1 pair of settings next to each other in time whose GPU times "
                       "overlap (min..max):\n  samples: 4 samples (1.500..2.500) and 8 samples "
                       "(2.000..4.000)\n  their order in time"),
            std::string::npos)
      << table;
  EXPECT_EQ(table.find("1 sample (0.900"), std::string::npos) << table;
  EXPECT_EQ(table.find("tile-size: "), std::string::npos) << table;
  // Ranges apart everywhere: no note.
  results.points[1].gpu_ms = {3.0, 2.6, 4.0, 30};
  table = tradeoff_table(results, args);
  EXPECT_EQ(table.find("note: "), std::string::npos) << table;
}

TEST(Tradeoff, ParsesItsOptionsAndRejectsBadOnes) {
  const CommandLine line = parse_command_line({"tradeoff", "--scene", "grid", "--objects", "49",
                                               "--knob", "brdf,small-triangle", "--size", "64x32",
                                               "--rounds", "2", "--truth-samples", "4"});
  ASSERT_EQ(line.command, Command::tradeoff);
  EXPECT_EQ(line.tradeoff.scene, "grid");
  EXPECT_EQ(line.tradeoff.objects, 49u);
  EXPECT_EQ(line.tradeoff.knobs, (std::vector<std::string>{"brdf", "small-triangle"}));
  EXPECT_EQ(line.tradeoff.frame.width, 64u);
  EXPECT_EQ(line.tradeoff.rounds, 2u);
  EXPECT_EQ(line.tradeoff.truth_samples, 4u);
  EXPECT_EQ(line.tradeoff.warmup_ms, 200.0) << "by time by default, as bench";
  auto message = [](const std::vector<std::string>& args) {
    try {
      parse_command_line(args);
    } catch (const UsageError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message({"tradeoff"}).find("--knob is required"), std::string::npos)
      << message({"tradeoff"});
  // --objects has bench's limit (it took up to 10^8 and failed after building the scene), and
  // a count whose triangles Tessera cannot number is refused, naming it, before the scene is
  // built: 960 triangles a grid sphere, 4473924 * 960 < 2^32 <= 4473925 * 960.
  EXPECT_NE(message({"tradeoff", "--knob", "brdf", "--objects", "16777217"})
                .find("--objects: expects a whole number from 1 to 16777216"),
            std::string::npos);
  TradeoffArgs many = line.tradeoff;
  many.objects = 4473925;
  try {
    load_tradeoff_scene(many);
    ADD_FAILURE() << "4473925 grid spheres accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--objects 4473925: 960 triangles per object make "
                                         "4294968000 triangle instances, more than the 2^32 - 1 "
                                         "Tessera can number (at most 4473924 objects)"),
              std::string::npos)
        << e.what();
  }
  EXPECT_NE(message({"tradeoff", "--knob", "speed"}).find("unknown knob 'speed'"),
            std::string::npos);
  EXPECT_NE(message({"tradeoff", "--knob", "brdf", "--truth-samples", "64"})
                .find("--truth-samples: expects a whole number from 1 to 32"),
            std::string::npos);
  EXPECT_NE(message({"tradeoff", "--knob", "brdf", "--chart", "c.jpg"}).find("--chart"),
            std::string::npos);
  // A knob twice would be measured twice; objects for a scene of its own would be ignored.
  EXPECT_NE(
      message({"tradeoff", "--knob", "brdf,tile-size,brdf"}).find("--knob: 'brdf' is given twice"),
      std::string::npos);
  EXPECT_NE(message({"tradeoff", "--knob", "brdf", "--knob", "brdf"})
                .find("--knob: 'brdf' is given twice"),
            std::string::npos);
  EXPECT_NE(message({"tradeoff", "--knob", "brdf", "--scene", "spheres", "--objects", "10"})
                .find("--objects applies to the benchmark families (grid, scatter, huge, "
                      "yardstick), not to 'spheres'"),
            std::string::npos);
  EXPECT_EQ(message({"tradeoff", "--knob", "brdf", "--scene", "yardstick", "--objects", "10"}),
            "no error");
  // The --help says what the truths are, and that the knobs' errors do not add up.
  const std::string help = parse_command_line({"tradeoff", "--help"}).help;
  EXPECT_NE(help.find("The brdf knob is measured against the filament BRDF with energy\n"
                      "compensation, every other knob against the settings' BRDF"),
            std::string::npos)
      << help;
  EXPECT_NE(help.find("the knobs are not measured against one truth, and their\nerrors do not "
                      "add up"),
            std::string::npos)
      << help;
}

TEST(Tradeoff, ShortRunOrdersTheBrdfsAndKeepsSpeedOnlyImages) {
  const std::string base = test::output_path("tradeoff");
  std::string out;
  const std::string command =
      std::string(TESSERA_BINARY) +
      " tradeoff --device lavapipe --validate --scene spheres --knob "
      "brdf,anisotropy,small-triangle,tile-size,depth-rejection,shade-tiles --size 48x48 "
      "--repeat 1 "
      "--rounds 1 "
      "--truth-samples 4 --warmup 1 --warmup-ms 1 --json " +
      base + ".json --chart " + base + ".svg";
  ASSERT_EQ(test::run_command(command, out), 0) << out;
  std::ifstream f(base + ".json");
  ASSERT_TRUE(f) << base << ".json";
  const nlohmann::json j = nlohmann::json::parse(f);
  EXPECT_EQ(j["width"], 48);
  const auto& points = j["points"];
  ASSERT_EQ(points.size(), 17u);  // brdf 5, small-triangle 6, the others 2 each
  // The spheres have no texture maps: anisotropy is left out, and said to be.
  ASSERT_EQ(j["skipped_knobs"].size(), 1u) << j["skipped_knobs"].dump();
  EXPECT_EQ(j["skipped_knobs"][0]["knob"], "anisotropy");
  EXPECT_NE(out.find("  anisotropy: no material the scene draws with has a texture map"),
            std::string::npos)
      << out;
  for (const auto& p : points) EXPECT_NE(p["knob"], "anisotropy");
  // The truth shades with filament and energy compensation: that setting's interior error
  // (shading alone, edges apart) must be the lowest of the BRDF knob's, and well below
  // Blinn-Phong's, which is a different model altogether.
  double filament_ec = 0.0, blinn = 0.0, lowest_other = 1e9;
  for (const auto& p : points) {
    if (p["knob"] != "brdf") continue;
    const double e = p["interior_mean_relative_error"];
    if (p["setting"] == "filament+ec") {
      filament_ec = e;
    } else {
      lowest_other = std::min(lowest_other, e);
      if (p["setting"] == "blinn-phong") blinn = e;
    }
  }
  EXPECT_LT(filament_ec, lowest_other) << out;
  EXPECT_LT(filament_ec, 0.5 * blinn) << out;
  // Each point names its truth's BRDF: the brdf knob's filament+ec, the others' the settings'
  // (classic, the default), and the chart says so under its legend.
  for (const auto& p : points)
    EXPECT_EQ(p["truth_brdf"], p["knob"] == "brdf" ? "filament+ec" : "classic") << p.dump();
  // The small-triangle threshold, the tile size, depth rejection and shading by tiles trade
  // speed only: every image equals the default's.
  for (const auto& p : points) {
    // Every setting warmed up once (one round) for at least --warmup frames.
    ASSERT_EQ(p["warmups"].size(), 1u) << p.dump();
    EXPECT_GE(p["warmups"][0]["frames"].get<int>(), 1) << p.dump();
    if (p["knob"] != "small-triangle" && p["knob"] != "tile-size" &&
        p["knob"] != "depth-rejection" && p["knob"] != "shade-tiles")
      continue;
    EXPECT_TRUE(p["identical_to_default"].get<bool>()) << p.dump();
    EXPECT_GT(p["gpu_ms"]["median"].get<double>(), 0.0);
  }
  EXPECT_EQ(j["warmup"]["min_ms"], 1.0);
  int on_front = 0;
  for (const auto& p : points) on_front += p["pareto_front"].get<bool>();
  EXPECT_GE(on_front, 2);
  std::ifstream svg(base + ".svg");
  const std::string chart(std::istreambuf_iterator<char>(svg), {});
  EXPECT_NE(chart.find("Pareto front"), std::string::npos);
  EXPECT_NE(chart.find("filament+ec"), std::string::npos);
  EXPECT_NE(chart.find(">  anisotropy<"), std::string::npos) << "named as not measured";
  EXPECT_NE(chart.find(">  brdf knob: filament+ec<"), std::string::npos);
  EXPECT_NE(chart.find(">  other knobs: classic<"), std::string::npos);
}

TEST(Tradeoff, EveryLodRowUnderAnEnvironmentHasItsPrecompute) {
  // One sphere of 224 triangles near the camera, under a sky: at 0.25 to 1 px the levels of
  // detail are finer than the mesh, and the first frame of those settings is redone with larger
  // batches (compute/renderer.cpp) after the attempt that precomputed the environment. Every
  // setting precomputes it once (each has a renderer of its own), and every row must say how
  // long that took: those rows said nothing (the JSON 0).
  const std::string base = test::output_path("tradeoff_lod_environment");
  {
    std::ofstream scene(base + ".json");
    scene << R"({"version": 1,
      "camera": {"position": [0, 0, 3], "target": [0, 0, 0], "vertical_fov_degrees": 40},
      "environment": {"type": "sky", "width": 64},
      "meshes": [{"name": "sphere", "type": "sphere", "segments": 16, "rings": 8}],
      "materials": [{"name": "m", "base_color": [0.9, 0.9, 0.9], "roughness": 0.3}],
      "objects": [{"name": "s", "mesh": "sphere", "material": "m"}]})";
  }
  std::string out;
  const std::string command = std::string(TESSERA_BINARY) + " tradeoff --device lavapipe --scene " +
                              base + ".json --knob lod --size 64x64 --repeat 1 --rounds 1 " +
                              "--warmup 0 --warmup-ms 0 --truth-samples 1 --truth-env-samples 16 " +
                              "--json " + base + "_out.json";
  ASSERT_EQ(test::run_command(command, out), 0) << out;
  std::ifstream f(base + "_out.json");
  const nlohmann::json j = nlohmann::json::parse(f);
  ASSERT_EQ(j["points"].size(), 6u) << "off, then auto at 5 bounds";
  for (const auto& p : j["points"]) {
    EXPECT_GT(p["environment_precompute_ms"].get<double>(), 0.0) << p["setting"] << "\n" << out;
    // The table's row says it too.
    const std::string label = p["setting"];
    const size_t row = out.find("lod   " + label + " ");
    ASSERT_NE(row, std::string::npos) << label << "\n" << out;
    EXPECT_NE(out.substr(row, out.find('\n', row) - row).find("precompute"), std::string::npos)
        << label << "\n"
        << out;
  }
}

TEST(Tradeoff, NothingToMeasureIsAnErrorNamingEachKnobsReason) {
  std::string out;
  const std::string command =
      std::string(TESSERA_BINARY) +
      " tradeoff --device lavapipe --scene spheres --knob anisotropy,env-size";
  EXPECT_EQ(test::run_command(command, out), 1) << out;
  EXPECT_NE(out.find("tessera: error: nothing to measure: no knob asked for can matter for "
                     "scene 'spheres':\n  anisotropy: no material the scene draws with has a "
                     "texture map, the only thing it filters\n  env-size: the scene has no "
                     "environment"),
            std::string::npos)
      << out;
}

TEST(Tradeoff, ObjectsNeedABenchFamily) {
  std::string out;
  const std::string command = std::string(TESSERA_BINARY) +
                              " tradeoff --device lavapipe --scene spheres --objects 5 --knob brdf";
  // A bad command line: status 2 and the pointer to --help, as every other.
  EXPECT_EQ(test::run_command(command, out), 2) << out;
  EXPECT_NE(out.find("--objects applies to the benchmark families"), std::string::npos) << out;
  EXPECT_NE(out.find("tessera tradeoff --help"), std::string::npos) << out;
}

}  // namespace
}  // namespace tessera
