// `--quality draft|balanced|reference` (host/quality.h): every preset sets what the table of
// docs/tradeoffs.md, "Presets", says, read from the document itself and compared with what the
// same option given by hand sets; options given explicitly win over the preset.
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "host/cli.h"
#include "host/report.h"
#include "host/tradeoff.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

// The rows of the Presets table: option, then its value under draft, balanced and reference
// (backquoted cells; "on"/"off" for a flag).
std::vector<std::vector<std::string>> preset_rows() {
  const std::filesystem::path doc =
      std::filesystem::path(TESSERA_README).parent_path() / "docs" / "tradeoffs.md";
  std::ifstream file(doc);
  EXPECT_TRUE(file) << doc;
  std::vector<std::vector<std::string>> rows;
  std::string line;
  bool in_section = false;
  while (std::getline(file, line)) {
    if (line.starts_with("## ")) in_section = line == "## Presets";
    if (!in_section || !line.starts_with("| `--")) continue;
    std::vector<std::string> cells;
    std::stringstream row(line.substr(1));
    std::string cell;
    while (std::getline(row, cell, '|')) {
      const size_t a = cell.find('`'), b = cell.rfind('`');
      cells.push_back(a != std::string::npos && b > a ? cell.substr(a + 1, b - a - 1) : "");
    }
    if (cells.size() >= 4) rows.push_back({cells.begin(), cells.begin() + 4});
  }
  return rows;
}

// What each option sets in `render`'s arguments, as text to compare.
const std::map<std::string, std::function<std::string(const RenderArgs&)>>& render_fields() {
  static const std::map<std::string, std::function<std::string(const RenderArgs&)>> fields = {
      {"--brdf", [](const RenderArgs& a) { return std::to_string(int(a.frame.brdf)); }},
      {"--energy-compensation",
       [](const RenderArgs& a) { return std::to_string(a.frame.energy_compensation); }},
      {"--samples", [](const RenderArgs& a) { return std::to_string(a.frame.samples); }},
      {"--lod", [](const RenderArgs& a) { return std::to_string(int(a.frame.lod)); }},
      {"--lod-error", [](const RenderArgs& a) { return std::to_string(a.frame.lod_error_px); }},
      {"--anisotropy", [](const RenderArgs& a) { return std::to_string(a.frame.max_anisotropy); }},
      {"--env-size",
       [](const RenderArgs& a) { return std::to_string(a.env_options.specular_size); }},
      {"--env-samples",
       [](const RenderArgs& a) { return std::to_string(a.env_options.specular_samples); }},
      {"--hdr-format", [](const RenderArgs& a) { return std::to_string(int(a.frame.hdr_format)); }},
      {"--tile-size", [](const RenderArgs& a) { return std::to_string(a.tile_size); }},
  };
  return fields;
}

RenderArgs render_args(const std::vector<std::string>& args) {
  std::vector<std::string> line = {"render"};
  line.insert(line.end(), args.begin(), args.end());
  return parse_command_line(line).render;
}

