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

}  // namespace
}  // namespace tessera
