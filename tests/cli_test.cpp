// The command-line tool: help, bad arguments give a clear message and a non-zero exit.
#include <gtest/gtest.h>

#include "core/image.h"

#include "core/check.h"
#include "host/cli.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

std::string parse_error(std::vector<std::string> args) {
  RenderArgs out;
  try {
    parse_render_args(args, out);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(Cli, ParsesEveryOption) {
  RenderArgs a;
  ASSERT_TRUE(parse_render_args(
      {"--scene",    "metals",    "--size=640x360", "--out",    "x.png",
       "--hdr-out",  "x.pfm",     "--device",       "lavapipe", "--exposure",
       "-1.5",       "--tonemap", "reinhard",       "--repeat", "5",
       "--validate", "--quiet",   "--brdf",         "filament", "--energy-compensation"},
      a));
  EXPECT_EQ(a.scene, "metals");
  EXPECT_EQ(a.width, 640u);
  EXPECT_EQ(a.height, 360u);
  EXPECT_EQ(a.out, "x.png");
  EXPECT_EQ(a.hdr_out, "x.pfm");
  EXPECT_EQ(a.device, "lavapipe");
  EXPECT_FLOAT_EQ(a.exposure_ev, -1.5f);
  EXPECT_EQ(a.tonemap, ToneMap::reinhard);
  EXPECT_EQ(a.repeat, 5u);
  EXPECT_TRUE(a.validate);
  EXPECT_TRUE(a.quiet);
  EXPECT_EQ(a.brdf, Brdf::filament);
  EXPECT_TRUE(a.energy_compensation);
  RenderArgs help;
  EXPECT_FALSE(parse_render_args({"--help"}, help));
}

TEST(Cli, BadArgumentsNameTheProblem) {
  EXPECT_NE(parse_error({"--size", "0x512"}).find("--size width"), std::string::npos);
  EXPECT_NE(parse_error({"--size", "512x0"}).find("--size height"), std::string::npos);
  EXPECT_NE(parse_error({"--size", "100000x100"}).find("16384"), std::string::npos);
  EXPECT_NE(parse_error({"--size", "big"}).find("WxH"), std::string::npos);
  EXPECT_NE(parse_error({"--size"}).find("needs a value"), std::string::npos);
  EXPECT_NE(parse_error({"--out", "image.jpg"}).find(".png"), std::string::npos);
  EXPECT_NE(parse_error({"--exposure", "bright"}).find("--exposure"), std::string::npos);
  EXPECT_NE(parse_error({"--exposure", "nan"}).find("--exposure"), std::string::npos);
  EXPECT_NE(parse_error({"--tonemap", "filmic"}).find("aces"), std::string::npos);
  EXPECT_NE(parse_error({"--brdf", "phong"}).find("classic, filament or blinn-phong"),
            std::string::npos);
  EXPECT_NE(parse_error({"--frobnicate"}).find("unknown option '--frobnicate'"), std::string::npos);
  EXPECT_NE(parse_error({"--repeat", "0"}).find("--repeat"), std::string::npos);
}

struct ToolCase {
  std::string args;
  std::string message;
};

TEST(Cli, ToolExitsNonZeroWithAMessage) {
  const ToolCase cases[] = {
      {"render --size 0x10", "--size width"},
      {"render --scene nowhere", "unknown scene 'nowhere'"},
      {"render --out /nonexistent-dir/x.png", "cannot write output file"},
      {"render --device 99", "out of range"},
      {"render --device warp-drive", "unknown device 'warp-drive'"},
      {"render --bogus", "unknown option"},
      {"explode", "unknown command 'explode'"},
      {"render --env /nonexistent/sky.hdr --out /tmp/x.png",
       "cannot read environment '/nonexistent/sky.hdr'"},
      {"render --env sky.exr", "--env expects a .hdr or .pfm file"},
      {"render --env-size 3", "not a power of two"},
      {"render --anisotropy 17", "--anisotropy expects a whole number from 1 to 16"},
  };
  for (const ToolCase& c : cases) {
    std::string out;
    int status = test::run_command(std::string(TESSERA_BINARY) + " " + c.args, out);
    EXPECT_NE(status, 0) << c.args;
    EXPECT_NE(out.find(c.message), std::string::npos) << c.args << " printed: " << out;
    EXPECT_EQ(out.find("Segmentation"), std::string::npos) << out;
  }
}

// An environment file round trip: a .hdr written by Tessera lights a scene under validation.
TEST(Cli, RendersWithAnEnvironmentFile) {
  ImageF sky{8, 4, std::vector<glm::vec4>(32, glm::vec4(0.5f, 0.6f, 0.9f, 1.0f))};
  const std::string hdr = test::output_path("sky.hdr");
  write_hdr_image(hdr, sky);
  const std::string png = test::output_path("env.png");
  std::string out;
  ASSERT_EQ(
      test::run_command(std::string(TESSERA_BINARY) +
                            " render --device lavapipe --validate --scene spheres --size 64x64 "
                            "--env " +
                            hdr + " --env-size 8 --env-samples 8 --out " + png,
                        out),
      0)
      << out;
  EXPECT_NE(out.find("environment precomputation"), std::string::npos) << out;
  // The background is the map's radiance: tone-mapped, not the scene's dark background.
  const Image8 image = read_png(png);
  EXPECT_GT(image.at(0, 0).b, 150) << "corner pixel shows the sky";
}

TEST(Cli, RendersAndSaysWhereItWrote) {
  const std::string png = test::output_path("cli.png");
  std::string out;
  ASSERT_EQ(test::run_command(std::string(TESSERA_BINARY) +
                                  " render --device lavapipe --validate "
                                  "--size 96x64 --out " +
                                  png,
                              out),
            0)
      << out;
  EXPECT_NE(out.find("wrote " + png), std::string::npos) << out;
  EXPECT_NE(out.find("GPU time"), std::string::npos) << out;
  const std::string reference = test::output_path("reference.png");
  ASSERT_EQ(test::run_command(std::string(TESSERA_BINARY) +
                                  " render --device reference --size 96x64 --out " + reference,
                              out),
            0)
      << out;
  EXPECT_NE(out.find("wrote " + reference), std::string::npos) << out;
  std::string help;
  ASSERT_EQ(test::run_command(std::string(TESSERA_BINARY) + " render --help", help), 0);
  EXPECT_NE(help.find("--size WxH"), std::string::npos);
}

}  // namespace
}  // namespace tessera
