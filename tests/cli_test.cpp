// The command-line tool: parsing, --help, and bad arguments giving a message that names the
// option and the exit statuses of host/cli.h (2 for a bad command line, 1 for a failure while
// running).
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include <gtest/gtest.h>

#include "compute/context.h"
#include "core/bench_scenes.h"
#include "core/check.h"
#include "core/image.h"
#include "host/cli.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

// The message of the UsageError `args` throw, or "" if they parse.
std::string usage_error(const std::vector<std::string>& args) {
  try {
    parse_command_line(args);
  } catch (const UsageError& e) {
    return e.what();
  }
  return "";
}

std::string help_of(const std::vector<std::string>& args) {
  const CommandLine line = parse_command_line(args);
  EXPECT_EQ(line.command, Command::help);
  return line.help;
}

std::string tool() {
  return TESSERA_BINARY;
}

TEST(Cli, ParsesEveryRenderOption) {
  const CommandLine line = parse_command_line({"render",
                                               "--scene",
                                               "metals",
                                               "--size=640x360",
                                               "--out",
                                               "x.png",
                                               "--hdr-out",
                                               "x.pfm",
                                               "--device",
                                               "lavapipe",
                                               "--exposure",
                                               "-1.5",
                                               "--tonemap",
                                               "reinhard",
                                               "--repeat",
                                               "5",
                                               "--validate",
                                               "--quiet",
                                               "--brdf",
                                               "filament",
                                               "--energy-compensation",
                                               "--env",
                                               "sky",
                                               "--env-size",
                                               "64",
                                               "--env-samples",
                                               "32",
                                               "--env-irradiance-size",
                                               "16",
                                               "--env-reference-samples",
                                               "256",
                                               "--anisotropy",
                                               "8",
                                               "--lod",
                                               "auto",
                                               "--lod-error",
                                               "0.25",
                                               "--view",
                                               "uv"});
  ASSERT_EQ(line.command, Command::render);
  const RenderArgs& a = line.render;
  EXPECT_EQ(a.scene, "metals");
  EXPECT_EQ(a.frame.width, 640u);
  EXPECT_EQ(a.frame.height, 360u);
  EXPECT_EQ(a.out, "x.png");
  EXPECT_EQ(a.hdr_out, "x.pfm");
  EXPECT_EQ(a.device, "lavapipe");
  EXPECT_FLOAT_EQ(a.frame.exposure_ev, -1.5f);
  EXPECT_EQ(a.frame.tonemap, ToneMap::reinhard);
  EXPECT_EQ(a.repeat, 5u);
  EXPECT_TRUE(a.validate);
  EXPECT_TRUE(a.quiet);
  EXPECT_EQ(a.frame.brdf, Brdf::filament);
  EXPECT_TRUE(a.frame.energy_compensation);
  EXPECT_EQ(a.env, "sky");
  EXPECT_EQ(a.env_options.specular_size, 64u);
  EXPECT_EQ(a.env_options.specular_samples, 32u);
  EXPECT_EQ(a.env_options.irradiance_size, 16u);
  EXPECT_EQ(a.env_reference_samples, 256u);
  EXPECT_EQ(a.frame.max_anisotropy, 8u);
  EXPECT_EQ(a.frame.lod, Lod::automatic);
  EXPECT_FLOAT_EQ(a.frame.lod_error_px, 0.25f);
  EXPECT_EQ(a.frame.view, View::uv);
}

// `tessera --version`: the project's version from CMakeLists.txt (project(Tessera VERSION ...)).
TEST(Cli, VersionIsTheProjectVersion) {
  std::ifstream cmake(std::filesystem::path(TESSERA_README).parent_path() / "CMakeLists.txt");
  const std::string text{std::istreambuf_iterator<char>(cmake), {}};
  const size_t at = text.find("project(Tessera VERSION ");
  ASSERT_NE(at, std::string::npos);
  const size_t from = at + std::string("project(Tessera VERSION ").size();
  const std::string version = text.substr(from, text.find_first_of(" )", from) - from);
  const CommandLine line = parse_command_line({"--version"});
  EXPECT_EQ(line.command, Command::help);
  EXPECT_TRUE(line.help.starts_with("tessera " + version + "\n") ||
              line.help.starts_with("tessera " + version + " (git "))
      << line.help;
  EXPECT_NE(usage_error({"--version", "render"}).find("--version takes nothing after it"),
            std::string::npos);
  // A lost write is a failure: standard output on a full device (errors still reach stderr).
  std::string out;
  EXPECT_EQ(
      test::run_command("(" + std::string(TESSERA_BINARY) + " --version 2>&1 >/dev/full)", out), 1);
  EXPECT_NE(out.find("tessera: error: cannot write the standard output"), std::string::npos) << out;
  // After --help too it prints the version and succeeds (it was "tessera: error: tessera 0.1").
  const CommandLine after_help = parse_command_line({"--help", "--version"});
  EXPECT_EQ(after_help.command, Command::help);
  EXPECT_EQ(after_help.help, line.help);
  EXPECT_NE(help_of({"--help"}).find("--version"), std::string::npos);
}

