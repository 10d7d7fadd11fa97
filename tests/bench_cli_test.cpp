// `tessera bench` as a smoke test on lavapipe: a short sweep over every backend writes CSV, JSON
// and charts. Not a timing assertion: speed is measured in bench/ and docs/performance.md.
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>

#include "core/bench_scenes.h"
#include "core/check.h"
#include "core/image.h"
#include "host/bench_command.h"
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

TEST(BenchCli, BadArgumentsNameTheProblem) {
  auto error = [](std::vector<std::string> args) {
    BenchArgs a;
    try {
      parse_bench_args(args, a);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error({"--scene", "forest"}).find("unknown benchmark scene 'forest'"),
            std::string::npos);
  EXPECT_NE(error({"--objects", "1,x"}).find("--objects"), std::string::npos);
  EXPECT_NE(error({"--objects", "0"}).find("--objects"), std::string::npos);
  EXPECT_NE(error({"--backends", "compute,magic"}).find("'magic'"), std::string::npos);
  EXPECT_NE(error({"--chart", "c.jpg"}).find(".svg or .png"), std::string::npos);
  EXPECT_NE(error({"--csv", "/nonexistent-dir/x.csv"}).find("cannot write"), std::string::npos);
  EXPECT_NE(error({"--segments", "2"}).find("--segments"), std::string::npos);
}

}  // namespace
}  // namespace tessera
