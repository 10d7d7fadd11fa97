#pragma once
// `tessera bench --compare BASE.json`: each point's time against a saved `--json` run, as
// Google Benchmark's compare.py does (old, new, new / old), points matched by scene, object
// count, image size and backend.

#include <cstdint>
#include <string>
#include <vector>

#include "host/bench_measure.h"
#include "host/cli.h"

namespace tessera {

/// A point of a saved run: what identifies it and its figure (total_ms, the median).
struct SavedPoint {
  std::string scene;
  uint32_t objects = 0;
  uint32_t width = 0, height = 0;
  std::string backend;
  double total_ms = 0.0;
};

struct SavedRun {
  std::string path;
  std::string device, date;  // as recorded (empty if the file has none)
  std::vector<SavedPoint> points;
  // The frame settings it recorded (bench_settings' keys present in the file), as JSON text.
  std::vector<std::pair<std::string, std::string>> settings;
  // A compute point lacks per_pass_total_ms: the file is from before `tessera bench` timed the
  // compute frames whole, so its compute times include the timestamps between passes.
  bool compute_timed_by_pass = false;
  // The base's sweep was stopped by a signal (its "interrupted"): it lacks points it planned,
  // and its last points may come from fewer runs than it asked. Its measurement counts as
  // recorded (0 in a file from before they were).
  bool interrupted = false;
  uint64_t measurements_planned = 0, measurements_made = 0;
};

/// The settings of a bench run that change what a frame computes, by the keys its `--json`
/// file records them under (samples, aa_coverage, aa_walk_steps, lod, segments,
/// small_triangle_area, tile_size, depth_rejection, shade_tiles, tile_lists, hdr_format), each as
/// JSON text.
std::vector<std::pair<std::string, std::string>> bench_settings(const BenchArgs& args);

/// "key value (base: value)" for each setting `base` recorded that this run's `args` differ in;
/// empty if none (a file from before a key was recorded is not compared on it).
std::vector<std::string> differing_settings(const SavedRun& base, const BenchArgs& args);

/// Reads the points of a file `tessera bench --json` wrote. Throws Error naming `path` when it
/// cannot be read, is not JSON (with the parser's line and column), or lacks a field of that
/// format (scene, width, height, results[i].objects / backend / total_ms).
SavedRun read_bench_json(const std::string& path);

/// One row of the comparison. `old_ms` < 0: only in this run; `new_ms` < 0: only in the base.
struct ComparedPoint {
  SavedPoint point;  // scene, objects, size, backend (total_ms unused)
  double old_ms = -1.0, new_ms = -1.0;
  bool matched() const { return old_ms >= 0 && new_ms >= 0; }
  double ratio() const { return old_ms > 0 ? new_ms / old_ms : 0.0; }  // new / old
};

/// This run's points in their order (matched, or only here), then the base's points this run
/// does not have. Skipped rows (the reference over its triangle limit) count as absent.
std::vector<ComparedPoint> compare_runs(const SavedRun& base, const BenchResults& results,
                                        const BenchArgs& args);

/// Prints the comparison table: old ms, new ms, new / old, and the unmatched points by name;
/// first a warning naming the settings that differ from the base's (`differing`), whose ratios
/// then compare unlike frames, one when the base was measured on another device than this
/// run's `device`, one when the base's sweep was interrupted (SavedRun::interrupted), and one
/// when no point of this run is in the base (another scene or size).
void print_comparison(const SavedRun& base, const std::vector<ComparedPoint>& points,
                      const std::vector<std::string>& differing, const std::string& device);

}  // namespace tessera