// Output files are told by their extension in any case, as model files are (x.GLB): x.PNG was
// refused as "expects a .png file" (a new user's trial). A choice spelt with '_' for '-' is the
// same choice (scene files write blinn_phong).
TEST(Cli, ExtensionsInAnyCaseAndChoicesWithUnderscores) {
  const CommandLine line = parse_command_line(
      {"render", "--out", "x.PNG", "--hdr-out", "x.Pfm", "--brdf", "blinn_phong"});
  EXPECT_EQ(line.render.out, "x.PNG");
  EXPECT_EQ(line.render.hdr_out, "x.Pfm");
  EXPECT_EQ(line.render.frame.brdf, Brdf::blinn_phong);
  EXPECT_EQ(usage_error({"tradeoff", "--chart", "c.SVG"}).find("--chart"), std::string::npos);
  // An environment map in upper case passes the extension check and is looked for.
  try {
    parse_command_line({"render", "--env", "NO_SUCH_SKY.HDR"});
    ADD_FAILURE() << "a missing --env file was taken";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("no file 'NO_SUCH_SKY.HDR'"), std::string::npos)
        << e.what();
  }
  EXPECT_NE(usage_error({"render", "--out", "x.jpg"}).find("expects a .png file"),
            std::string::npos);
  EXPECT_NE(usage_error({"render", "--out", ".PNG"}).find("expects a .png file"),
            std::string::npos);
}

TEST(Cli, DefaultsAreTheDocumentedOnes) {
  const RenderArgs a = parse_command_line({"render"}).render;
  EXPECT_EQ(a.scene, "spheres");
  EXPECT_EQ(a.frame.width, 512u);
  EXPECT_EQ(a.frame.height, 512u);
  EXPECT_EQ(a.out, "tessera.png");
  EXPECT_EQ(a.frame.tonemap, ToneMap::aces);
  EXPECT_EQ(a.frame.brdf, Brdf::classic);
  EXPECT_EQ(a.repeat, 3u);
  EXPECT_FALSE(a.validate);
  EXPECT_EQ(parse_command_line({"devices"}).command, Command::devices);
  EXPECT_EQ(parse_command_line({"scenes"}).command, Command::scenes);
}

TEST(Cli, HelpOfTheToolAndOfEachCommandListsItsOptions) {
  for (const auto& args : {std::vector<std::string>{"--help"}, {"-h"}, {"help"}}) {
    const std::string help = help_of(args);
    for (const char* command : {"render", "bench", "devices", "scenes", "Exit status"})
      EXPECT_NE(help.find(command), std::string::npos) << command << " in\n" << help;
  }
  const std::string render = help_of({"render", "--help"});
  for (const char* option : {"Usage: tessera render",
                             "--scene NAME",
                             "--size WxH",
                             "--out FILE.png",
                             "--hdr-out FILE",
                             "--device D",
                             "--exposure EV",
                             "--tonemap aces|reinhard|clamp",
                             "--brdf classic|filament|blinn-phong",
                             "--energy-compensation",
                             "--env E",
                             "--env-size N",
                             "--env-samples N",
                             "--env-irradiance-size N",
                             "--env-reference-samples N",
                             "--anisotropy N",
                             "--view shaded|normal|uv|triangle|object",
                             "--repeat K",
                             "--validate",
                             "--quiet",
                             "--help"}) {
    EXPECT_NE(render.find(option), std::string::npos) << option << " in\n" << render;
  }
  EXPECT_EQ(help_of({"render", "-h"}), render);
  for (const char* command : {"devices", "scenes"}) {
    const std::string help = help_of({command, "--help"});
    EXPECT_NE(help.find(std::string("Usage: tessera ") + command), std::string::npos) << help;
  }
}

// The help of an option that takes a benchmark family names every one (core/bench_scenes.h):
// tradeoff's --scene and --objects once left out yardstick.
TEST(Cli, HelpNamesEveryBenchmarkFamily) {
  struct Section {
    std::vector<std::string> args;
    const char *from, *to;  // the option's help runs from `from` to the next option, `to`
  };
  for (const Section& s : {Section{{"bench", "--help"}, "--scene", "--objects"},
                           Section{{"tradeoff", "--help"}, "--scene", "--objects"},
                           Section{{"tradeoff", "--help"}, "--objects", "--knob"}}) {
    const std::string help = help_of(s.args);
    const size_t from = help.find(std::string("  ") + s.from + " ");
    const size_t to = help.find(std::string("  ") + s.to + " ", from);
    ASSERT_NE(from, std::string::npos) << help;
    ASSERT_NE(to, std::string::npos) << help;
    const std::string option = help.substr(from, to - from);
    for (const BenchFamilyInfo& family : bench_families())
      EXPECT_NE(option.find(family.name), std::string::npos)
          << s.args[0] << " " << s.from << " lacks " << family.name << ":\n"
          << option;
  }
}

// README.md quotes the help texts; a changed option must change them there too.
TEST(Cli, ReadmeQuotesTheHelpTexts) {
  std::ifstream file(TESSERA_README);
  ASSERT_TRUE(file) << TESSERA_README;
  const std::string readme(std::istreambuf_iterator<char>(file), {});
  for (const auto& args : {std::vector<std::string>{"--help"},
                           {"render", "--help"},
                           {"bench", "--help"},
                           {"view", "--help"},
                           {"tradeoff", "--help"}}) {
    std::string command = "$ tessera";
    for (const std::string& arg : args) command += " " + arg;
    EXPECT_NE(readme.find(command + "\n" + help_of(args)), std::string::npos)
        << "README.md lacks the output of `" << command << "`:\n"
        << help_of(args);
  }
}

