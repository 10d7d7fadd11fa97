// `tessera bench` as a smoke test on lavapipe: a short sweep over every backend writes CSV, JSON
// and charts. Not a timing assertion: speed is measured in bench/ and docs/performance.md.
#include <algorithm>
#include <fstream>
#include <functional>
#include <iterator>
#include <sstream>
#include <tuple>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "core/bench_scenes.h"
#include "core/check.h"
#include "core/image.h"
#include "core/mesh.h"
#include "core/warmup.h"
#include "host/bench_compare.h"
#include "host/bench_report.h"
#include "host/cli.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

std::string read_text(const std::string& path) {
  std::ifstream f(path);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

// The cells of a CSV row of `tessera bench`: commas inside double quotes (the device name, the
// note) belong to their cell.
std::vector<std::string> split_csv_row(const std::string& row) {
  std::vector<std::string> cells(1);
  bool quoted = false;
  for (char c : row) {
    if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      cells.emplace_back();
    } else {
      cells.back() += c;
    }
  }
  return cells;
}

TEST(BenchCli, ShortSweepWritesCsvJsonAndCharts) {
  for (const auto& family : bench_families()) {
    const std::string base = test::output_path(std::string(family.name));
    std::string out;
    const std::string command =
        std::string(TESSERA_BINARY) + " bench --device lavapipe --validate --scene " +
        std::string(family.name) +
        " --objects 1,3 --size 64x48 --segments 8 --backends compute,hardware,reference "
        "--repeat 2 --warmup 0 --warmup-ms 0 --csv " +
        base + ".csv --json " + base + ".json --chart " + base + ".svg";
    ASSERT_EQ(test::run_command(command, out), 0) << out;
    EXPECT_NE(out.find("compute / hardware"), std::string::npos) << out;
    const std::string csv = read_text(base + ".csv");
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 2 * 3)
        << csv;  // header + 2 counts x 3 backends
    EXPECT_NE(csv.find("\"" + std::string(family.name) + "\",3,hardware,64,48"), std::string::npos)
        << csv;
    // What the hardware baseline does not measure (rasterized triangles, the passes, batches)
    // is left empty, not written as a measured 0; the compute rows have it.
    std::istringstream rows(csv);
    std::string header;
    std::getline(rows, header);
    const std::vector<std::string> names = split_csv_row(header);
    // Every row ends with the settings its points were measured with (lavapipe's rasterizer
    // settings where none were given), after the measured columns, which keep their places.
    EXPECT_TRUE(header.starts_with("scene,objects,backend,width,height,triangles_submitted,"))
        << header;
    const size_t note = std::find(names.begin(), names.end(), "note") - names.begin();
    const RasterTuning cpu = raster_tuning(VK_PHYSICAL_DEVICE_TYPE_CPU);
    const std::pair<const char*, std::string> settings[] = {
        {"samples", "1"},
        {"aa_coverage", "count"},
        {"lod", "off"},
        {"segments", "8"},
        {"small_triangle_area", std::to_string(cpu.small_triangle_max_area)},
        {"tile_size", "16"},
        {"shade_tiles", cpu.shade_tiles ? "true" : "false"},
        {"tile_lists", tile_lists_name(cpu.tile_lists)},
        {"hdr_format", "fp16"},
        {"generic_shading", "false"},
        {"warmup_min_frames", "0"},
        {"warmup_min_ms", "0"},
        {"raster_shade", cpu.raster_shade ? "true" : "false"}};
    for (std::string row; std::getline(rows, row);) {
      const std::vector<std::string> cells = split_csv_row(row);
      ASSERT_EQ(cells.size(), names.size()) << row;
      for (const auto& [column, value] : settings) {
        const size_t i = std::find(names.begin(), names.end(), column) - names.begin();
        ASSERT_LT(i, names.size()) << column << " in " << header;
        EXPECT_GT(i, note) << column << " comes after the measured columns";
        EXPECT_EQ(cells[i], value) << column << " in " << row;
      }
      const size_t driver = std::find(names.begin(), names.end(), "driver") - names.begin();
      ASSERT_LT(driver, names.size()) << header;
      EXPECT_NE(cells[driver], "") << row;
      const bool hardware = cells[2] == "hardware", compute = cells[2] == "compute";
      // Measured per point, but new: at the end, after the settings.
      EXPECT_EQ(names.back(), "rasterized_and_shaded") << header;
      EXPECT_EQ(cells.back(), compute ? "false" : "") << row;
      // One run has no spread; the reference has no warm-up and records no command buffer.
      const auto cell = [&](const char* column) {
        const size_t i = std::find(names.begin(), names.end(), column) - names.begin();
        return i < cells.size() ? cells[i] : std::string("(no column)");
      };
      EXPECT_EQ(cell("runs"), "1") << row;
      EXPECT_EQ(cell("run_spread_pct"), "") << row;
      for (const char* column : {"warmup_frames", "warmup_ms", "warmup_stable", "cpu_record_ms"}) {
        if (cells[2] == "reference") {
          EXPECT_EQ(cell(column), "") << column << " in " << row;
        } else {
          EXPECT_NE(cell(column), "") << column << " in " << row;
        }
      }
      // A flag, written as the CSV's other flags are (docs/performance.md, "Columns").
      if (cells[2] != "reference") {
        EXPECT_TRUE(cell("warmup_stable") == "true" || cell("warmup_stable") == "false") << row;
      }
      for (const char* column : {"triangles_rasterized", "setup_ms", "shade_ms", "batches",
                                 "tile_entries", "tile_list_stride"}) {
        const size_t i = std::find(names.begin(), names.end(), column) - names.begin();
        ASSERT_LT(i, names.size()) << column;
        if (hardware) {
          EXPECT_EQ(cells[i], "") << column << " in " << row;
        }
        if (compute) {
          EXPECT_NE(cells[i], "") << column << " in " << row;
        }
      }
    }
    const std::string json = read_text(base + ".json");
    EXPECT_NE(json.find("\"backend\": \"hardware\", \"triangles_submitted\": "), std::string::npos);
    EXPECT_NE(json.find("\"triangles_rasterized\": null"), std::string::npos) << json;
    EXPECT_NE(json.find("\"batches\": null"), std::string::npos) << json;
    EXPECT_NE(json.find("\"passes_ms\": null"), std::string::npos) << json;
    EXPECT_NE(json.find("\"run_spread_pct\": null"), std::string::npos) << json;
    EXPECT_NE(json.find("\"warmup_frames\": null"), std::string::npos) << json;
    EXPECT_NE(json.find("\"statistic\": \"median\""), std::string::npos);
    EXPECT_NE(json.find("\"compute_over_hardware\": [{\"objects\": 1"), std::string::npos) << json;
    const std::string svg = read_text(base + ".svg");
    EXPECT_NE(svg.find("<svg"), std::string::npos);
    EXPECT_NE(svg.find(">setup</text>"), std::string::npos) << "the per-pass breakdown is drawn";
  }
  const std::string png = test::output_path("grid.png");
  std::string out;
  ASSERT_EQ(test::run_command(std::string(TESSERA_BINARY) +
                                  " bench --device lavapipe --validate --objects 1,2 --size 32x32 "
                                  "--segments 6 --repeat 1 "
                                  "--warmup 0 --warmup-ms 0 --quiet --chart " +
                                  png,
                              out),
            0)
      << out;
  Image8 chart = read_png(png);
  EXPECT_EQ(chart.width, 1300u);
}