TEST(Quality, PresetsSetWhatTheDocumentSays) {
  const std::vector<std::vector<std::string>> rows = preset_rows();
  ASSERT_GE(rows.size(), 10u) << "the Presets table of docs/tradeoffs.md";
  const char* presets[] = {"draft", "balanced", "reference"};
  size_t checked = 0;
  for (const std::vector<std::string>& row : rows) {
    const auto field = render_fields().find(row[0]);
    if (field == render_fields().end()) continue;  // an option render does not have
    for (int p = 0; p < 3; ++p) {
      const std::string& value = row[1 + p];
      std::vector<std::string> by_hand;
      if (row[0] == "--energy-compensation") {
        if (value == "on") by_hand = {row[0]};
      } else {
        by_hand = {row[0], value};
      }
      EXPECT_EQ(field->second(render_args({"--quality", presets[p]})),
                field->second(render_args(by_hand)))
          << row[0] << " under --quality " << presets[p] << ": the document says " << value;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 3 * render_fields().size()) << "every option render has is in the table";
}

TEST(Quality, ExplicitOptionsWin) {
  const RenderArgs a = render_args(
      {"--quality", "reference", "--samples", "1", "--brdf", "classic", "--hdr-format", "fp16"});
  EXPECT_EQ(a.frame.samples, 1u);
  EXPECT_EQ(a.frame.brdf, Brdf::classic);
  EXPECT_FALSE(a.frame.energy_compensation) << "a given --brdf keeps the preset's compensation";
  EXPECT_EQ(a.frame.hdr_format, HdrFormat::fp16);
  // What was not given is the preset's.
  const RenderArgs reference = render_args({"--quality", "reference"});
  EXPECT_EQ(a.frame.lod_error_px, reference.frame.lod_error_px);
  EXPECT_EQ(a.frame.max_anisotropy, reference.frame.max_anisotropy);
  EXPECT_TRUE(a.brdf_given) << "a preset's BRDF wins over a scene file's";
  // Without --quality nothing changes.
  const RenderArgs plain = render_args({});
  EXPECT_EQ(plain.frame.samples, 1u);
  EXPECT_EQ(plain.frame.lod, Lod::off);
  EXPECT_EQ(plain.frame.hdr_format, HdrFormat::fp16);
  EXPECT_FALSE(plain.brdf_given);
}

TEST(Quality, BenchAndTradeoffTakeTheirShare) {
  const RenderArgs balanced = render_args({"--quality", "balanced"});
  const CommandLine bench = parse_command_line({"bench", "--quality", "balanced"});
  EXPECT_EQ(bench.bench.samples, balanced.frame.samples);
  EXPECT_EQ(bench.bench.lod, balanced.frame.lod);
  EXPECT_EQ(bench.bench.lod_error_px, balanced.frame.lod_error_px);
  EXPECT_EQ(bench.bench.tile_size, balanced.tile_size);
  if (balanced.frame.samples > 1) {
    // The hardware baseline renders one sample: the default backends become compute alone,
    // and asking for it explicitly is an error.
    EXPECT_EQ(bench.bench.backends, std::vector<std::string>{"compute"});
    EXPECT_THROW(parse_command_line({"bench", "--quality", "balanced", "--backends", "hardware"}),
                 UsageError);
  }
  const CommandLine explicit_bench =
      parse_command_line({"bench", "--quality", "balanced", "--samples", "1"});
  EXPECT_EQ(explicit_bench.bench.samples, 1u);
  const CommandLine tradeoff =
      parse_command_line({"tradeoff", "--quality", "draft", "--knob", "samples"});
  const RenderArgs draft = render_args({"--quality", "draft"});
  EXPECT_EQ(tradeoff.tradeoff.frame.brdf, draft.frame.brdf);
  EXPECT_EQ(tradeoff.tradeoff.frame.samples, draft.frame.samples);
  EXPECT_EQ(tradeoff.tradeoff.env_options.specular_size, draft.env_options.specular_size);
  EXPECT_EQ(tradeoff.tradeoff.tile_size, draft.tile_size);
  EXPECT_THROW(parse_command_line({"render", "--quality", "best"}), UsageError);
}

std::string usage_error(const std::vector<std::string>& args) {
  try {
    parse_command_line(args);
  } catch (const UsageError& e) {
    return e.what();
  }
  return "no error";
}

// A value the user never typed is named as the preset's, with the option that overrides it.
TEST(Quality, ErrorsFromAPresetsValueNameThePreset) {
  EXPECT_NE(usage_error({"bench", "--quality", "reference", "--backends", "compute,hardware"})
                .find("--quality reference sets --samples 16: the hardware backend renders 1 "
                      "sample per pixel; leave it out of --backends, or add --samples 1"),
            std::string::npos)
      << usage_error({"bench", "--quality", "reference", "--backends", "compute,hardware"});
  // Given by hand, the option is named as given.
  const std::string given = usage_error({"bench", "--samples", "16", "--backends", "hardware"});
  EXPECT_NE(given.find("--samples 16: the hardware backend renders 1 sample per pixel; leave it "
                       "out of --backends"),
            std::string::npos)
      << given;
  EXPECT_EQ(given.find("--quality"), std::string::npos) << given;
  const std::string hdr =
      usage_error({"bench", "--quality", "reference", "--samples", "1", "--backends", "hardware"});
  EXPECT_NE(hdr.find("--quality reference sets --hdr-format fp32: the hardware backend renders "
                     "into an fp16 image; leave it out of --backends, or add --hdr-format fp16"),
            std::string::npos)
      << hdr;
  // A size too large at the preset's samples (render, bench, tradeoff report it alike).
  const ImageSizeError e(2048, 2048, "at 16 samples needs more");
  EXPECT_EQ(with_samples_source(e, Quality::reference, false, 16).reason,
            "at 16 samples needs more (--quality reference sets --samples 16)");
  EXPECT_EQ(with_samples_source(e, Quality::reference, true, 16).reason, e.reason);
  EXPECT_EQ(with_samples_source(e, Quality::none, false, 16).reason, e.reason);
  std::string out;
  EXPECT_EQ(test::run_command(std::string(TESSERA_BINARY) +
                                  " render --device lavapipe --quality reference --size 2048x2048 "
                                  "--out " +
                                  test::output_path("quality_too_large.png"),
                              out),
            2)
      << out;
  EXPECT_NE(out.find("--size 2048x2048: at 16 samples"), std::string::npos) << out;
  EXPECT_NE(out.find("(--quality reference sets --samples 16)"), std::string::npos) << out;
  // tradeoff has no --samples or --lod: a preset's make raster-shade unable to matter.
  const CommandLine balanced = parse_command_line(
      {"tradeoff", "--quality", "balanced", "--knob", "raster-shade,brdf", "--size", "8x8"});
  const TradeoffScene scene = load_tradeoff_scene(balanced.tradeoff);
  ASSERT_EQ(scene.skipped.size(), 1u);
  EXPECT_EQ(scene.skipped[0].reason,
            "the frames are at 4 samples, and only frames at 1 take the one pass (--quality "
            "balanced sets --samples 4)");
  const CommandLine draft = parse_command_line(
      {"tradeoff", "--quality", "draft", "--knob", "raster-shade,brdf", "--size", "8x8"});
  ASSERT_EQ(load_tradeoff_scene(draft.tradeoff).skipped.size(), 1u);
  EXPECT_EQ(load_tradeoff_scene(draft.tradeoff).skipped[0].reason,
            "the frames have level of detail, and only frames without take the one pass "
            "(--quality draft sets --lod auto)");
}

TEST(Quality, RenderSaysWhatThePresetChose) {
  // The settings as the table of docs/tradeoffs.md, "Presets", gives reference's.
  const RenderArgs reference = render_args({"--quality", "reference"});
  EXPECT_EQ(quality_settings_line(Quality::reference, reference.frame, &reference.env_options,
                                  reference.tile_size),
            "--quality reference: filament BRDF with energy compensation, 16 samples per pixel "
            "(count coverage), level of detail off, 16x anisotropic texture filtering, "
            "environment cube of 256 px and 512 samples per texel, fp32 HDR, tiles of 16 px");
  // An option given wins, and the line says what the frame used.
  const RenderArgs draft = render_args({"--quality", "draft", "--anisotropy", "8"});
  EXPECT_EQ(quality_settings_line(Quality::draft, draft.frame, nullptr, draft.tile_size),
            "--quality draft: classic BRDF with energy compensation, 1 sample per pixel, level "
            "of detail auto at 0.5 px, 8x anisotropic texture filtering, fp16 HDR");
  EXPECT_EQ(quality_settings_line(Quality::none, draft.frame, nullptr, 16), "");
  // The tool prints it once, with its other lines, and not under --quiet.
  const std::string png = test::output_path("quality_render.png");
  std::string out;
  ASSERT_EQ(test::run_command(std::string(TESSERA_BINARY) +
                                  " render --device lavapipe --quality draft --size 16x16 "
                                  "--repeat 1 --out " +
                                  png,
                              out),
            0)
      << out;
  const std::string line = "--quality draft: classic BRDF with energy compensation";
  ASSERT_NE(out.find(line), std::string::npos) << out;
  EXPECT_EQ(out.find(line, out.find(line) + 1), std::string::npos) << "once:\n" << out;
  ASSERT_EQ(test::run_command(std::string(TESSERA_BINARY) +
                                  " render --device lavapipe --quality draft --size 16x16 "
                                  "--repeat 1 --quiet --out " +
                                  png,
                              out),
            0)
      << out;
  EXPECT_EQ(out.find("--quality"), std::string::npos) << out;
}

}  // namespace
}  // namespace tessera