struct BadArguments {
  std::vector<std::string> args;
  std::string message;  // a part of the message; it starts with the option's name
};

TEST(Cli, BadArgumentsNameTheOption) {
  const BadArguments cases[] = {
      {{"render", "--size", "0x5"}, "--size: width expects a whole number from 1 to 16384"},
      {{"render", "--size", "512x0"}, "--size: height expects"},
      {{"render", "--size", "99999x1"}, "got '99999' in '99999x1'"},
      {{"render", "--size", "abc"}, "--size: expects WxH"},
      // An option given without its value reads the next option as it: said so.
      {{"render", "--repeat", "--out", "x.png"},
       "--repeat: expects a whole number from 1 to 1000, got '--out' (an option: is this one's "
       "value missing?)"},
      {{"render", "--tonemap", "--quiet"}, "got '--quiet' (an option: is this one's value"},
      {{"render", "--size", "-5x5"}, "--size: width"},
      {{"render", "--size"}, "--size needs a value"},
      {{"render", "--tile-lists", "direct", "--tile-lists", "counted"},
       "--tile-lists: given 2 times; give it once"},
      {{"render", "--tile-lists", "sideways"},
       "--tile-lists: expects automatic, direct or counted, got 'sideways'"},
      {{"bench", "--size", "64x64", "--size", "32x32"}, "--size: given 2 times; give it once"},
      {{"render", "--scene", "nowhere"}, "--scene: unknown scene 'nowhere'"},
      {{"render", "--out", "image.jpg"}, "--out: expects a .png file, got 'image.jpg'"},
      {{"render", "--hdr-out", "x.exr"}, "--hdr-out: expects a .pfm file or a .hdr file"},
      {{"render", "--exposure", "bright"}, "--exposure: expects a number from -64 to 64"},
      {{"render", "--exposure", "nan"}, "--exposure: expects a number"},
      {{"render", "--exposure", "65"}, "--exposure: expects a number from -64 to 64"},
      {{"render", "--tonemap", "filmic"}, "--tonemap: expects aces, reinhard or clamp"},
      {{"render", "--brdf", "phong"}, "--brdf: expects classic, filament or blinn-phong"},
      {{"render", "--view", "depth"}, "--view: expects shaded, normal, uv, triangle or object"},
      {{"render", "--env", "sky.exr"}, "--env: expects a .hdr file, a .pfm file, sky or none"},
      {{"render", "--env-size", "3"}, "--env-size: environment specular size 3 is not a power"},
      {{"render", "--env-size", "1024"}, "--env-size: expects a whole number from 1 to 512"},
      {{"render", "--env-samples", "0"}, "--env-samples: expects a whole number from 1"},
      {{"render", "--env-irradiance-size", "0"}, "--env-irradiance-size: expects"},
      {{"render", "--env-reference-samples", "x"}, "--env-reference-samples: expects"},
      {{"render", "--anisotropy", "17"}, "--anisotropy: expects a whole number from 1 to 16"},
      {{"render", "--lod", "on"}, "--lod: expects off or auto"},
      {{"bench", "--lod-error", "0"}, "--lod-error: expects a number from 0.001 to 1000"},
      {{"render", "--repeat", "0"}, "--repeat: expects a whole number from 1 to 1000"},
      {{"render", "--repeat", "1.5"}, "--repeat: expects a whole number"},
      {{"render", "--frobnicate"}, "unknown option '--frobnicate'"},
      // A slip of one or two letters gets the option or command it is nearest to.
      {{"render", "--sise", "64x64"}, "unknown option '--sise', did you mean '--size'?"},
      {{"render", "--sampels=4"}, "unknown option '--sampels=4', did you mean '--samples'?"},
      {{"rendr"}, "unknown command 'rendr', did you mean 'render'?"},
      // So does a value: in another case, or a letter or two off.
      {{"render", "--samples", "4", "--aa-coverage", "Analytic"},
       "--aa-coverage: expects count, analytic or silhouette, got 'Analytic', did you mean "
       "'analytic'?"},
      {{"render", "--brdf", "filamint"},
       "--brdf: expects classic, filament or blinn-phong, got 'filamint', did you mean "
       "'filament'?"},
      {{"bench", "--backends", "compute,hardwar"},
       "--backends: expects compute, hardware or reference, got 'hardwar', did you mean "
       "'hardware'?"},
      {{"render", "extra"}, "unexpected argument 'extra'"},
      {{"scenes", "--all"}, "unknown option '--all'"},
      {{"explode"}, "unknown command 'explode'"},
      {{"--verbose"}, "unknown option '--verbose'"},
      {{}, "a command is required: render, bench, view, tradeoff, devices or scenes"},
      {{"view", "--vsync", "maybe"}, "--vsync: expects on or off, got 'maybe'"},
      {{"view", "--overlay", "x"}, "--overlay: expects on or off"},
      {{"view", "--size", "0x3"}, "--size: width expects a whole number from 1 to 16384"},
      {{"view", "--scene", "nowhere"}, "--scene: unknown scene 'nowhere'"},
      {{"render", "--scene", "sphers"}, "--scene: unknown scene 'sphers' (known scenes: "},
      {{"render", "--scene", "sphers"}, "; or a scene file's path), did you mean 'spheres'?"},
      {{"tradeoff", "--knob", "brdff"}, "--knob: unknown knob 'brdff' (known: brdf, "},
      {{"tradeoff", "--knob", "brdff"}, "), did you mean 'brdf'?"},
      // CLI11's own text was "Could not convert: --camera = -1".
      {{"render", "--camera", "-1"},
       "--camera: expects a camera number (0 for the first camera of the scene file's models, 1 "
       "for the next, ...), got '-1'"},
      {{"view", "--camera", "one"}, "--camera: expects a camera number (0 for the first"},
      // CLI11 alone would drop empty entries of a list and run the rest.
      {{"bench", "--objects", "1,,2"}, "--objects: an empty entry in '1,,2'"},
      {{"bench", "--objects=1,10,"}, "--objects: an empty entry in '1,10,'"},
      {{"bench", "--backends", ",compute"}, "--backends: an empty entry in ',compute'"},
      {{"tradeoff", "--knob", "brdf,,lod"}, "--knob: an empty entry in 'brdf,,lod'"},
  };
  for (const BadArguments& c : cases) {
    const std::string message = usage_error(c.args);
    EXPECT_NE(message.find(c.message), std::string::npos)
        << testing::PrintToString(c.args) << " gave '" << message << "'";
  }
}