// Two objects: "a" one triangle, "b" a quad (2 triangles) and a triangle; bounding box [0, 1]^3.
constexpr const char* kTwoObjects =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\n"
    "o a\nf 1 2 3\no b\nf 1 2 3 4\nf 1 2 5\n";

TEST(BenchCli, ModelFileIsPlacedNTimesOnTheGrid) {
  const std::string obj = test::output_path("two_objects.obj");
  std::ofstream(obj) << kTwoObjects;
  const std::string csv_path = test::output_path("two_objects.csv");
  std::string out;
  ASSERT_EQ(test::run_command(std::string(TESSERA_BINARY) + " bench --device lavapipe --validate " +
                                  "--scene " + obj +
                                  " --objects 1,3 --size 32x32 --backends compute,reference "
                                  "--repeat 1 --warmup 0 --warmup-ms 0 --quiet --csv " +
                                  csv_path,
                              out),
            0)
      << out;
  const std::string csv = read_text(csv_path);
  // N copies: 2 N objects and 4 N triangles (columns objects, backend, size, submitted).
  EXPECT_NE(csv.find(",2,compute,32,32,4,"), std::string::npos) << csv;
  EXPECT_NE(csv.find(",6,compute,32,32,12,"), std::string::npos) << csv;
  EXPECT_NE(csv.find(",6,reference,32,32,12,"), std::string::npos) << csv;
  // --strict, as for render: a scene file's unknown key is an error, not a warning.
  const std::string scene = test::output_path("unknown_key.json");
  std::ofstream(scene) << R"({"models": [{"name": "m", "file": "two_objects.obj"}],
                             "objects": [{"model": "m"}], "colour": 1})";
  const std::string bench = std::string(TESSERA_BINARY) + " bench --device lavapipe --scene " +
                            scene + " --objects 1 --size 16x16 --backends reference --repeat 1 " +
                            "--warmup 0 --warmup-ms 0 --quiet";
  ASSERT_EQ(test::run_command(bench, out), 0) << out;
  ASSERT_EQ(test::run_command(bench + " --strict", out), 1) << out;
  EXPECT_NE(out.find("colour: unknown key 'colour'"), std::string::npos) << out;
}

TEST(BenchCli, InstancedCopiesFillGridCells) {
  Scene content;
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}};
  m.normals.assign(3, {0, 0, 1});
  m.uvs.assign(3, {0, 0});
  m.indices = {0, 1, 2};
  content.meshes.push_back(m);
  content.materials.push_back({});
  content.objects.push_back({0, 0, glm::mat4(1.0f)});
  // A second object: the same triangle moved up by 1 in z, so the box is [0, 1]^3.
  content.objects.push_back({0, 0, glm::translate(glm::mat4(1.0f), {0.0f, 0.0f, 1.0f})});
  const Scene s = make_instanced_bench_scene(content, 3, 1.0f);
  ASSERT_EQ(s.objects.size(), 6u);
  EXPECT_EQ(s.meshes.size(), 1u) << "copies share the content's meshes";
  // Centre (0.5, 0.5, 0.5), radius sqrt(3) / 2 -> unit sphere. 3 copies at aspect 1: 2 x 2
  // cells 2.5 apart, the first at (-1.25, -1.25, 0); the origin vertex of its first object
  // lands at the cell centre minus 0.5 / (sqrt(3) / 2) = 1 / sqrt(3) on each axis.
  const float d = 1.0f / std::sqrt(3.0f);
  const glm::vec3 p0 = glm::vec3(s.objects[0].transform * glm::vec4(0, 0, 0, 1));
  EXPECT_NEAR(glm::distance(p0, glm::vec3(-1.25f - d, -1.25f - d, -d)), 0.0f, 1e-5f);
  // Copy 2 (third cell: column 0, row 1), second object: vertex (1, 1, 0) + z 1.
  const glm::vec3 p5 = glm::vec3(s.objects[5].transform * glm::vec4(1, 1, 0, 1));
  EXPECT_NEAR(glm::distance(p5, glm::vec3(-1.25f + d, 1.25f + d, d)), 0.0f, 1e-5f);
  EXPECT_EQ(s.lights.size(), 4u) << "content without lights gets the grid's four";
}

