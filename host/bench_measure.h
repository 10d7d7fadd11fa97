#pragma once
// The measuring half of `tessera bench`: renders each point of the sweep with each backend and
// returns one row per point. Reporting (tables, CSV, JSON, charts) is in host/bench_report.h.

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "compute/context.h"
#include "compute/renderer.h"
#include "host/cli.h"

namespace tessera {

/// One measured point of the sweep: a backend at an object count. Times are medians, in ms.
struct BenchRow {
  uint32_t objects = 0;
  std::string backend;
  uint64_t triangles_submitted = 0;
  uint64_t triangles_rasterized = 0;  // after culling and clipping (0: not known)
  uint64_t pixels_shaded = 0;
  uint64_t small_triangles = 0;  // compute: rasterized one thread per triangle
  uint64_t bin_entries = 0;      // compute: blocks of tiles of binned triangles
  uint64_t tile_entries = 0;     // compute: (tile, triangle) pairs the per-tile rasterizer tests
  double total_ms = 0.0;         // GPU time (compute, hardware) or wall time (reference)
  double cpu_record_ms = 0.0;
  std::array<double, kPassCount> pass_ms{};
  uint32_t frames = 0;
  uint32_t batches = 0;
  bool skipped = false;  // the reference, above --reference-max-triangles
  std::string note;
  double triangles_per_second() const {
    return total_ms > 0 ? triangles_submitted / (total_ms * 1e-3) : 0.0;
  }
};

struct BenchResults {
  std::vector<BenchRow> rows;  // by object count, then in the order of BenchArgs::backends
  std::vector<std::pair<uint32_t, double>> compute_over_hardware;  // (objects, time ratio)
  std::string device = "reference (CPU)";
  std::string driver;
};

/// Runs the sweep `args` describes. `ctx` is the device for the compute and hardware backends
/// (null when only the reference runs; it must outlive the call). Throws Error for a scene or
/// size the renderer rejects.
BenchResults measure_bench(Context* ctx, const BenchArgs& args);

}  // namespace tessera