struct ToolCase {
  std::string args;
  int status;
  std::string message;
};

// One error style for both kinds: usage errors (2) and failures while running (1).
TEST(Cli, ToolReportsErrorsInOneStyleWithTheirExitStatus) {
  const std::string bad_script = test::output_path("bad_script.txt");
  const std::string folder_env = test::output_path("folder.hdr");  // a folder named like a file
  std::filesystem::create_directories(folder_env);
  std::ofstream(bad_script) << "1 key A\n2 jump\n";
  // A size the device cannot render, given by a scene file's "render" block (line 2, column 12).
  const std::string big_scene = test::output_path("big_render.json");
  std::ofstream(big_scene) << "{\"ambient\": [1, 1, 1],\n \"render\": {\"width\": 16384, "
                              "\"height\": 16384}}\n";
  // 16384 x 16384 keys of 8 bytes are 2048 MiB; lavapipe's storage buffers hold 128 MiB, 2^24
  // keys: 4096 x 4096.
  const std::string too_big =
      "needs a 2048 MiB visibility buffer, more than this device's maxStorageBufferRange (128 "
      "MiB): it takes at most 16777216 pixels at 1 sample, e.g. 4096x4096";
  const ToolCase cases[] = {
      {"render --size 0x10", 2, "tessera: error: --size: width"},
      {"render --brdf phong", 2, "tessera: error: --brdf: expects classic"},
      {"render --bogus", 2, "tessera: error: unknown option '--bogus'"},
      {"explode", 2, "tessera: error: unknown command 'explode'"},
      {"", 2, "tessera: error: a command is required"},
      {"render --scene nowhere", 2, "tessera: error: --scene: unknown scene 'nowhere'"},
      {"render --env sky.exr", 2, "tessera: error: --env: expects a .hdr file"},
      {"render --env-size 3", 2, "not a power of two"},
      {"render --anisotropy 17", 2, "--anisotropy: expects a whole number from 1 to 16"},
      {"render --camera -1", 2, "tessera: error: --camera: expects a camera number"},
      // The device's limit is known once it is open, but the size is the command line's.
      {"render --device lavapipe --size 16384x16384 --out /tmp/x.png", 2,
       "tessera: error: --size 16384x16384: " + too_big},
      {"bench --device lavapipe --size 16384x16384 --objects 1 --backends compute", 2,
       "tessera: error: --size 16384x16384: " + too_big},
      {"tradeoff --device lavapipe --size 16384x16384 --knob samples", 2,
       "tessera: error: --size 16384x16384: " + too_big},
      {"render --device lavapipe --scene " + big_scene + " --out /tmp/x.png", 1,
       "tessera: error: " + big_scene + ":2:12: render: the size 16384x16384 " + too_big +
           " (--size overrides it)"},
      {"tradeoff --device lavapipe --scene " + big_scene + " --knob samples", 1,
       "tessera: error: " + big_scene + ":2:12: render: the size 16384x16384 " + too_big +
           " (--size overrides it)"},
      // An output that cannot be written is a bad command line, found before any work.
      {"render --out /nonexistent-dir/x.png", 2,
       "tessera: error: --out: cannot write '/nonexistent-dir/x.png': folder "
       "'/nonexistent-dir' does not exist"},
      {"render --out /tmp/x.png --hdr-out /nonexistent-dir/x.pfm", 2,
       "tessera: error: --hdr-out: cannot write '/nonexistent-dir/x.pfm': folder "
       "'/nonexistent-dir' does not exist"},
      {"tradeoff --knob samples --chart /nonexistent-dir/x.svg", 2,
       "tessera: error: --chart: cannot write '/nonexistent-dir/x.svg': folder "
       "'/nonexistent-dir' does not exist"},
      // What is there but is not a regular file is named with its option, as a missing one is.
      {"render --scene /dev/zero --out /tmp/x.png", 2,
       "tessera: error: --scene: /dev/zero: is not a regular file (a character device)"},
      {"devices", 0, "(CPU) - usable (--device "},
      {"devices", 0, "\nreference: the CPU reference renderer"},
      // `tessera devices` names lavapipe's device llvmpipe.
      {"render --device llvmpipe", 2,
       "tessera: error: --device: unknown device 'llvmpipe' (lavapipe, gpu, reference, or a "
       "device index of `tessera devices`), did you mean 'lavapipe'?"},
      // A device index is checked against the devices present while parsing, as a misspelt
      // device name is.
      {"render --device 99", 2, "tessera: error: --device: device index 99 is out of range: only "},
      {"bench --device 99", 2, "tessera: error: --device: device index 99 is out of range: only "},
      {"view --device 99", 2, "tessera: error: --device: device index 99 is out of range: only "},
      {"tradeoff --knob lod --device 99", 2,
       "tessera: error: --device: device index 99 is out of range: only "},
      {"bench --device foo", 2, "tessera: error: --device: unknown device 'foo'"},
      // The commands that have the CPU reference in another form say which.
      {"bench --device reference", 2,
       "tessera: error: --device: 'reference' is not a device for this command: the CPU reference "
       "is "
       "one of its backends (--backends reference)"},
      {"view --device reference", 2,
       "--device: 'reference' is not a device for this command: the viewer draws with Vulkan only"},
      {"tradeoff --knob brdf --device reference", 2,
       "--device: 'reference' is not a device for this command: the CPU reference renders every "
       "knob's ground truth"},
      {"render --aa-coverage analytic", 2,
       "tessera: error: --aa-coverage analytic does nothing at 1 sample per pixel"},
      {"render --device warp-drive", 2, "tessera: error: --device: unknown device 'warp-drive'"},
      {"view --device foo", 2, "tessera: error: --device: unknown device 'foo'"},
      {"view --script /nonexistent/s.txt", 2,
       "tessera: error: --script: script file '/nonexistent/s.txt' not found"},
      // A bad script line is a bad command line too; it is read before any window opens.
      {"view --script " + bad_script, 2, bad_script + ":2: unknown event 'jump'"},
      {"render --env /nonexistent/sky.hdr --out /tmp/x.png", 2,
       "tessera: error: --env: no file '/nonexistent/sky.hdr'"},
      // Refused before it is opened, as a FIFO is (a FIFO blocked the open: mapped_file_test).
      {"render --env " + folder_env + " --out /tmp/x.png", 2,
       "tessera: error: --env: " + folder_env + ": is not a regular file (a directory)"},
      {"view --script " + folder_env, 2,
       "tessera: error: --script: " + folder_env + ": is not a regular file (a directory)"},
  };
  for (const ToolCase& c : cases) {
    std::string out;
    const int status = test::run_command(tool() + " " + c.args, out);
    EXPECT_EQ(status, c.status) << c.args << " printed: " << out;
    EXPECT_NE(out.find(c.message), std::string::npos) << c.args << " printed: " << out;
    if (c.status == 2) {
      EXPECT_NE(out.find("--help' for the options"), std::string::npos) << out;
    }
  }
  std::string help;
  EXPECT_EQ(test::run_command(tool() + " render --help", help), 0);
  EXPECT_NE(help.find("--size WxH"), std::string::npos) << help;
}