// The triangle (0, 0, 0), (1, 0, 0), (0, 1, 0) as glTF `name` (its buffer beside it), placed by
// nodes[0] at `translation`, with KHR_lights_punctual light `light` on nodes[1] at (0, 0, 2)
// unless `light` is null.
std::string write_triangle_gltf(const std::string& name, const nlohmann::json& translation,
                                const nlohmann::json& light) {
  const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  std::ofstream(test::output_path(name + ".bin"), std::ios::binary)
      .write(reinterpret_cast<const char*>(positions), sizeof positions);
  nlohmann::json doc = nlohmann::json::parse(R"({"asset": {"version": "2.0"}, "scene": 0,
    "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                   "min": [0, 0, 0], "max": [1, 1, 0]}],
    "bufferViews": [{"buffer": 0, "byteLength": 36}],
    "buffers": [{"byteLength": 36}]})");
  doc["buffers"][0]["uri"] = name + ".bin";
  doc["nodes"][0]["translation"] = translation;
  if (!light.is_null()) {
    doc["extensionsUsed"] = nlohmann::json::array({"KHR_lights_punctual"});
    doc["extensions"]["KHR_lights_punctual"]["lights"] = nlohmann::json::array({light});
    doc["nodes"].push_back(
        {{"translation", {0, 0, 2}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    doc["scenes"][0]["nodes"].push_back(1);
  }
  const std::string path = test::output_path(name);
  std::ofstream(path) << doc.dump();
  return path;
}

// `tessera bench` sweeping `scene` over `objects` at 32x32 with the reference backend: its
// exit status, and its output in `out`.
int bench_model(const std::string& scene, const std::string& objects, std::string& out) {
  return test::run_command(std::string(TESSERA_BINARY) + " bench --device lavapipe --scene " +
                               scene + " --objects " + objects +
                               " --size 32x32 --backends reference --repeat 1 --warmup 0 "
                               "--warmup-ms 0",
                           out);
}

// A model file given to bench is held to the scene's limits as a scene file placing it once,
// unmoved, holds it (SceneFile.ModelsBreakingSceneLimitsAreNamedInTheModelFile): the message
// names the model file and the place in it. It said "invalid scene: light 0 intensity times
// color is 9.15081e+27" (the value scaled by the placement) with no file, and accepted a node
// at 2e15 m, whose vertices the placement then scaled from float rounding.
TEST(BenchCli, ModelFileBreakingSceneLimitsIsNamedInIt) {
  std::string out;
  // 1e30 cd / 683 lm/W = 1.46413e27 W/sr, above 1e26.
  std::string model =
      write_triangle_gltf("limit_light.gltf", {0, 0, 0}, {{"type", "point"}, {"intensity", 1e30}});
  EXPECT_EQ(bench_model(model, "1", out), 1) << out;
  EXPECT_NE(
      out.find("tessera: error: " + model +
               ": extensions.KHR_lights_punctual.lights[0].intensity: invalid scene: light 0 "
               "intensity times color is 1.46413e+27, above 1e+26 W/sr (KHR_lights_punctual's "
               "candela or lux divided by 683 lm/W)\n"),
      std::string::npos)
      << out;
  model = write_triangle_gltf("limit_range.gltf", {0, 0, 0},
                              {{"type", "point"}, {"intensity", 1}, {"range", 2e9}});
  EXPECT_EQ(bench_model(model, "1", out), 1) << out;
  EXPECT_NE(out.find("tessera: error: " + model +
                     ": extensions.KHR_lights_punctual.lights[0].range: invalid scene: light 0 "
                     "range is 2e+09 m; it must be 0 (no fade) or within [0.001, 1e+09] m\n"),
            std::string::npos)
      << out;
  // No NORMAL: flat normals, so the vertex is named by its value.
  model = write_triangle_gltf("limit_node.gltf", {2e15, 0, 0}, nullptr);
  EXPECT_EQ(bench_model(model, "1", out), 1) << out;
  EXPECT_NE(out.find("tessera: error: " + model +
                     ": nodes[0]: invalid scene: object 0 reaches outside +-1e+15 m per coordinate "
                     "in world space (meshes[0].primitives[0].attributes.POSITION value (0, 0, 0) "
                     "is placed at (2e+15, 0, 0))\n"),
            std::string::npos)
      << out;
  const std::string obj = test::output_path("limit_vertex.obj");
  std::ofstream(obj) << "# a triangle\nv 0 0 0\nv 2e15 0 0\nv 0 1 0\nf 1 2 3\n";
  EXPECT_EQ(bench_model(obj, "1", out), 1) << out;
  EXPECT_NE(out.find("tessera: error: '" + obj +
                     "' line 3: invalid scene: object 0 reaches outside +-1e+15 m per coordinate "
                     "in world space (its vertex (2e+15, 0, 0) is placed at (2e+15, 0, 0))\n"),
            std::string::npos)
      << out;
}

// A light within the limits in the file can be past them once the bench moves it with the
// copies: the message names the file and the place, and says by how much the placement scaled
// the value, before any count is measured. By hand: the triangle's bounding sphere has centre
// (0.5, 0.5, 0) and radius sqrt(0.5); 1 copy's grid (one cell of 2.5) has half diagonal
// 0.5 * 2.5 * sqrt(2) = 2.5 sqrt(0.5), 4 copies' (2 x 2) 0.5 * 2.5 * sqrt(8) = 5 sqrt(0.5), so
// the lights scale by 2.5 and by 5. 6.83e27 cd is 1e25 W/sr: 6.25e25 for 1 copy, within 1e26;
// 2.5e26 for 4, past it.
TEST(BenchCli, LightsThePlacementScalesPastTheLimitsAreExplained) {
  const std::string model = write_triangle_gltf("scaled_light.gltf", {0, 0, 0},
                                                {{"type", "point"}, {"intensity", 6.83e27}});
  std::string out;
  ASSERT_EQ(bench_model(model, "1", out), 0) << out;
  EXPECT_EQ(bench_model(model, "1,4", out), 1) << out;
  const std::string place = "tessera: error: --objects 4: " + model +
                            ": extensions.KHR_lights_punctual.lights[0].intensity: invalid "
                            "scene: light 0 intensity times color is ";
  const size_t at = out.find(place);
  ASSERT_NE(at, std::string::npos) << out;
  EXPECT_NEAR(std::stod(out.substr(at + place.size())), 2.5e26, 1e21) << out;
  EXPECT_NE(out.find("; the file's value is within the limits, but the bench scaled it by 25 "
                     "(5 squared): it moves the file's lights with its 4 copies on the grid, so "
                     "that they light each copy as they lit the file's objects\n",
                     at),
            std::string::npos)
      << out;
  EXPECT_EQ(out.find("median ms"), std::string::npos) << "refused before measuring: " << out;
  // A scene file's light is named by the line of its entry, as the file's own errors are; the
  // second light (line 6) is the one past the limit, the first is dim.
  const std::string file = test::output_path("scaled_light.json");
  std::ofstream(file)
      << "{\"meshes\": [{\"name\": \"s\", \"type\": \"sphere\"}],\n"
         " \"materials\": [{\"name\": \"m\"}],\n"
         " \"objects\": [{\"mesh\": \"s\", \"material\": \"m\"}],\n"
         " \"lights\": [\n"
         "   {\"type\": \"point\", \"position\": [0, 0, 2], \"intensity\": 1},\n"
         "   {\"type\": \"point\", \"position\": [0, 0, 2], \"intensity\": 1e25}]}\n";
  ASSERT_EQ(bench_model(file, "1", out), 0) << out;
  EXPECT_EQ(bench_model(file, "1,1000", out), 1) << out;
  EXPECT_NE(out.find("tessera: error: --objects 1000: " + file +
                     ":6:4: lights[1]: invalid scene: light 1 intensity times color is "),
            std::string::npos)
      << out;
}

// The yardstick family against the issue's formulas worked by hand: side = ceil(sqrt N),
// centre (((i mod side) + 0.5) / side * 2 - 1) * 3, (((i div side) + 0.5) / side * 2 - 1) * 1.7,
// radius 0.45 * 3.4 / side = 1.53 / side.
TEST(BenchCli, YardstickLayoutIsTheMinimalProgramsLayout) {
  struct Case {
    uint32_t objects, i;
    glm::vec3 centre;
    float radius;
  };
  const Case cases[] = {
      {1, 0, {0.0f, 0.0f, 0.0f}, 1.53f},           // side 1: the one cell's centre
      {10, 0, {-2.25f, -1.275f, 0.0f}, 0.3825f},   // side 4: (0.25 - 1) * 3, (0.25 - 1) * 1.7
      {10, 9, {-0.75f, 0.425f, 0.0f}, 0.3825f},    // column 1, row 2: (0.75 - 1) * 3, 0.25 * 1.7
      {49, 24, {0.0f, 0.0f, 0.0f}, 1.53f / 7.0f},  // side 7: the middle cell (3, 3)
      {49, 48, {18.0f / 7.0f, 10.2f / 7.0f, 0.0f}, 1.53f / 7.0f},  // (13/7 - 1) * 3, * 1.7
  };
  for (const Case& c : cases) {
    const Scene s = make_bench_scene("yardstick", c.objects, 32, 16.0f / 9.0f);
    ASSERT_EQ(s.objects.size(), c.objects);
    EXPECT_EQ(s.meshes[0].triangle_count(), 960u);
    const glm::mat4& m = s.objects[c.i].transform;
    const glm::vec3 centre = glm::vec3(m * glm::vec4(0, 0, 0, 1));
    const glm::vec3 east = glm::vec3(m * glm::vec4(1, 0, 0, 1));  // the unit sphere's +x pole
    EXPECT_NEAR(glm::distance(centre, c.centre), 0.0f, 1e-5f) << c.objects << " " << c.i;
    EXPECT_NEAR(glm::distance(east, c.centre + glm::vec3(c.radius, 0, 0)), 0.0f, 1e-5f)
        << c.objects << " " << c.i;
    EXPECT_EQ(s.camera.position, glm::vec3(0, 0, 3));
    EXPECT_EQ(s.camera.target, glm::vec3(0));
    EXPECT_NEAR(s.camera.vertical_fov, 3.14159265f / 3.0f, 1e-6f);
    ASSERT_EQ(s.lights.size(), 4u);
    EXPECT_EQ(s.lights[3].position, glm::vec3(4, -4, 4));
  }
}

// The minimal graphics program computes its layout from the issue's formulas itself, projects
// with its own matrices and rasterizes on the device's graphics pipeline: the pixels it covers
// must be those the compute path's visibility buffer holds for the yardstick family, at every
// rung of its ladder (--variant all).
TEST(BenchCli, MinimalProgramCoversTheYardsticksPixels) {
#ifndef TESSERA_MINIMAL_GRAPHICS
  GTEST_SKIP() << "built without bench/ (TESSERA_BUILD_BENCH off)";
#else
  const std::string minimal = test::output_path("minimal.json");
  const std::string bench = test::output_path("yardstick.json");
  const std::string common =
      " --device lavapipe --objects 1,10,49 --size 96x54 --repeat 1 "
      "--warmup 0 --warmup-ms 0 --json ";
  std::string out;
  // The validation layer prints to stdout when no messenger is installed.
  ASSERT_EQ(test::run_command("VK_INSTANCE_LAYERS=VK_LAYER_KHRONOS_validation " +
                                  std::string(TESSERA_MINIMAL_GRAPHICS) + " --variant all" +
                                  common + minimal,
                              out),
            0)
      << out;
  EXPECT_EQ(out.find("Validation"), std::string::npos) << out;
  ASSERT_EQ(test::run_command(std::string(TESSERA_BINARY) +
                                  " bench --validate --scene yardstick --backends compute "
                                  "--quiet" +
                                  common + bench,
                              out),
            0)
      << out;
  std::ifstream m(minimal), b(bench);
  const nlohmann::json mj = nlohmann::json::parse(m), bj = nlohmann::json::parse(b);
  // Rung after rung, each with the three counts in order.
  const size_t rungs = 8;
  ASSERT_EQ(mj["results"].size(), 3u * rungs);
  ASSERT_EQ(bj["results"].size(), 3u);
  for (size_t k = 0; k < mj["results"].size(); ++k) {
    const nlohmann::json& m = mj["results"][k];
    const nlohmann::json& b = bj["results"][k % 3];
    EXPECT_EQ(m["variant"], k / 3);
    EXPECT_EQ(m["objects"], b["objects"]);
    EXPECT_GT(int(m["pixels_shaded"]), 1000);
    EXPECT_EQ(m["pixels_shaded"], b["pixels_shaded"])
        << "rung " << m["backend"] << ", objects " << m["objects"];
  }
  EXPECT_EQ(mj["results"][0]["backend"], "minimal");
#endif
}

TEST(BenchCli, ParsesEveryOption) {
  const std::string base = test::output_path("base.json");  // --compare's file must exist
  std::ofstream(base) << "{}";
  const CommandLine line = parse_command_line({"bench",
                                               "--scene",
                                               "scatter",
                                               "--objects",
                                               "2,20,200",
                                               "--size",
                                               "64x32",
                                               "--segments",
                                               "8",
                                               "--device",
                                               "lavapipe",
                                               "--backends",
                                               "reference,compute",
                                               "--repeat",
                                               "4",
                                               "--warmup",
                                               "1",
                                               "--warmup-ms",
                                               "250",
                                               "--runs",
                                               "3",
                                               "--compare",
                                               base,
                                               "--reference-max-triangles",
                                               "1000",
                                               "--small-triangle-area",
                                               "16",
                                               "--generic-shading",
                                               "--csv",
                                               "a.csv",
                                               "--json",
                                               "a.json",
                                               "--chart",
                                               "a.svg",
                                               "--validate",
                                               "--quiet"});
  ASSERT_EQ(line.command, Command::bench);
  const BenchArgs& a = line.bench;
  EXPECT_EQ(a.scene, "scatter");
  EXPECT_EQ(a.objects, (std::vector<uint32_t>{2, 20, 200}));
  EXPECT_EQ(a.width, 64u);
  EXPECT_EQ(a.height, 32u);
  EXPECT_EQ(a.segments, 8u);
  EXPECT_EQ(a.device, "lavapipe");
  EXPECT_EQ(a.backends, (std::vector<std::string>{"reference", "compute"}));
  EXPECT_EQ(a.repeat, 4u);
  EXPECT_EQ(a.warmup, 1u);
  EXPECT_EQ(a.warmup_ms, 250.0);
  EXPECT_EQ(a.runs, 3u);
  EXPECT_EQ(a.compare, base);
  EXPECT_EQ(a.reference_max_triangles, 1000u);
  EXPECT_EQ(a.small_triangle_area, 16u);
  EXPECT_TRUE(a.generic_shading);
  EXPECT_EQ(a.csv, "a.csv");
  EXPECT_EQ(a.json, "a.json");
  EXPECT_EQ(a.chart, "a.svg");
  EXPECT_TRUE(a.validate);
  EXPECT_TRUE(a.quiet);
  // Defaults: the documented sweep.
  const BenchArgs d = parse_command_line({"bench"}).bench;
  EXPECT_EQ(d.objects, (std::vector<uint32_t>{1, 10, 100}));
  EXPECT_EQ(d.backends, (std::vector<std::string>{"compute", "hardware"}));
  EXPECT_EQ(d.repeat, 10u);
  EXPECT_EQ(d.warmup, 2u);
  EXPECT_EQ(d.warmup_ms, 500.0);
  EXPECT_EQ(d.runs, 1u);
  EXPECT_EQ(d.compare, "");
}

TEST(BenchCli, HelpListsEveryOption) {
  const CommandLine line = parse_command_line({"bench", "--help"});
  ASSERT_EQ(line.command, Command::help);
  for (const char* option : {"Usage: tessera bench",
                             "--scene NAME",
                             "--objects LIST",
                             "--size WxH",
                             "--segments S",
                             "--device D",
                             "--backends LIST",
                             "--repeat K",
                             "--warmup K",
                             "--warmup-ms MS",
                             "--runs K",
                             "--compare BASE.json",
                             "--reference-max-triangles T",
                             "--small-triangle-area A",
                             "--generic-shading",
                             "--csv FILE",
                             "--json FILE",
                             "--chart FILE",
                             "--validate",
                             "--quiet",
                             "Exit status"}) {
    EXPECT_NE(line.help.find(option), std::string::npos) << option << " in\n" << line.help;
  }
}

TEST(BenchCli, BadArgumentsNameTheOption) {
  auto error = [](std::vector<std::string> args) {
    args.insert(args.begin(), "bench");
    try {
      parse_command_line(args);
    } catch (const UsageError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string forest = error({"--scene", "forest"});
  EXPECT_NE(forest.find("--scene: unknown benchmark scene 'forest' (known: grid, scatter, huge, "
                        "yardstick); or a built-in scene (bench-grid, environment, "),
            std::string::npos)
      << forest;
  EXPECT_NE(forest.find("; or a scene file (.json) or model (.gltf, .glb, .obj)"),
            std::string::npos)
      << forest;
  EXPECT_NE(error({"--objects", "1,10,1"}).find("--objects: 1 is given twice"), std::string::npos);
  EXPECT_NE(error({"--compare", "/nonexistent/base.json"})
                .find("--compare: no file '/nonexistent/base.json'"),
            std::string::npos);
  EXPECT_NE(error({"--compare", test::output_path("")}).find("' is a folder, not a --json file"),
            std::string::npos);
  EXPECT_NE(error({"--objects", "1,x"}).find("--objects: expects a whole number"),
            std::string::npos);
  EXPECT_NE(error({"--objects", "0"}).find("--objects: expects a whole number from 1"),
            std::string::npos);
  // As many as a scene file may hold, 2^24: 10^8 spheres took minutes and 9 GB to be refused.
  EXPECT_NE(
      error({"--objects", "16777217"}).find("--objects: expects a whole number from 1 to 16777216"),
      std::string::npos);
  // A scene of its own is one point: a count for it would be measured as something else.
  EXPECT_NE(error({"--scene", "spheres", "--objects", "5"})
                .find("--objects: 'spheres' is a scene with objects of its own, measured as one "
                      "point; --objects applies to the benchmark families (grid, scatter, huge, "
                      "yardstick) and to scene or model files"),
            std::string::npos);
  EXPECT_EQ(error({"--scene", "spheres"}), "");
  EXPECT_EQ(error({"--scene", "huge", "--objects", "5"}), "");
  EXPECT_NE(error({"--objects", "1", "2"}).find("unexpected argument '2'"), std::string::npos);
  EXPECT_NE(error({"--backends", "compute,magic"})
                .find("--backends: expects compute, hardware or "
                      "reference, got 'magic'"),
            std::string::npos);
  EXPECT_NE(error({"--chart", "c.jpg"}).find("--chart: expects a .svg file or a .png file"),
            std::string::npos);
  EXPECT_NE(error({"--segments", "2"}).find("--segments: expects a whole number from 4"),
            std::string::npos);
  EXPECT_NE(error({"--repeat", "0"}).find("--repeat:"), std::string::npos);
  EXPECT_NE(error({"--warmup", "101"}).find("--warmup: expects a whole number from 0 to 100"),
            std::string::npos);
  EXPECT_NE(error({"--warmup-ms", "-1"}).find("--warmup-ms:"), std::string::npos);
  EXPECT_NE(error({"--runs", "0"}).find("--runs: expects a whole number from 1 to 100"),
            std::string::npos);
  EXPECT_NE(error({"--size", "0x5"}).find("--size: width"), std::string::npos);
  EXPECT_NE(error({"--small-triangle-area", "-1"}).find("--small-triangle-area:"),
            std::string::npos);
  EXPECT_NE(error({"--reference-max-triangles", "0"}).find("--reference-max-triangles:"),
            std::string::npos);
  EXPECT_NE(error({"--turbo"}).find("unknown option '--turbo'"), std::string::npos);
}

// An output that cannot be written is a bad command line (status 2), found before the sweep
// spends any time.
TEST(BenchCli, UnwritableOutputFailsBeforeMeasuring) {
  std::string out;
  for (const char* option : {"--csv", "--json"}) {
    EXPECT_EQ(test::run_command(std::string(TESSERA_BINARY) + " bench --device lavapipe " + option +
                                    " /nonexistent-dir/x.out",
                                out),
              2);
    EXPECT_NE(out.find("tessera: error: " + std::string(option) +
                       ": cannot write '/nonexistent-dir/x.out': folder '/nonexistent-dir' does "
                       "not exist"),
              std::string::npos)
        << out;
  }
  EXPECT_EQ(out.find("objects"), std::string::npos) << "no table: nothing was measured\n" << out;
}

// A scene file's path is the CSV's first cell whatever it holds: quoted, so that a comma in
// it does not shift the row's columns (RFC 4180, as the device and note cells are).
TEST(BenchCli, SceneFilePathWithACommaStaysOneCell) {
  const std::string scene = test::output_path("a,b.json");
  std::ofstream(scene) << R"({"meshes": [{"name": "s", "type": "sphere", "segments": 8}],
    "materials": [{"name": "m"}], "ambient": [1, 1, 1],
    "objects": [{"mesh": "s", "material": "m"}]})";
  const std::string csv_path = test::output_path("comma_scene.csv");
  std::string out;
  ASSERT_EQ(test::run_command(std::string(TESSERA_BINARY) + " bench --device lavapipe --scene '" +
                                  scene + "' --size 16x16 --backends compute --repeat 1 " +
                                  "--warmup 0 --warmup-ms 0 --quiet --csv " + csv_path,
                              out),
            0)
      << out;
  std::istringstream rows(read_text(csv_path));
  std::string header, row;
  std::getline(rows, header);
  std::getline(rows, row);
  const std::vector<std::string> names = split_csv_row(header), cells = split_csv_row(row);
  EXPECT_EQ(cells.size(), names.size()) << row;
  EXPECT_EQ(cells[0], scene) << row;
  EXPECT_EQ(cells[2], "compute") << row;
}

// Frames for warm_up with a clock of their own: frame k (from 1) returns sequence[k - 1] (then
// the last value again) and moves the clock to k ms.
struct FakeFrames {
  std::vector<double> sequence;
  int calls = 0;
  std::function<double()> frame() {
    return [this] { return sequence[std::min<size_t>(calls++, sequence.size() - 1)]; };
  }
  std::function<double()> clock() {
    return [this] { return double(calls); };
  }
};

TEST(BenchWarmup, StopsWhenTheMedianOfTheLastFiveFramesSettles) {
  // Frame times 10 8 6 4 2 then 1s, 5 ms asked for. After frame 13 the last five (9..13) are
  // all 1 and the five before (4..8: 4 2 1 1 1) have median 1 too: settled. After frame 12
  // the five before (3..7: 6 4 2 1 1) have median 2: not yet.
  FakeFrames f{{10, 8, 6, 4, 2, 1}};
  const WarmupStats w =
      warm_up(f.frame(), {.min_frames = 2, .ms = 5, .window = 5, .tolerance = 0.02}, f.clock());
  EXPECT_EQ(w.frames, 13u);
  EXPECT_EQ(w.ms, 13.0);
  EXPECT_TRUE(w.stable);
  // Settled from the start, it still runs for the time asked: 5 ms after the first frame.
  FakeFrames flat{{1}};
  const WarmupStats early =
      warm_up(flat.frame(), {.min_frames = 0, .ms = 30, .window = 5}, flat.clock());
  EXPECT_EQ(early.frames, 31u);
  EXPECT_TRUE(early.stable);
}

TEST(BenchWarmup, GivesUpAtTheCapAndSaysSo) {
  // Medians of five alternate between 1 and 2 forever: never settled. 5 ms capped at 4x:
  // stops once 20 ms have passed after the first frame, at frame 21.
  FakeFrames f{{}};
  for (int i = 0; i < 100; ++i) f.sequence.push_back(1 + i % 2);
  const WarmupStats w = warm_up(
      f.frame(), {.min_frames = 2, .ms = 5, .window = 5, .tolerance = 0.02, .cap_factor = 4},
      f.clock());
  EXPECT_FALSE(w.stable);
  EXPECT_EQ(w.frames, 21u);
}

TEST(BenchWarmup, ZeroMillisecondsMeansTheFrameCountAlone) {
  FakeFrames f{{5, 4, 3}};
  const WarmupStats w = warm_up(f.frame(), {.min_frames = 3, .ms = 0}, f.clock());
  EXPECT_EQ(w.frames, 3u);
  EXPECT_FALSE(w.stable);
  FakeFrames none{{5}};
  EXPECT_EQ(warm_up(none.frame(), {.min_frames = 0, .ms = 0}, none.clock()).frames, 0u);
}

nlohmann::json read_json(const std::string& path) {
  std::ifstream f(path);
  return nlohmann::json::parse(f);
}

TEST(BenchCli, RunsRepeatTheSweepAndReportTheirSpreadAndWarmup) {
  const std::string json_path = test::output_path("runs.json");
  const std::string csv_path = test::output_path("runs.csv");
  std::string out;
  ASSERT_EQ(test::run_command(std::string(TESSERA_BINARY) +
                                  " bench --device lavapipe --validate --scene yardstick "
                                  "--objects 1,2 --size 32x32 --segments 8 --repeat 2 --runs 3 "
                                  "--warmup 1 --warmup-ms 20 --json " +
                                  json_path + " --csv " + csv_path,
                              out),
            0)
      << out;
  for (const char* text : {"median ms", "min ms", "max ms", "spread", "warm-up", "3 runs"})
    EXPECT_NE(out.find(text), std::string::npos) << text << " in\n" << out;
  const nlohmann::json j = read_json(json_path);
  EXPECT_EQ(j["runs"], 3);
  EXPECT_EQ(j["warmup"]["min_ms"], 20.0);
  ASSERT_EQ(j["results"].size(), 4u);
  for (const nlohmann::json& r : j["results"]) {
    const std::vector<double> runs = r["run_ms"];
    ASSERT_EQ(runs.size(), 3u) << r;
    std::vector<double> sorted = runs;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(double(r["total_ms"]), sorted[1]) << "the median of three runs' medians";
    // The compute path's passes are timed in frames of their own (Timing::per_pass).
    if (r["backend"] == "compute") {
      EXPECT_GT(double(r["per_pass_total_ms"]), 0.0) << r;
    }
    // The file holds 9 significant digits.
    const double spread = (sorted[2] - sorted[0]) / sorted[1] * 100.0;
    EXPECT_NEAR(double(r["run_spread_pct"]), spread, 1e-6 * spread + 1e-9);
    EXPECT_LE(double(r["min_ms"]), sorted[0]);
    EXPECT_GE(double(r["max_ms"]), sorted[2]);
    // Each run warms up for at least one frame and 20 ms after its first frame.
    EXPECT_GE(int(r["warmup_frames"]), 3 * 2) << r;
    EXPECT_GE(double(r["warmup_ms"]), 3 * 20.0) << r;
    EXPECT_TRUE(r["warmup_stable"].is_boolean()) << r;
  }
  const std::string csv = read_text(csv_path);
  EXPECT_NE(csv.find("min_ms,max_ms,runs,run_spread_pct,warmup_frames,warmup_ms,warmup_stable"),
            std::string::npos)
      << csv;
}

// A saved run written by hand; the ratios expected below are worked out from it.
constexpr const char* kBase = R"({
  "device": "hand", "date": "2026-11-29T00:00:00Z", "scene": "yardstick", "width": 32,
  "height": 32, "results": [
    {"objects": 1, "backend": "compute", "total_ms": 2.0},
    {"objects": 1, "backend": "hardware", "total_ms": 4.0},
    {"objects": 7, "backend": "compute", "total_ms": 1.0}
  ]
})";

