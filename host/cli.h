#pragma once
// Command-line parsing for the `tessera` tool. Each command has an options struct and a
// parser; adding an option means adding a field and one entry in its parser's table.

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "compute/environment_gpu.h"
#include "core/scene.h"

namespace tessera {

struct RenderArgs {
  std::string scene = "spheres";
  uint32_t width = 512;
  uint32_t height = 512;
  std::string out = "tessera.png";
  std::string hdr_out;  // empty: no HDR file
  std::string device = "auto";
  float exposure_ev = 0.0f;
  ToneMap tonemap = ToneMap::aces;
  View view = View::shaded;
  Brdf brdf = Brdf::classic;
  bool energy_compensation = false;
  std::string env;  // --env: a .hdr/.pfm file, "sky", "none", or empty (the scene's)
  EnvironmentOptions env_options;
  uint32_t env_reference_samples = 1024;  // Monte Carlo directions per lobe (reference)
  uint32_t anisotropy = 1;
  uint32_t repeat = 1;  // frames rendered; timings are the median over them
  bool validate = false;
  bool quiet = false;
  bool strict = false;  // --strict: unknown keys in a scene file are errors
  // Which frame options the command line gave: the others come from the scene file's
  // "render" block when it has them.
  bool size_given = false, exposure_given = false, tonemap_given = false, brdf_given = false;
};

/// Parses the arguments after `tessera render`. Throws tessera::Error naming the bad
/// argument. Returns false (and prints nothing) if --help was given.
bool parse_render_args(const std::vector<std::string>& args, RenderArgs& out);

/// Help text of `tessera render`.
std::string render_help();
/// Help text of `tessera` itself.
std::string main_help();

using ValueHandler = std::function<void(const std::string&)>;

/// Parses `--name value`, `--name=value` and `--flag` arguments with the given handlers.
/// Throws Error for an unknown option (naming `command` for help) or a missing value.
/// Returns false, handling nothing further, if --help or -h was given.
bool parse_options(const std::vector<std::string>& args,
                   const std::map<std::string, ValueHandler>& with_value,
                   const std::map<std::string, std::function<void()>>& flags,
                   const std::string& command);

/// Parses a whole number in [min, max] for `option`. Throws Error naming the option otherwise.
uint32_t parse_uint(const std::string& option, const std::string& text, uint32_t min, uint32_t max);

/// Parses "WxH" (e.g. "1920x1080"), each side in [1, 16384]. Throws Error otherwise.
void parse_size(const std::string& text, uint32_t& width, uint32_t& height);

}  // namespace tessera