// An unknown scene's message names every scene `tessera scenes` lists (the scene files, the
// benchmark ones among them), for render and view alike.
TEST(Cli, UnknownSceneListsEverySceneThatScenesLists) {
  std::string listing;
  ASSERT_EQ(test::run_command(tool() + " scenes", listing), 0);
  std::vector<std::string> names;
  std::istringstream lines(listing);
  for (std::string line; std::getline(lines, line);) {
    if (line.empty() || line.starts_with("scene files in")) continue;
    names.push_back(line.substr(0, line.find(' ')));
  }
  ASSERT_GE(names.size(), 5u) << listing;
  for (const char* command : {"render", "view"}) {
    std::string out;
    EXPECT_EQ(test::run_command(tool() + " " + command + " --scene nosuchscene", out), 2);
    const size_t known = out.find("(known scenes: ");
    ASSERT_NE(known, std::string::npos) << out;
    for (const std::string& name : names) {
      // Each name ends at a comma, or at the semicolon after the last.
      const bool listed = out.find(" " + name + ",", known) != std::string::npos ||
                          out.find(" " + name + ";", known) != std::string::npos;
      EXPECT_TRUE(listed) << command << ": '" << name << "' missing from: " << out;
    }
  }
}

// An environment file round trip: a .hdr written by Tessera lights a scene under validation.
TEST(Cli, RendersWithAnEnvironmentFile) {
  ImageF sky{8, 4, std::vector<glm::vec4>(32, glm::vec4(0.5f, 0.6f, 0.9f, 1.0f))};
  const std::string hdr = test::output_path("sky.hdr");
  write_hdr_image(hdr, sky);
  const std::string png = test::output_path("env.png");
  std::string out;
  ASSERT_EQ(test::run_command(tool() +
                                  " render --device lavapipe --validate --scene spheres "
                                  "--size 64x64 --repeat 1 --env " +
                                  hdr + " --env-size 8 --env-samples 8 --out " + png,
                              out),
            0)
      << out;
  EXPECT_NE(out.find("DFG tables, irradiance and prefiltered cube"), std::string::npos) << out;
  // The background is the map's radiance: tone-mapped, not the scene's dark background.
  const Image8 image = read_png(png);
  EXPECT_GT(image.at(0, 0).b, 150) << "corner pixel shows the sky";
}