// Without --small-triangle-area and --depth-rejection, bench takes the device's settings
// (raster_tuning: lavapipe is a CPU device) and its JSON says which; given, they win. A
// --quality preset's small-triangle area, the GPUs' setting, leaves a CPU device's as it is
// (docs/tradeoffs.md, "Presets").
TEST(BenchCli, RasterizerSettingsAreTheDevicesUnlessGiven) {
  const RasterTuning cpu = raster_tuning(VK_PHYSICAL_DEVICE_TYPE_CPU);
  const std::string base = std::string(TESSERA_BINARY) +
                           " bench --device lavapipe --validate --objects 1 --size 32x32 "
                           "--segments 6 --backends compute --repeat 1 --warmup 0 "
                           "--warmup-ms 0 --quiet --json ";
  const std::string tuned = test::output_path("tuned.json");
  const std::string given = test::output_path("given.json");
  const std::string preset = test::output_path("preset.json");
  std::string out;
  ASSERT_EQ(test::run_command(base + tuned, out), 0) << out;
  ASSERT_EQ(test::run_command(base + preset + " --quality draft", out), 0) << out;
  ASSERT_EQ(
      test::run_command(base + given + " --small-triangle-area 64 --depth-rejection off", out), 0)
      << out;
  const nlohmann::json t = read_json(tuned), g = read_json(given), p = read_json(preset);
  EXPECT_EQ(t["small_triangle_area"], cpu.small_triangle_max_area);
  EXPECT_EQ(p["small_triangle_area"], cpu.small_triangle_max_area);
  EXPECT_EQ(t["depth_rejection"], cpu.depth_rejection);
  EXPECT_EQ(g["small_triangle_area"], 64);
  EXPECT_EQ(g["depth_rejection"], false);
}

