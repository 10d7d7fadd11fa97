// `tessera bench` as a smoke test on lavapipe: a short sweep over every backend writes CSV, JSON
// and charts. Not a timing assertion: speed is measured in bench/ and docs/performance.md.
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "core/bench_scenes.h"
#include "core/check.h"
#include "core/image.h"
#include "core/mesh.h"
#include "host/cli.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

std::string read_text(const std::string& path) {
  std::ifstream f(path);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

TEST(BenchCli, ShortSweepWritesCsvJsonAndCharts) {
  for (const auto& family : bench_families()) {
    const std::string base = test::output_path(std::string(family.name));
    std::string out;
    const std::string command =
        std::string(TESSERA_BINARY) + " bench --device lavapipe --validate --scene " +
        std::string(family.name) +
        " --objects 1,3 --size 64x48 --segments 8 --backends compute,hardware,reference "
        "--repeat 2 --warmup 0 --csv " +
        base + ".csv --json " + base + ".json --chart " + base + ".svg";
    ASSERT_EQ(test::run_command(command, out), 0) << out;
    EXPECT_NE(out.find("compute / hardware"), std::string::npos) << out;
    const std::string csv = read_text(base + ".csv");
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 2 * 3)
        << csv;  // header + 2 counts x 3 backends
    EXPECT_NE(csv.find(std::string(family.name) + ",3,hardware,64,48"), std::string::npos) << csv;
    const std::string json = read_text(base + ".json");
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
                                  "--warmup 0 --quiet --chart " +
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
                                  "--repeat 1 --warmup 0 --quiet --csv " +
                                  csv_path,
                              out),
            0)
      << out;
  const std::string csv = read_text(csv_path);
  // N copies: 2 N objects and 4 N triangles (columns objects, backend, size, submitted).
  EXPECT_NE(csv.find(",2,compute,32,32,4,"), std::string::npos) << csv;
  EXPECT_NE(csv.find(",6,compute,32,32,12,"), std::string::npos) << csv;
  EXPECT_NE(csv.find(",6,reference,32,32,12,"), std::string::npos) << csv;
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

// The yardstick family against the formulas worked by hand: side = ceil(sqrt N),
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

TEST(BenchCli, ParsesEveryOption) {
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
}

TEST(BenchCli, HelpListsEveryOption) {
  const CommandLine line = parse_command_line({"bench", "--help"});
  ASSERT_EQ(line.command, Command::help);
  for (const char* option :
       {"Usage: tessera bench", "--scene NAME", "--objects LIST", "--size WxH", "--segments S",
        "--device D", "--backends LIST", "--repeat K", "--warmup K", "--reference-max-triangles T",
        "--small-triangle-area A", "--generic-shading", "--csv FILE", "--json FILE", "--chart FILE",
        "--validate", "--quiet", "Exit status"}) {
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
  EXPECT_NE(error({"--scene", "forest"}).find("--scene: unknown benchmark scene 'forest'"),
            std::string::npos);
  EXPECT_NE(error({"--objects", "1,x"}).find("--objects: expects a whole number"),
            std::string::npos);
  EXPECT_NE(error({"--objects", "0"}).find("--objects: expects a whole number from 1"),
            std::string::npos);
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
  EXPECT_NE(error({"--size", "0x5"}).find("--size: width"), std::string::npos);
  EXPECT_NE(error({"--small-triangle-area", "-1"}).find("--small-triangle-area:"),
            std::string::npos);
  EXPECT_NE(error({"--reference-max-triangles", "0"}).find("--reference-max-triangles:"),
            std::string::npos);
  EXPECT_NE(error({"--turbo"}).find("unknown option '--turbo'"), std::string::npos);
}

// An output that cannot be written is a failure while running (status 1), found before the
// sweep spends any time.
TEST(BenchCli, UnwritableOutputFailsBeforeMeasuring) {
  std::string out;
  EXPECT_EQ(test::run_command(std::string(TESSERA_BINARY) +
                                  " bench --device lavapipe --csv /nonexistent-dir/x.csv",
                              out),
            1);
  EXPECT_NE(out.find("tessera: error: cannot write output file '/nonexistent-dir/x.csv'"),
            std::string::npos)
      << out;
  EXPECT_EQ(out.find("objects"), std::string::npos) << "no table: nothing was measured\n" << out;
}

}  // namespace
}  // namespace tessera