size_t count_of(const std::string& text, const std::string& part) {
  size_t n = 0;
  for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

// The first frame (pipeline compilation and other first-use costs) is reported apart from the
// timed ones, and the figures say how many frames they are a median of.
TEST(Cli, RenderReportsTheFirstFrameApartAndCountsTheTimedOnes) {
  const std::string png = test::output_path("cli.png");
  std::string out;
  ASSERT_EQ(test::run_command(
                tool() + " render --device lavapipe --validate --size 96x64 --out " + png, out),
            0)
      << out;
  EXPECT_NE(out.find("wrote " + png), std::string::npos) << out;
  EXPECT_EQ(count_of(out, "GPU time, first frame, including pipeline compilation"), 1u) << out;
  EXPECT_EQ(count_of(out, "GPU time, median of 3 frames after the first (ms):"), 1u) << out;
  EXPECT_EQ(count_of(out, "(min "), 1u) << "min and max of the timed frames only: " << out;
  EXPECT_EQ(count_of(out, "| total "), 2u) << out;

  ASSERT_EQ(test::run_command(
                tool() + " render --device lavapipe --size 32x32 --repeat 1 --out " + png, out),
            0)
      << out;
  EXPECT_EQ(count_of(out, "GPU time, median of 1 frame after the first (ms):"), 1u) << out;
  EXPECT_EQ(count_of(out, "(min "), 0u) << "no spread for one frame: " << out;

  ASSERT_EQ(test::run_command(
                tool() + " render --device lavapipe --size 32x32 --quiet --out " + png, out),
            0);
  EXPECT_EQ(out, "") << "--quiet prints nothing";

  const std::string reference = test::output_path("reference.png");
  ASSERT_EQ(test::run_command(tool() +
                                  " render --device reference --size 96x64 --repeat 2 "
                                  "--out " +
                                  reference,
                              out),
            0)
      << out;
  EXPECT_NE(out.find("wrote " + reference), std::string::npos) << out;
  EXPECT_EQ(count_of(out, "CPU time, first frame, including one-time setup"), 1u) << out;
  EXPECT_EQ(count_of(out, "CPU time, median of 2 frames after the first:"), 1u) << out;
  // Without --repeat the reference renders its first frame alone (the Vulkan devices time 3
  // after it): one CPU render for one image.
  ASSERT_EQ(
      test::run_command(tool() + " render --device reference --size 16x8 --out " + reference, out),
      0)
      << out;
  EXPECT_EQ(count_of(out, "CPU time, first frame, including one-time setup"), 1u) << out;
  EXPECT_EQ(count_of(out, "after the first"), 0u) << out;
  // Options only the Vulkan devices use are warned about, not silently accepted.
  ASSERT_EQ(test::run_command(tool() +
                                  " render --device reference --size 16x8 --validate "
                                  "--shade-tiles on --out " +
                                  reference,
                              out),
            0)
      << out;
  EXPECT_NE(out.find("warning: --validate: --device reference makes no Vulkan calls"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("warning: --shade-tiles: it tunes the Vulkan devices' passes"),
            std::string::npos)
      << out;
}

TEST(AntiAliasingCli, SamplesOptionTakesOneFourEightOrSixteen) {
  EXPECT_EQ(parse_command_line({"render", "--samples", "8"}).render.frame.samples, 8u);
  EXPECT_EQ(parse_command_line({"render"}).render.frame.samples, 1u);
  const CommandLine bench = parse_command_line({"bench", "--samples", "4"});
  EXPECT_EQ(bench.bench.samples, 4u);
  EXPECT_EQ(bench.bench.backends, std::vector<std::string>{"compute"});  // no hardware MSAA
  for (const std::string bad : {"3", "0", "32", "-4", "four", "4.0"}) {
    for (const std::string command : {"render", "bench"}) {
      const std::string message = usage_error({command, "--samples", bad});
      // One wording for a count of the wrong value and for what is not a count.
      EXPECT_EQ(message, "--samples: expects 1, 4, 8 or 16 samples per pixel, got '" + bad + "'");
    }
  }
  EXPECT_NE(usage_error({"bench", "--samples", "4", "--backends", "compute,hardware"})
                .find("--samples 4: the hardware backend"),
            std::string::npos);
}

// An index past the devices present names each of them, as `tessera devices` lists them.
// fp16 HDR saturates at 65504: --hdr-out says how many values were clamped there (a new
// user's trial: most of a brightly lit image was, without a word). A light of 1e9 W/sr 1 m
// in front of a plane of the default material (the xy plane, facing the camera) gives it about
// 1e9 / pi W/m^2/sr times its albedo, far past 65504; with fp32 nothing is.
TEST(Cli, ClampedHdrValuesAreNoted) {
  const std::string scene = test::output_path("bright.json");
  std::ofstream(scene) << R"({"camera": {"position": [0, 0, 3], "target": [0, 0, 0]},
      "meshes": [{"name": "p", "type": "plane"}], "materials": [{"name": "m"}],
      "objects": [{"mesh": "p", "material": "m", "scale": 10}],
      "lights": [{"type": "point", "position": [0, 0, 1], "intensity": 1e9}]})";
  const std::string base = tool() + " render --device reference --size 8x8 --scene " + scene +
                           " --out " + test::output_path("bright.png") + " --hdr-out " +
                           test::output_path("bright.pfm");
  std::string out;
  ASSERT_EQ(test::run_command(base, out), 0) << out;
  EXPECT_NE(out.find(" colour values of " + test::output_path("bright.pfm") +
                     " are 65504, the largest an fp16 HDR image holds"),
            std::string::npos)
      << out;
  ASSERT_EQ(test::run_command(base + " --hdr-format fp32", out), 0) << out;
  EXPECT_EQ(out.find("65504"), std::string::npos) << out;
}

