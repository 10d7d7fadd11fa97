// `tessera tradeoff`: the Pareto front by hand, the knobs' settings, and a short run on lavapipe
// whose errors must order as physics says (the truth's own BRDF is the most accurate) and whose
// speed-only knob must not change the image. No timing is asserted.
#include <cmath>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/check.h"
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
}

TEST(Tradeoff, ShortRunOrdersTheBrdfsAndKeepsSpeedOnlyImages) {
  const std::string base = test::output_path("tradeoff");
  std::string out;
  const std::string command =
      std::string(TESSERA_BINARY) +
      " tradeoff --device lavapipe --validate --scene spheres --knob "
      "brdf,small-triangle,tile-size,depth-rejection,shade-tiles --size 48x48 --repeat 1 "
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
