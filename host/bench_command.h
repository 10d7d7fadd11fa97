#pragma once
// `tessera bench`: sweeps a benchmark scene family over object counts and backends.

#include <cstdint>
#include <string>
#include <vector>

namespace tessera {

struct BenchArgs {
  std::string scene = "grid";                    // a family of core/bench_scenes.h
  std::vector<uint32_t> objects = {1, 10, 100};  // object counts, the sweep
  uint32_t width = 512;
  uint32_t height = 512;
  uint32_t segments = 32;  // sphere tessellation: 960 triangles per sphere
  std::string device = "auto";
  std::vector<std::string> backends = {"compute", "hardware"};  // and/or "reference"
  uint32_t repeat = 10;  // timed frames per point; figures are their medians
  uint32_t warmup = 2;   // untimed frames first
  uint64_t reference_max_triangles = 2'000'000;  // the CPU reference runs only up to this
  uint32_t small_triangle_area = 64;             // RendererOptions::small_triangle_max_area
  bool generic_shading = false;                  // RendererOptions::specialize_lights off
  std::string csv, json, chart;
  bool quiet = false;
  bool validate = false;  // Khronos validation layer; exit status 3 if it reports anything
};

/// Parses the arguments after `tessera bench`. Throws Error naming a bad argument; returns
/// false if --help was given.
bool parse_bench_args(const std::vector<std::string>& args, BenchArgs& out);
std::string bench_help();

/// Runs the sweep, prints a table and writes the requested files; returns the exit code.
int run_bench(const BenchArgs& args, const std::string& command_line);

}  // namespace tessera