// Options a render does not use are said to change nothing, each with why (a new user's
// trial: they were accepted without a word). The default scene has no textures and no
// environment, and its level of detail is off; with an environment, the reference takes its
// own sample count and the compute path's prefiltering options do nothing.
TEST(Cli, OptionsThatChangeNothingAreWarnedAbout) {
  const std::string base =
      tool() + " render --device reference --size 8x8 --out " + test::output_path("ignored.png");
  std::string out;
  ASSERT_EQ(test::run_command(base + " --lod-error 2 --anisotropy 16 --env-samples 4", out), 0)
      << out;
  for (const char* line :
       {"tessera: warning: --lod-error: level of detail is off for this render (--lod auto turns "
        "it on); the option changes nothing\n",
        "tessera: warning: --anisotropy: no material the scene draws with has a texture map, the "
        "only thing it filters; the option changes nothing\n",
        "tessera: warning: --env-samples: the scene has no environment; the option changes "
        "nothing\n"})
    EXPECT_NE(out.find(line), std::string::npos) << line << " in\n" << out;
  ASSERT_EQ(
      test::run_command(base + " --scene environment --env-size 64 --env-reference-samples 2", out),
      0)
      << out;
  EXPECT_NE(out.find("tessera: warning: --env-size: --device reference samples the environment "
                     "itself (--env-reference-samples); the option changes nothing\n"),
            std::string::npos)
      << out;
  EXPECT_EQ(out.find("--env-reference-samples:"), std::string::npos) << out;
}

TEST(Cli, DeviceIndexPastTheDevicesNamesThem) {
  const std::vector<DeviceInfo> devices = list_devices();
  ASSERT_FALSE(devices.empty());  // lavapipe, where the tests run
  for (const char* command : {"render", "bench", "view"}) {
    const std::string message = usage_error({command, "--device", "123456"});
    EXPECT_TRUE(message.starts_with("--device: device index 123456 is out of range: only " +
                                    std::to_string(devices.size()) +
                                    (devices.size() == 1 ? " device: " : " devices: ")))
        << message;
    for (const DeviceInfo& d : devices)
      EXPECT_NE(message.find(std::to_string(d.index) + " '" + d.name + "'"), std::string::npos)
          << message;
    EXPECT_TRUE(message.ends_with(" (`tessera devices`)")) << message;
    // The last index present is accepted.
    EXPECT_EQ(usage_error({command, "--device", std::to_string(devices.size() - 1)}), "");
  }
}

// A scene or model file that is not there is a bad command line, as a mistyped scene name is;
// one named like a built-in scene's file points to the built-in scene.
TEST(Cli, MissingSceneFileIsABadCommandLine) {
  for (const std::string command : {"render", "bench", "view"}) {
    EXPECT_EQ(usage_error({command, "--scene", "no/such/file.json"}),
              "--scene: no file 'no/such/file.json'")
        << command;
    EXPECT_EQ(usage_error({command, "--scene", "metals.json"}),
              "--scene: no file 'metals.json'; the built-in scene 'metals' is --scene metals")
        << command;
  }
  EXPECT_EQ(usage_error({"bench", "--scene", "nosuch.glb"}), "--scene: no file 'nosuch.glb'");
  const std::string folder = test::output_path("");
  for (const std::string command : {"render", "bench", "view"}) {
    EXPECT_EQ(usage_error({command, "--scene", folder}),
              "--scene: '" + folder +
                  "' is a folder, not a scene file (.json) or model (.gltf, .glb, .obj)")
        << command;
  }
  std::string out;
  EXPECT_EQ(test::run_command(tool() + " render --scene nosuch.json", out), 2) << out;
  // A file of a format Tessera does not read, named as a scene would be, is not a misspelt
  // scene name.
  std::ofstream(test::output_path("box.fbx")) << "Kaydara FBX Binary";
  EXPECT_EQ(test::run_command("cd " + std::filesystem::path(test::output_path("")).string() +
                                  " && " + tool() + " render --scene box.fbx",
                              out),
            2);
  EXPECT_NE(out.find("tessera: error: --scene: 'box.fbx' is a file of a format Tessera does not "
                     "read: give a scene file (.json) or a model (.gltf, .glb or .obj)"),
            std::string::npos)
      << out;
  // The same with a folder in the path (it was read as a scene file: a JSON syntax error).
  const std::string fbx = test::output_path("box.fbx");
  EXPECT_EQ(test::run_command(tool() + " render --scene " + fbx, out), 2);
  EXPECT_NE(out.find("tessera: error: --scene: '" + fbx + "' is a file of a format Tessera"),
            std::string::npos)
      << out;
  // A scene file by another extension is still read as one.
  const std::string txt = test::output_path("ball_scene.txt");
  std::ofstream(txt)
      << R"( {"meshes": [{"name": "m", "type": "sphere"}], "materials": [{"name": "red"}],
    "objects": [{"mesh": "m", "material": "red"}]})";
  EXPECT_EQ(test::run_command(tool() + " render --device lavapipe --size 8x8 --scene " + txt +
                                  " --out " + test::output_path("ball_scene.png"),
                              out),
            0)
      << out;
}