// The heading lists the settings that apply to what was measured: the CPU reference takes the
// size, samples and the family's segments, but neither it nor the hardware baseline has the
// compute path's rasterizer settings (small triangles, shading by tiles, tile lists, the
// one-pass path), which a run that measures the compute path lists.
TEST(BenchCli, HeadingListsOnlyTheSettingsOfTheBackendsMeasured) {
  const std::string base = std::string(TESSERA_BINARY) +
                           " bench --device lavapipe --scene grid --objects 1 --size 24x16 "
                           "--segments 6 --repeat 1 --warmup 0 --warmup-ms 0 ";
  const char* compute_settings[] = {"small-triangle area", "shading by tiles", "tile lists",
                                    "raster and shade in one pass"};
  // The heading's first line (a driver may say something before it).
  const auto heading = [](const std::string& out) {
    const size_t start = out.find("scene grid");
    return start == std::string::npos ? "" : out.substr(start, out.find('\n', start) - start);
  };
  std::string out;
  ASSERT_EQ(test::run_command(base + "--samples 4 --backends reference", out), 0) << out;
  EXPECT_EQ(heading(out),
            "scene grid, 24x16, 4 samples per pixel, count coverage, 6 segments, device "
            "'reference (CPU)',")
      << out;
  ASSERT_EQ(test::run_command(base + "--backends hardware,reference", out), 0) << out;
  EXPECT_TRUE(
      heading(out).starts_with("scene grid, 24x16, 1 sample per pixel, 6 segments, "
                               "device '"))
      << out;
  for (const char* setting : compute_settings)
    EXPECT_EQ(heading(out).find(setting), std::string::npos) << setting << "\n" << out;
  ASSERT_EQ(test::run_command(base + "--backends reference,compute", out), 0) << out;
  for (const char* setting : compute_settings)
    EXPECT_NE(heading(out).find(setting), std::string::npos) << setting << "\n" << out;
}

