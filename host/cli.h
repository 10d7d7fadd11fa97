#pragma once
// The command line of the `tessera` tool: its commands, their options (parsed with CLI11, which
// also writes the --help texts) and how a bad command line is reported. Adding an option means
// a field in RenderArgs or BenchArgs and one add_option call in host/cli.cpp.

#include <cstdint>
#include <string>
#include <vector>

#include "compute/environment_gpu.h"
#include "compute/renderer.h"
#include "compute/swapchain.h"
#include "core/check.h"
#include "core/frame_settings.h"
#include "core/scene.h"
#include "host/quality.h"

namespace tessera {

struct RenderArgs {
  std::string scene = "spheres";
  FrameSettings frame;  // --size, --exposure, --tonemap, --view, --brdf, --anisotropy, ...
  std::string out = "tessera.png";
  std::string hdr_out;  // empty: no HDR file
  std::string device = "auto";
  std::string env;  // --env: a .hdr/.pfm file, "sky", "none", or empty (the scene's)
  EnvironmentOptions env_options;
  uint32_t env_reference_samples = 1024;        // Monte Carlo directions per lobe (reference)
  uint32_t tile_size = TS_TILE_SIZE;            // RendererOptions::tile_size
  bool depth_rejection = true;                  // RendererOptions::depth_rejection
  bool shade_tiles = false;                     // RendererOptions::shade_tiles
  bool raster_shade = false;                    // RendererOptions::raster_shade
  TileLists tile_lists = TileLists::automatic;  // RendererOptions::tile_lists
  Quality quality = Quality::none;              // --quality, applied by parse_command_line
  // Timed frames after the first, whose times (which include pipeline compilation and other
  // first-use costs) are reported apart; the figures are medians over these.
  // --device reference renders the first frame alone unless --repeat is given: each frame after
  // it costs the whole CPU render again.
  uint32_t repeat = 3;
  bool repeat_given = false;
  bool validate = false;
  bool quiet = false;
  bool strict = false;  // --strict: unknown keys in a scene file are errors
  uint32_t camera = 0;  // --camera N: the scene file's model camera N (use_model_camera)
  bool camera_given = false;
  // Which frame options the command line gave: the others come from the scene file's
  // "render" block when it has them.
  bool size_given = false, exposure_given = false, tonemap_given = false, brdf_given = false,
       view_given = false, samples_given = false;
  // --depth-rejection and --shade-tiles given: else the device's (raster_tuning,
  // compute/renderer.h).
  bool depth_rejection_given = false, shade_tiles_given = false, tile_lists_given = false,
       raster_shade_given = false;
  // Options that act only with some scenes or settings, given on the command line: warned
  // about where they do nothing (render_command.cpp, ignored_options).
  bool lod_error_given = false, anisotropy_given = false, env_size_given = false,
       env_samples_given = false, env_reference_samples_given = false;
};

struct BenchArgs {
  std::string scene = "grid";                    // a family of core/bench_scenes.h
  std::vector<uint32_t> objects = {1, 10, 100};  // object counts, the sweep
  uint32_t width = 512;
  uint32_t height = 512;
  bool size_given = false;     // --size given
  bool samples_given = false;  // --samples given: else 1 or --quality's
  uint32_t segments = 32;      // sphere tessellation: 960 triangles per sphere
  uint32_t samples = 1;        // FrameSettings::samples (compute and reference backends)
  AaCoverage aa_coverage = AaCoverage::count;  // FrameSettings::aa_coverage
  uint32_t silhouette_steps = 0;               // FrameSettings::silhouette_steps
  std::string device = "auto";
  std::vector<std::string> backends = {"compute", "hardware"};  // and/or "reference"
  uint32_t repeat = 10;    // timed frames per point; figures are their medians
  uint32_t warmup = 2;     // untimed frames first, at least
  double warmup_ms = 500;  // and at least this long, until the frame time settles (0: no)
  uint32_t runs = 1;       // whole sweeps; figures are the medians of their medians
  std::string compare;     // --compare: a saved --json run to print ratios against
  uint64_t reference_max_triangles = 2'000'000;  // the CPU reference runs only up to this
  uint32_t small_triangle_area = 128;            // RendererOptions::small_triangle_max_area
  bool generic_shading = false;                  // RendererOptions::specialize_lights off
  Lod lod = Lod::off;                            // FrameSettings::lod, for every backend
  float lod_error_px = 0.5f;                     // FrameSettings::lod_error_px
  HdrFormat hdr_format = HdrFormat::fp16;        // FrameSettings::hdr_format (not hardware)
  uint32_t tile_size = TS_TILE_SIZE;             // RendererOptions::tile_size
  bool depth_rejection = true;                   // RendererOptions::depth_rejection
  bool shade_tiles = false;                      // RendererOptions::shade_tiles
  bool raster_shade = false;                     // RendererOptions::raster_shade
  TileLists tile_lists = TileLists::automatic;   // RendererOptions::tile_lists
  Quality quality = Quality::none;               // --quality, applied by parse_command_line
  // --small-triangle-area, --depth-rejection, --shade-tiles, --tile-lists and --raster-shade
  // given: else the device's
  // (raster_tuning, compute/renderer.h), written here by run_bench once the device is known;
  // --quality's small-triangle area counts as given on GPUs (preset_sets_small_triangle_area).
  bool small_triangle_area_given = false, depth_rejection_given = false, shade_tiles_given = false,
       tile_lists_given = false, raster_shade_given = false;
  std::string csv, json, chart;
  bool quiet = false;
  bool strict = false;    // --strict: unknown keys in a scene file (and model warnings) are errors
  bool validate = false;  // Khronos validation layer; exit status 3 if it reports anything
};

struct ViewArgs {
  std::string scene = "spheres";
  FrameSettings frame;  // --size: the window's starting size; the frame follows the window
  std::string device = "auto";
  bool vsync = true;
  std::string script;  // --script: input events replayed at frame numbers (host/view_script.h)
  bool overlay = true;
  bool validate = false;
  bool strict = false;  // --strict: unknown keys in a scene file are errors
  uint32_t camera = 0;  // --camera N: the scene file's model camera N (use_model_camera)
  bool camera_given = false;
  bool size_given = false;
  PresentPath present = PresentPath::automatic;             // --present
  SurfaceFormat surface_format = SurfaceFormat::automatic;  // --surface-format
};

struct TradeoffArgs {
  std::string scene = "spheres";   // a scene of `tessera scenes`, a scene file, or a bench family
  uint32_t objects = 0;            // objects of a bench family (grid, scatter, huge); 0: 100
  std::vector<std::string> knobs;  // host/tradeoff.h, knobs()
  FrameSettings frame;             // --size, --hdr-format, --quality; the rest each knob's
  EnvironmentOptions env_options;  // the environment knobs' defaults
  uint32_t tile_size = TS_TILE_SIZE;  // RendererOptions::tile_size of every setting but its knob's
  // RendererOptions::small_triangle_max_area, likewise: --quality's on GPUs, else the device's
  // (tradeoff_base_options).
  uint32_t small_triangle_area = 128;
  Quality quality = Quality::none;  // --quality, applied by parse_command_line
  std::string device = "auto";
  uint32_t repeat = 10;               // timed frames per setting and round
  uint32_t warmup = 2;                // untimed frames per setting and round, at least
  double warmup_ms = 200;             // and this long, until the time settles (core/warmup.h)
  uint32_t rounds = 3;                // passes over all settings, interleaved
  uint32_t truth_samples = 8;         // N x N samples per pixel of the ground truth
  uint32_t truth_env_samples = 1024;  // environment directions per lobe and pixel of the truth
  std::string json, chart;
  bool quiet = false;
  bool strict = false;
  bool validate = false;
  bool size_given = false;
  bool brdf_given = false;  // --brdf or a preset's: a scene file's "render" block does not set it
};

enum class Command { help, render, bench, devices, scenes, view, tradeoff };

/// A parsed command line.
struct CommandLine {
  Command command = Command::help;
  std::string help;  // Command::help: the text asked for (the tool's or a command's)
  RenderArgs render;
  BenchArgs bench;
  ViewArgs view;
  TradeoffArgs tradeoff;
};

/// A command line that does not parse: an unknown command or option, a missing or bad value.
/// The message names the option; `help_command` is what shows the usage (e.g.
/// "tessera render --help").
struct UsageError : Error {
  UsageError(const std::string& message, std::string help_command)
      : Error(message), help_command(std::move(help_command)) {}
  std::string help_command;
};

/// Exit statuses of the tool.
constexpr int kExitRuntimeError = 1;     // a tessera::Error while running (files, devices)
constexpr int kExitUsageError = 2;       // a UsageError
constexpr int kExitValidationError = 3;  // --validate and the validation layer reported

/// Parses the arguments after the program name (argv[1..]). Throws UsageError.
/// "tessera 0.1 (git v0.1-12-gabcdef)": the project's version (CMakeLists.txt) and, where the
/// source was a git checkout when configured, `git describe` then (`tessera --version`).
std::string version_text();

CommandLine parse_command_line(const std::vector<std::string>& args);

}  // namespace tessera