// `--device gpu` where only CPU devices are present (as here, on lavapipe) says so and names the
// way to render anyway, rather than that a GPU lacks features.
TEST(Cli, GpuAskedForWhereThereIsNoneNamesTheCpuDevice) {
  for (const DeviceInfo& d : list_devices()) {
    if (d.type != VK_PHYSICAL_DEVICE_TYPE_CPU) GTEST_SKIP() << "a GPU is present: " << d.name;
  }
  std::string out;
  EXPECT_EQ(
      test::run_command(
          tool() + " render --device gpu --size 8x8 --out " + test::output_path("never.png"), out),
      1);
  EXPECT_NE(out.find("tessera: error: no GPU found (--device lavapipe renders on the CPU); "
                     "devices: "),
            std::string::npos)
      << out;
}

// --aa-coverage weighs a pixel's samples: a mode other than count at 1 sample would do nothing,
// so it is refused, naming where the 1 sample came from.
TEST(AntiAliasingCli, CoverageModeAtOneSampleIsABadCommandLine) {
  for (const std::string command : {"render", "bench"}) {
    EXPECT_EQ(usage_error({command, "--aa-coverage", "analytic"}),
              "--aa-coverage analytic does nothing at 1 sample per pixel (the default of "
              "--samples): it weighs the visibility samples of a pixel; add --samples 4, 8 or 16");
    EXPECT_EQ(usage_error({command, "--aa-coverage", "silhouette", "--samples", "1"}),
              "--aa-coverage silhouette does nothing at --samples 1: it weighs the visibility "
              "samples of a pixel; add --samples 4, 8 or 16");
    EXPECT_EQ(usage_error({command, "--quality", "draft", "--aa-coverage", "silhouette"}),
              "--aa-coverage silhouette does nothing at 1 sample per pixel (--quality draft's): "
              "it weighs the visibility samples of a pixel; add --samples 4, 8 or 16");
    // What is not refused: count (one sample's count is that sample), more samples, given or
    // from a preset.
    EXPECT_EQ(usage_error({command, "--aa-coverage", "count"}), "");
    EXPECT_EQ(usage_error({command, "--aa-coverage", "analytic", "--samples", "4"}), "");
    EXPECT_EQ(usage_error({command, "--quality", "balanced", "--aa-coverage", "silhouette"}), "");
    EXPECT_EQ(usage_error({command, "--quality", "balanced", "--samples", "1", "--aa-coverage",
                           "analytic"}),
              "--aa-coverage analytic does nothing at --samples 1: it weighs the visibility "
              "samples of a pixel; add --samples 4, 8 or 16");
  }
  EXPECT_EQ(parse_command_line({"render", "--aa-coverage", "silhouette", "--samples", "8"})
                .render.frame.aa_coverage,
            AaCoverage::silhouette);
}

// --aa-walk-steps limits the silhouette walk: with another coverage mode it does nothing and is
// refused; 1 is not a walk, and neither is anything above 32 (the walk's triangle limit).
TEST(AntiAliasingCli, WalkStepsNeedSilhouetteCoverage) {
  for (const std::string command : {"render", "bench"}) {
    const std::string refused =
        "--aa-walk-steps does nothing without --aa-coverage silhouette: it limits the walk that "
        "measures a pixel's outline under silhouette coverage";
    EXPECT_EQ(usage_error({command, "--samples", "4", "--aa-walk-steps", "3"}), refused);
    EXPECT_EQ(usage_error(
                  {command, "--samples", "4", "--aa-coverage", "analytic", "--aa-walk-steps", "3"}),
              refused);
    EXPECT_NE(usage_error({command, "--samples", "4", "--aa-coverage", "silhouette",
                           "--aa-walk-steps", "1"}),
              "");
    EXPECT_NE(usage_error({command, "--samples", "4", "--aa-coverage", "silhouette",
                           "--aa-walk-steps", "33"}),
              "");
    EXPECT_EQ(usage_error({command, "--samples", "4", "--aa-coverage", "silhouette",
                           "--aa-walk-steps", "0"}),
              "");
    // 0, the default, limits nothing: given without silhouette coverage it is not refused.
    EXPECT_EQ(usage_error({command, "--aa-walk-steps", "0"}), "");
  }
  EXPECT_EQ(parse_command_line(
                {"render", "--samples", "4", "--aa-coverage", "silhouette", "--aa-walk-steps", "3"})
                .render.frame.silhouette_steps,
            3u);
  EXPECT_EQ(parse_command_line(
                {"bench", "--samples", "4", "--aa-coverage", "silhouette", "--aa-walk-steps", "4"})
                .bench.silhouette_steps,
            4u);
}

}  // namespace
}  // namespace tessera