// The chart's title says how many frames each series' medians are of: the CPU reference times
// at most 3 (kReferenceMaxFrames) of the 5 asked, so a title of 5 alone was untrue of its series.
TEST(BenchCli, ChartTitleSaysTheReferencesFewerFrames) {
  const std::string chart = test::output_path("bench.svg");
  const std::string base = std::string(TESSERA_BINARY) +
                           " bench --device lavapipe --scene grid --objects 1 --size 24x16 "
                           "--segments 6 --repeat 5 --warmup 0 --warmup-ms 0 --quiet --chart " +
                           chart + " --backends ";
  std::string out;
  ASSERT_EQ(test::run_command(base + "compute,reference", out), 0) << out;
  EXPECT_NE(read_text(chart).find("(medians of 5 frames; reference: medians of 3 frames)"),
            std::string::npos)
      << read_text(chart);
  ASSERT_EQ(test::run_command(base + "reference", out), 0) << out;
  EXPECT_NE(read_text(chart).find("(medians of 3 frames)"), std::string::npos) << read_text(chart);
  ASSERT_EQ(test::run_command(base + "compute", out), 0) << out;
  EXPECT_NE(read_text(chart).find("(medians of 5 frames)"), std::string::npos) << read_text(chart);
}

// The CSV and JSON say, point by point, whether the compute path's timed frames were rasterized
// and shaded in one pass: on lavapipe only when asked for and with shading by tiles off (one
// sphere at 32x32 is far below the pass's limits), never for the other backends.
TEST(BenchCli, CsvAndJsonSayWhichPointsTookTheOnePass) {
  const std::string base = test::output_path("one_pass");
  std::string out;
  ASSERT_EQ(test::run_command(std::string(TESSERA_BINARY) +
                                  " bench --device lavapipe --validate --objects 1 --size 32x32 "
                                  "--segments 6 --backends compute,hardware --repeat 2 "
                                  "--warmup 1 --warmup-ms 0 --quiet --raster-shade on "
                                  "--shade-tiles off --tile-lists direct --csv " +
                                  base + ".csv --json " + base + ".json",
                              out),
            0)
      << out;
  std::istringstream rows(read_text(base + ".csv"));
  std::string header, compute, hardware;
  std::getline(rows, header);
  std::getline(rows, compute);
  std::getline(rows, hardware);
  const std::vector<std::string> names = split_csv_row(header);
  const size_t setting = std::find(names.begin(), names.end(), "raster_shade") - names.begin();
  ASSERT_LT(setting, names.size()) << header;
  EXPECT_EQ(split_csv_row(compute)[setting], "true") << compute;
  EXPECT_EQ(names.back(), "rasterized_and_shaded") << header;
  EXPECT_TRUE(compute.starts_with("\"grid\",1,compute,")) << compute;
  EXPECT_EQ(split_csv_row(compute).back(), "true") << compute;
  EXPECT_TRUE(hardware.starts_with("\"grid\",1,hardware,")) << hardware;
  EXPECT_EQ(split_csv_row(hardware).back(), "") << hardware;
  const nlohmann::json j = read_json(base + ".json");
  EXPECT_EQ(j["raster_shade"], true);
  EXPECT_EQ(j["results"][0]["rasterized_and_shaded"], true) << j["results"][0];
  EXPECT_TRUE(j["results"][1]["rasterized_and_shaded"].is_null()) << j["results"][1];
}

