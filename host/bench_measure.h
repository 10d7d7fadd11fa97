#pragma once
// The measuring half of `tessera bench`: renders each point of the sweep with each backend and
// returns one row per point. Reporting (tables, CSV, JSON, charts) is in host/bench_report.h.

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "compute/context.h"
#include "compute/renderer.h"
#include "core/warmup.h"
#include "host/cli.h"

namespace tessera {

/// The CPU reference's timed frames at most (of --repeat): it is slow, and 3 suffice for a
/// median. It has no warm-up.
constexpr uint32_t kReferenceMaxFrames = 3;

/// One measured point of the sweep: a backend at an object count. Times are medians, in ms;
/// with several runs (--runs), the median of the runs' medians.
struct BenchRow {
  uint32_t objects = 0;
  std::string backend;
  uint64_t triangles_submitted = 0;
  uint64_t triangles_rasterized = 0;  // after culling and clipping (the hardware path: not counted)
  uint64_t pixels_shaded = 0;
  uint64_t small_triangles = 0;   // compute: rasterized one thread per triangle
  uint64_t bin_entries = 0;       // compute: blocks of tiles of binned triangles
  uint64_t tile_entries = 0;      // compute: (tile, triangle) pairs the per-tile rasterizer tests
  uint64_t rejected_entries = 0;  // compute: of those, skipped by depth rejection
  uint64_t rejected_small = 0;    // compute: small triangles skipped by depth rejection
  uint32_t tile_list_stride = 0;  // compute: slots per tile list (direct lists), 0 if counted
  // compute: the frames were rasterized and shaded in one pass (small frames; the small,
  // binned and tile-entry counts are then 0)
  bool rasterized_and_shaded = false;
  double total_ms = 0.0;  // GPU time (compute, hardware) or wall time (reference)
  // compute: the frames pass_ms comes from, timed with a timestamp after every pass, which
  // adds to the frame (Timing::frame); total_ms is of as many frames timed without them.
  double per_pass_total_ms = 0.0;
  double cpu_record_ms = 0.0;
  std::array<double, kPassCount> pass_ms{};
  double min_ms = 0.0;  // the fastest and slowest timed frame (of every run)
  double max_ms = 0.0;
  std::vector<double> run_ms;  // each run's median total_ms, in run order
  WarmupStats warmup;          // summed over the runs (stable: every run's was)
  uint32_t frames = 0;         // timed frames per run
  uint32_t batches = 0;
  bool skipped = false;  // the reference, above --reference-max-triangles
  std::string note;
  /// Run-to-run spread: (max - min) / median of the runs' medians, in percent (0 for one run).
  double run_spread_percent() const;
  double triangles_per_second() const {
    return total_ms > 0 ? triangles_submitted / (total_ms * 1e-3) : 0.0;
  }
};

struct BenchResults {
  std::vector<BenchRow> rows;  // by object count, then in the order of BenchArgs::backends
  std::vector<std::pair<uint32_t, double>> compute_over_hardware;  // (objects, time ratio)
  std::string device = "reference (CPU)";
  std::string driver;
  /// The signal (SIGINT, SIGTERM: host/stop_signal.h) that stopped the sweep before its end, 0
  /// when it ran to the end. `rows` then holds the points measured in at least one run.
  int interrupted = 0;
  size_t measurements_planned = 0;  // points x runs
  size_t measurements_made = 0;
};

/// The renderer options of the compute backend: `args`' rasterizer settings (the device's
/// already written where the command line gave none: run_bench), on `ctx`'s device's tuning
/// for the rest (tuned_for_device: the small-triangle walk area).
RendererOptions bench_renderer_options(const Context& ctx, const BenchArgs& args);

/// Runs the sweep `args` describes, `args.runs` times over (whole sweeps, one after the other),
/// and merges the runs per point. `ctx` is the device for the compute and hardware backends
/// (null when only the reference runs; it must outlive the call). `started`, if given, is called
/// once the counts have been checked, before the first point is measured; `row_done` with each
/// point's row as soon as it is final (in the last run), in the order of BenchResults::rows. After
/// stop_signal() (host/stop_signal.h) no further point is measured: the results hold those measured
/// so far (BenchResults::interrupted). Throws Error for a scene or size the renderer rejects.
BenchResults measure_bench(Context* ctx, const BenchArgs& args,
                           const std::function<void()>& started = {},
                           const std::function<void(const BenchRow&)>& row_done = {});

}  // namespace tessera