// Counts whose triangle instances the renderer could not number are refused before any scene
// is built, naming the most objects that fit: 4,473,924 spheres of 960 triangles
// (floor((2^32 - 1) / 960)), where 2^24 spheres were refused only after a minute of building.
TEST(BenchCli, CountsPastTheTriangleNumberingAreRefusedFirst) {
  std::string out;
  EXPECT_EQ(test::run_command(std::string(TESSERA_BINARY) +
                                  " bench --device lavapipe --objects 1,4473925 --size 32x32 "
                                  "--backends compute --repeat 1 --warmup 0 --warmup-ms 0",
                              out),
            1)
      << out;
  EXPECT_NE(out.find("--objects 4473925: 960 triangles per object make 4294968000 triangle "
                     "instances, more than the 2^32 - 1 Tessera can number (at most 4473924 "
                     "objects)"),
            std::string::npos)
      << out;
  EXPECT_EQ(out.find("median ms"), std::string::npos) << "refused before measuring: " << out;
}

// Counts whose object buffer would be larger than the device binds (lavapipe's
// maxStorageBufferRange, 128 MiB = 2^27 bytes) are refused before any scene is built, too:
// 10^6 spheres of 960 triangles need 160 bytes each and a group word per 256 triangle
// instances, 160e6 + 3.75e6 * 4 = 175e6 bytes (166.9 MiB), and 2^27 / 175 = 766958.4 fit.
TEST(BenchCli, CountsPastTheStorageRangeAreRefusedFirst) {
  std::string out;
  EXPECT_EQ(test::run_command(std::string(TESSERA_BINARY) +
                                  " bench --device lavapipe --objects 1,1000000 --size 32x32 "
                                  "--backends compute --repeat 1 --warmup 0 --warmup-ms 0",
                              out),
            1)
      << out;
  EXPECT_NE(out.find("--objects 1000000: the scene needs a 167 MiB object buffer (1000000 "
                     "objects), more than this device's maxStorageBufferRange (128 MiB): it "
                     "holds at most 766958 objects"),
            std::string::npos)
      << out;
  EXPECT_EQ(out.find("median ms"), std::string::npos) << "refused before measuring: " << out;
}

TEST(BenchCli, CompareMatchesPointsAndComputesNewOverOld) {
  const std::string base_path = test::output_path("base.json");
  std::ofstream(base_path) << kBase;
  const SavedRun base = read_bench_json(base_path);
  ASSERT_EQ(base.points.size(), 3u);
  EXPECT_EQ(base.device, "hand");
  BenchResults results;
  for (auto [objects, backend, ms] :
       {std::tuple{1u, "compute", 3.0}, {1u, "hardware", 1.0}, {2u, "compute", 5.0}}) {
    BenchRow r;
    r.objects = objects;
    r.backend = backend;
    r.total_ms = ms;
    results.rows.push_back(r);
  }
  BenchArgs a;
  a.scene = "yardstick";
  a.width = a.height = 32;
  const std::vector<ComparedPoint> c = compare_runs(base, results, a);
  ASSERT_EQ(c.size(), 4u);
  EXPECT_TRUE(c[0].matched());
  EXPECT_EQ(c[0].ratio(), 1.5);   // 3 / 2
  EXPECT_EQ(c[1].ratio(), 0.25);  // 1 / 4
  EXPECT_FALSE(c[2].matched());   // 2 objects: only in this run
  EXPECT_EQ(c[2].new_ms, 5.0);
  EXPECT_FALSE(c[3].matched());  // 7 objects: only in the base
  EXPECT_EQ(c[3].point.objects, 7u);
  // Another size matches nothing: every point is unmatched on one side or the other.
  a.width = 64;
  const std::vector<ComparedPoint> other = compare_runs(base, results, a);
  EXPECT_EQ(other.size(), 6u);
  for (const ComparedPoint& p : other) EXPECT_FALSE(p.matched());
}

// A base whose sweep a signal stopped lacks the points it did not reach: the comparison says
// so, rather than listing them as "only in this run" as if the base had never planned them.
TEST(BenchCli, CompareWarnsOfAnInterruptedBase) {
  const std::string path = test::output_path("base_interrupted.json");
  std::ofstream(path) << R"({"scene": "grid", "width": 32, "height": 32, "interrupted": true,
      "measurements_planned": 6, "measurements_made": 2,
      "results": [{"objects": 1, "backend": "compute", "total_ms": 2.0}]})";
  const SavedRun base = read_bench_json(path);
  EXPECT_TRUE(base.interrupted);
  EXPECT_EQ(base.measurements_planned, 6u);
  EXPECT_EQ(base.measurements_made, 2u);
  testing::internal::CaptureStdout();
  print_comparison(base, {}, {}, base.device);
  const std::string out = testing::internal::GetCapturedStdout();
  EXPECT_NE(out.find("tessera: warning: the base's sweep was interrupted after 2 of 6 "
                     "measurements: it lacks the points it did not reach"),
            std::string::npos)
      << out;
  // A complete run, and a file from before the flag was recorded, are not so marked.
  const std::string whole = test::output_path("base_whole.json");
  std::ofstream(whole) << kBase;
  testing::internal::CaptureStdout();
  print_comparison(read_bench_json(whole), {}, {}, "hand");
  const std::string quiet = testing::internal::GetCapturedStdout();
  EXPECT_EQ(quiet.find("interrupted"), std::string::npos) << quiet;
}

// The table's rasterized count: "-" where it is not measured (the hardware path), "0" where
// the compute path rasterized none (every triangle culled); it printed "-" for both.
TEST(BenchCli, TableTellsAnUnmeasuredCountFromAZeroOne) {
  BenchRow compute;
  compute.objects = 1;
  compute.backend = "compute";
  compute.triangles_submitted = 960;
  compute.triangles_rasterized = 0;
  BenchRow hardware = compute;
  hardware.backend = "hardware";
  testing::internal::CaptureStdout();
  print_bench_row(compute, BenchArgs{});
  print_bench_row(hardware, BenchArgs{});
  const std::string out = testing::internal::GetCapturedStdout();
  const std::string first = out.substr(0, out.find('\n')), second = out.substr(out.find('\n'));
  EXPECT_NE(first.find(" compute        960          0 "), std::string::npos) << out;
  EXPECT_NE(second.find(" hardware        960          - "), std::string::npos) << out;
}

TEST(BenchCli, CompareFlagPrintsOldNewAndRatio) {
  const std::string base_path = test::output_path("base_cli.json");
  std::ofstream(base_path) << kBase;
  const std::string json_path = test::output_path("compared.json");
  std::string out;
  ASSERT_EQ(test::run_command(std::string(TESSERA_BINARY) +
                                  " bench --device lavapipe --scene yardstick --objects 1,2 "
                                  "--size 32x32 --segments 8 --repeat 1 --warmup 0 "
                                  "--warmup-ms 0 --json " +
                                  json_path + " --compare " + base_path,
                              out),
            0)
      << out;
  const nlohmann::json j = read_json(json_path);
  for (const nlohmann::json& r : j["results"]) {
    if (r["objects"] != 1) continue;
    const double old_ms = r["backend"] == "compute" ? 2.0 : 4.0;
    char line[128];
    std::snprintf(line, sizeof(line), "%10.3f %10.3f %10.3f", old_ms, double(r["total_ms"]),
                  double(r["total_ms"]) / old_ms);
    EXPECT_NE(out.find(line), std::string::npos) << line << " in\n" << out;
  }
  EXPECT_NE(out.find("only in this run: yardstick, 2 objects, 32x32, compute"), std::string::npos)
      << out;
  EXPECT_NE(out.find("only in the base: yardstick, 7 objects, 32x32, compute"), std::string::npos)
      << out;
  // kBase has no per_pass_total_ms: its compute frames were timed pass by pass.
  EXPECT_NE(out.find("tessera: note: the base timed its compute frames pass by pass"),
            std::string::npos)
      << out;
  // A file this version wrote has it, and is not so marked.
  EXPECT_TRUE(read_bench_json(test::output_path("base_cli.json")).compute_timed_by_pass);
  EXPECT_FALSE(read_bench_json(json_path).compute_timed_by_pass);
  // kBase was measured on device "hand": the ratios compare devices, and the run says so.
  EXPECT_NE(
      out.find("tessera: warning: the base was measured on device 'hand', this run on 'llvmpipe"),
      std::string::npos)
      << out;
  EXPECT_EQ(out.find("warning: no point of this run is in the base"), std::string::npos) << out;
  // Another size shares no point with the base: said, rather than left to an empty table.
  ASSERT_EQ(test::run_command(std::string(TESSERA_BINARY) +
                                  " bench --device lavapipe --scene yardstick --objects 1 "
                                  "--size 16x16 --segments 8 --repeat 1 --warmup 0 "
                                  "--warmup-ms 0 --compare " +
                                  base_path,
                              out),
            0)
      << out;
  EXPECT_NE(out.find("tessera: warning: no point of this run is in the base, which measured "
                     "yardstick at 32x32"),
            std::string::npos)
      << out;
  // No ratio to show: no table header without rows.
  EXPECT_EQ(out.find("new / old\n"), std::string::npos) << out;
  EXPECT_NE(out.find("only in this run: yardstick, 1 object, 16x16, compute"), std::string::npos)
      << out;
}

// A base recorded with other frame settings is compared, with a warning naming each setting
// that differs (keys the base does not record, as in files from before them, are not).
TEST(BenchCli, CompareWarnsOfSettingsThatDiffer) {
  const std::string path = test::output_path("base_settings.json");
  std::ofstream(path) << R"({"scene": "spheres", "width": 32, "height": 32, "samples": 4,
      "aa_coverage": "silhouette", "aa_walk_steps": 3, "tile_size": 16,
      "results": [{"objects": 49, "backend": "compute", "total_ms": 2.0}]})";
  const SavedRun base = read_bench_json(path);
  BenchArgs a;
  a.samples = 4;
  a.aa_coverage = AaCoverage::silhouette;
  a.silhouette_steps = 3;
  a.tile_size = 16;
  EXPECT_TRUE(differing_settings(base, a).empty());
  a.aa_coverage = AaCoverage::count;
  a.silhouette_steps = 0;
  a.tile_size = 8;
  EXPECT_EQ(differing_settings(base, a),
            (std::vector<std::string>{"aa_coverage \"count\" (base: \"silhouette\")",
                                      "aa_walk_steps 0 (base: 3)", "tile_size 8 (base: 16)"}));
  // kBase records none of them: nothing to warn of.
  const std::string old_path = test::output_path("base_no_settings.json");
  std::ofstream(old_path) << kBase;
  EXPECT_TRUE(differing_settings(read_bench_json(old_path), a).empty());
}

TEST(BenchCli, BadCompareFilesAreClearErrors) {
  auto error_of = [](const std::string& name, const std::string& text) {
    const std::string path = test::output_path(name);
    std::ofstream(path) << text;
    try {
      read_bench_json(path);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error_of("truncated.json", R"({"scene": "grid", "width": )")
                .find("truncated.json' is not valid JSON: parse error at line 1, column 28"),
            std::string::npos)
      << error_of("truncated.json", R"({"scene": "grid", "width": )");
  EXPECT_NE(error_of("array.json", "[1, 2]").find("is not a `tessera bench --json` file"),
            std::string::npos);
  EXPECT_NE(error_of("no_results.json", R"({"scene": "grid", "width": 8, "height": 8})")
                .find("results is missing or not an array"),
            std::string::npos);
  EXPECT_NE(error_of("no_size.json", R"({"scene": "grid", "results": []})")
                .find("width is missing or not a whole number"),
            std::string::npos);
  EXPECT_NE(error_of("no_time.json", R"({"scene": "grid", "width": 8, "height": 8,
      "results": [{"objects": 1, "backend": "compute", "total_ms": 1},
                  {"objects": 2, "backend": "compute", "total_ms": "fast"}]})")
                .find("results[1].total_ms is missing or not a number"),
            std::string::npos);
  // 0 or a negative time is no measurement (a 0 vanished from the table, a negative one made
  // its point "only in this run": a fresh user's trial).
  for (const char* time : {"0", "-1.5"}) {
    const std::string error = error_of("zero_time.json", std::string(R"({"scene": "grid", "width":
      8, "height": 8, "results": [{"objects": 1, "backend": "compute", "total_ms": )") +
                                                             time + "}]}");
    EXPECT_NE(error.find("results[0].total_ms is " + std::string(time) + ", not a time (> 0 ms)"),
              std::string::npos)
        << error;
  }
  EXPECT_NE(error_of("twice.json", R"({"scene": "grid", "width": 8, "height": 8,
      "results": [{"objects": 1, "backend": "compute", "total_ms": 1},
                  {"objects": 1, "backend": "compute", "total_ms": 2}]})")
                .find("results[1] repeats the point grid, 1 object, 8x8, compute"),
            std::string::npos);
  try {
    read_bench_json("/nonexistent/base.json");
    ADD_FAILURE() << "no error for a missing file";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "--compare: cannot read '/nonexistent/base.json': No such file or directory"),
              std::string::npos)
        << e.what();
  }
  // From the command line: a bad command line (status 2), named, before anything is measured.
  std::string out;
  EXPECT_EQ(test::run_command(std::string(TESSERA_BINARY) +
                                  " bench --device lavapipe --compare /nonexistent/base.json",
                              out),
            2);
  EXPECT_NE(out.find("--compare: no file '/nonexistent/base.json'"), std::string::npos) << out;
  EXPECT_EQ(out.find("objects"), std::string::npos) << out;
}

}  // namespace
}  // namespace tessera
