#include "host/bench_measure.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <memory>

#include <unistd.h>

#include "compute/baselines/hardware_baseline.h"
#include "compute/scene_upload.h"
#include "core/bench_scenes.h"
#include "core/builtin_scenes.h"
#include "core/check.h"
#include "core/lod.h"
#include "core/reference_renderer.h"
#include "core/statistics.h"
#include "host/bench_content.h"
#include "host/heap_reuse.h"
#include "host/report.h"
#include "host/scene_source.h"
#include "host/stop_signal.h"

namespace tessera {
namespace {

class Progress {
 public:
  Progress(size_t total, bool enabled)
      : total_(total), enabled_(enabled && isatty(fileno(stderr))) {}
  void step(const std::string& what) {
    if (!enabled_) return;
    const int width = 30;
    const int filled = int(width * done_ / std::max<size_t>(total_, 1));
    std::fprintf(stderr, "\r[%s%s] %zu/%zu %-40s", std::string(filled, '#').c_str(),
                 std::string(width - filled, '.').c_str(), done_, total_, what.c_str());
    std::fflush(stderr);
    ++done_;
  }
  // Erases the bar, for a line of the table printed on the same terminal.
  void clear() {
    if (enabled_) std::fprintf(stderr, "\r%80s\r", "");
  }
  ~Progress() { clear(); }

 private:
  size_t total_, done_ = 0;
  bool enabled_;
};

WarmupRule warmup_rule(const BenchArgs& a) {
  WarmupRule rule;
  rule.min_frames = a.warmup;
  rule.ms = a.warmup_ms;
  return rule;
}

void set_range(BenchRow& row, const std::vector<double>& totals) {
  const Summary s = summarize(totals);
  row.total_ms = s.median;
  row.min_ms = s.min;
  row.max_ms = s.max;
}

// `repeat` frames timed pass by pass, for the passes' times, then as many timed whole, for the
// frame's: the timestamps between passes would add to it (Timing::frame).
BenchRow measure_compute(Renderer& r, const FrameSettings& settings, const BenchArgs& a) {
  // Nothing reads the timed frames' keys, so they need not be kept (the pixel count in
  // run_sweep reads them from an untimed frame before).
  FrameSettings fs = settings;
  fs.keep_visibility = false;
  const WarmupStats warmup = warm_up([&] { return r.render(fs).gpu_total_ms; }, warmup_rule(a));
  std::vector<FrameStats> frames;
  for (uint32_t i = 0; i < a.repeat; ++i) frames.push_back(r.render(fs));
  std::vector<double> cpu, per_pass_total, total;
  for (const FrameStats& f : frames) per_pass_total.push_back(f.gpu_total_ms);
  for (uint32_t i = 0; i < a.repeat; ++i) {
    const FrameStats f = r.render(fs, Timing::frame);
    total.push_back(f.gpu_total_ms);
    cpu.push_back(f.cpu_record_submit_ms);
  }
  BenchRow row;
  row.warmup = warmup;
  row.pass_ms = pass_medians(frames);
  row.per_pass_total_ms = median(per_pass_total);
  set_range(row, total);
  row.cpu_record_ms = median(cpu);
  const FrameStats& last = frames.back();
  row.triangles_rasterized = last.raster_triangles;
  row.small_triangles = last.small_triangles;
  row.bin_entries = last.big_triangles;
  row.tile_entries = last.tile_entries;
  row.rejected_entries = last.rejected_entries;
  row.rejected_small = last.rejected_small;
  row.tile_list_stride = last.tile_list_stride;
  row.rasterized_and_shaded = last.rasterized_and_shaded;
  row.batches = last.batches;
  row.frames = a.repeat;
  if (!last.has_timestamps) row.note = "no timestamps";
  return row;
}

// The hardware baseline (compute/baselines/): timestamps around its render pass (clear, draws,
// shading) are the yardstick.
BenchRow measure_hardware(Renderer& r, const FrameSettings& fs, const BenchArgs& a) {
  HardwareBaseline hardware(r);
  const WarmupStats warmup =
      warm_up([&] { return hardware.render(fs).render_pass_ms; }, warmup_rule(a));
  std::vector<double> pass, cpu;
  for (uint32_t i = 0; i < a.repeat; ++i) {
    const BaselineStats s = hardware.render(fs);
    pass.push_back(s.render_pass_ms);
    cpu.push_back(s.cpu_record_submit_ms);
  }
  BenchRow row;
  row.warmup = warmup;
  set_range(row, pass);
  row.cpu_record_ms = median(cpu);
  row.frames = a.repeat;
  return row;
}

BenchRow measure_reference(const Scene& scene, const FrameSettings& fs, const BenchArgs& a) {
  ReferenceSettings rs;
  rs.frame = fs;
  const uint32_t frames = std::min(a.repeat, kReferenceMaxFrames);
  std::vector<double> wall;
  keep_freed_memory_for_reuse();  // each frame freed before the next takes its pages
  ReferenceFrame f;
  for (uint32_t i = 0; i < frames; ++i) {
    f = ReferenceFrame{};
    const auto start = std::chrono::steady_clock::now();
    f = render_reference(scene, rs);
    wall.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count());
  }
  BenchRow row;
  set_range(row, wall);
  row.triangles_rasterized = f.raster_triangles;
  row.frames = frames;
  row.note = "CPU wall time";
  return row;
}

// compute / hardware per object count, from the same run.
std::vector<std::pair<uint32_t, double>> compute_over_hardware(const std::vector<BenchRow>& rows) {
  std::vector<std::pair<uint32_t, double>> ratios;
  for (const BenchRow& c : rows) {
    if (c.backend != "compute") continue;
    for (const BenchRow& h : rows) {
      if (h.objects == c.objects && h.backend == "hardware" && h.total_ms > 0)
        ratios.push_back({c.objects, c.total_ms / h.total_ms});
    }
  }
  return ratios;
}

// One sweep's rows, in order; `complete` false where a stop signal ended it early.
struct Sweep {
  std::vector<BenchRow> rows;
  size_t points = 0;  // (object count, backend) pairs the sweep measures when it runs to its end
  bool complete = true;
};

// One whole sweep: a row per (object count, backend); `run` (from 0) labels the progress bar.
// `max_range`: the device's maxStorageBufferRange (0 without a renderer). `measured` is called
// with each row as it is measured, `checked` when the counts have passed their checks. A stop
// signal ends it before the next scene or point: never inside a frame, whose submission is waited
// for.
Sweep measure_sweep(Renderer* renderer, uint64_t max_range, const BenchArgs& a, uint32_t run,
                    const std::function<void()>& checked,
                    const std::function<void(const BenchRow&)>& measured) {
  Sweep sweep;
  std::vector<BenchRow>& rows = sweep.rows;
  FrameSettings fs;
  fs.width = a.width;
  fs.height = a.height;
  fs.lod = a.lod;
  fs.lod_error_px = a.lod_error_px;
  fs.samples = a.samples;
  fs.aa_coverage = a.aa_coverage;
  fs.silhouette_steps = a.silhouette_steps;
  fs.hdr_format = a.hdr_format;
  const float aspect = float(a.width) / float(a.height);

  // A built-in scene has a fixed object count: it is one point of the sweep. A scene or model
  // file is content that each point places N times on the grid family's layout.
  const bool file = is_scene_path(a.scene) || is_model_path(a.scene);
  // A scene by name (built in, or NAME.json of the scenes folder) is one point of the sweep.
  const bool builtin = !file && (is_builtin_scene(a.scene) || is_named_scene(a.scene));
  BenchContent content;
  if (builtin) content.scene = load_scene_argument(a.scene, a.strict, a.quiet).scene;
  if (file) content = load_bench_content(a.scene, a.strict, a.quiet);
  const Scene& fixed = content.scene;
  const std::vector<uint32_t> counts =
      builtin ? std::vector<uint32_t>{uint32_t(fixed.objects.size())} : a.objects;
  // Each count's triangle instances, from one object's or placement's (every family and file
  // grows linearly with N), before any scene is built: a count past what the renderer can number
  // was refused only after its scene was built, a minute for 2^24 grid spheres.
  if (!builtin) {
    const Scene one = file ? make_instanced_bench_scene(fixed, 1, aspect)
                           : make_bench_scene(a.scene, 1, a.segments, aspect);
    const uint64_t per = lod_triangle_count(one, {}, FrameSettings{});
    for (uint32_t n : counts)
      check_triangle_numbering(per, n, file ? "placement of '" + a.scene + "'" : "object",
                               file ? "placements" : "objects");
    // The file's lights move and scale with the grid, which grows with the count: a count
    // that takes one past the scene's limits is refused here, not once the smaller ones are
    // measured.
    if (file)
      for (uint32_t n : counts) check_bench_lights(content, n, aspect);
    // And each count's buffers against the device's maxStorageBufferRange, which set_scene
    // would refuse only at that point, after the sweep's smaller counts: of the arrays only the
    // objects and their group table grow with N (every placement shares the meshes and textures).
    if (renderer) {
      const SceneBufferCounts base = buffer_counts(flatten_scene(one));
      for (uint32_t n : counts) {
        SceneBufferCounts c = base;
        c.objects = base.objects * n;
        c.group_objects = (per * n + TS_TRIANGLE_GROUP - 1) / TS_TRIANGLE_GROUP;
        try {
          check_scene_buffers(c, max_range);
        } catch (const SceneSizeError& e) {
          std::string placements;
          if (file && e.buffer == "object buffer") {
            placements = " (" + std::to_string(uint64_t(e.limit) * n / e.bytes) + " placements)";
          }
          throw Error("--objects " + std::to_string(n) + ": " + e.what() + placements);
        }
      }
    }
  }
  checked();
  sweep.points = counts.size() * a.backends.size();
  Progress progress(sweep.points, !a.quiet);
  const std::string run_label =
      a.runs > 1 ? "run " + std::to_string(run + 1) + "/" + std::to_string(a.runs) + ", " : "";
  for (uint32_t n : counts) {
    if (stop_signal()) {
      sweep.complete = false;
      return sweep;
    }
    const Scene scene = builtin ? fixed
                        : file  ? make_instanced_bench_scene(fixed, n, aspect)
                                : make_bench_scene(a.scene, n, a.segments, aspect);
    // After the level of detail, which the compute path counts on the GPU.
    uint64_t triangles = fs.lod == Lod::off || renderer
                             ? lod_triangle_count(scene, {}, FrameSettings{})
                             : lod_triangle_count(scene, build_lod_chains(scene), fs);
    uint64_t pixels_shaded = 0;
    if (renderer) {
      renderer->set_scene(scene);  // uploaded once, outside the timed frames
      triangles = renderer->render(fs).triangles_submitted;
      // Pixels with at least one covered sample.
      const std::vector<uint64_t> keys = renderer->read_visibility();
      for (size_t p = 0; p < keys.size(); p += fs.samples)
        pixels_shaded +=
            *std::min_element(keys.begin() + p, keys.begin() + p + fs.samples) != ~0ull;
    }
    for (const std::string& backend : a.backends) {
      if (stop_signal()) {
        sweep.complete = false;
        return sweep;
      }
      progress.step(run_label + "objects " + std::to_string(n) + ", " + backend);
      BenchRow row;
      if (backend == "compute") {
        row = measure_compute(*renderer, fs, a);
      } else if (backend == "hardware") {
        row = measure_hardware(*renderer, fs, a);
      } else if (triangles <= a.reference_max_triangles) {
        row = measure_reference(scene, fs, a);
      } else {
        row.skipped = true;
      }
      row.objects = file ? uint32_t(scene.objects.size()) : n;  // N copies of the file's objects
      row.backend = backend;
      row.triangles_submitted = triangles;
      row.pixels_shaded = pixels_shaded;
      rows.push_back(row);
      progress.clear();
      measured(row);
    }
  }
  return sweep;
}

// One point's row from its row in each run that measured it, in run order: figures are medians
// over the runs, extremes the extremes, warm-ups add up.
BenchRow merge_point(const std::vector<BenchRow>& runs) {
  BenchRow m = runs.front();
  std::vector<double> cpu, per_pass_total;
  m.run_ms.clear();
  for (const BenchRow& r : runs) {
    TESSERA_CHECK(r.objects == m.objects && r.backend == m.backend);
    m.run_ms.push_back(r.total_ms);
    cpu.push_back(r.cpu_record_ms);
    per_pass_total.push_back(r.per_pass_total_ms);
    m.min_ms = std::min(m.min_ms, r.min_ms);
    m.max_ms = std::max(m.max_ms, r.max_ms);
    if (&r != &runs.front()) {
      m.warmup.frames += r.warmup.frames;
      m.warmup.ms += r.warmup.ms;
      m.warmup.stable = m.warmup.stable && r.warmup.stable;
    }
  }
  m.total_ms = median(m.run_ms);
  m.cpu_record_ms = median(cpu);
  m.per_pass_total_ms = median(per_pass_total);
  // Counts come from the first run; a run that split the frame differently is named, since
  // each batch is a whole sequence of passes (one sphere once ran in 17 batches after 10^6).
  bool batches_differ = false;
  std::string batches;
  for (const BenchRow& r : runs) {
    batches += (batches.empty() ? "" : ", ") + std::to_string(r.batches);
    batches_differ = batches_differ || r.batches != m.batches;
  }
  if (batches_differ) m.note += (m.note.empty() ? "" : "; ") + ("batches per run: " + batches);
  for (size_t p = 0; p < kPassCount; ++p) {
    std::vector<double> v;
    for (const BenchRow& r : runs) v.push_back(r.pass_ms[p]);
    m.pass_ms[p] = median(v);
  }
  return m;
}

// Point `i`'s rows of the runs that measured it (an interrupted run may not have).
std::vector<BenchRow> point_rows(const std::vector<std::vector<BenchRow>>& runs, size_t i) {
  std::vector<BenchRow> out;
  for (const std::vector<BenchRow>& run : runs) {
    if (i < run.size()) out.push_back(run[i]);
  }
  return out;
}

}  // namespace

double BenchRow::run_spread_percent() const {
  if (run_ms.size() < 2 || total_ms <= 0) return 0.0;
  const auto [lo, hi] = std::minmax_element(run_ms.begin(), run_ms.end());
  return (*hi - *lo) / total_ms * 100.0;
}

RendererOptions bench_renderer_options(const Context& ctx, const BenchArgs& a) {
  // The device's tuning first, for what the command line has no option for: the walk area,
  // which on a CPU device walks every box whole as the small-triangle area it was measured
  // with did (raster_tuning).
  RendererOptions options = tuned_for_device(ctx, {});
  options.small_triangle_max_area = a.small_triangle_area;
  options.tile_size = a.tile_size;
  options.depth_rejection = a.depth_rejection;
  options.shade_tiles = a.shade_tiles;
  options.raster_shade = a.raster_shade;
  options.tile_lists = a.tile_lists;
  options.specialize_lights = !a.generic_shading;
  return options;
}

BenchResults measure_bench(Context* ctx, const BenchArgs& a, const std::function<void()>& started,
                           const std::function<void(const BenchRow&)>& row_done) {
  BenchResults results;
  std::unique_ptr<Renderer> renderer;
  if (ctx) {
    renderer = std::make_unique<Renderer>(*ctx, bench_renderer_options(*ctx, a));
    results.device = ctx->properties.deviceName;
    results.driver = ctx->driver;
  }
  const uint32_t run_count = std::max(a.runs, 1u);
  const uint64_t max_range = ctx ? ctx->properties.limits.maxStorageBufferRange : 0;
  std::vector<std::vector<BenchRow>> runs;
  for (uint32_t run = 0; run < run_count; ++run) {
    // A point's row is final once the last run has measured it.
    size_t point = 0;
    const auto measured = [&](const BenchRow& row) {
      if (run + 1 == run_count && row_done) {
        std::vector<BenchRow> rows = point_rows(runs, point);
        rows.push_back(row);
        row_done(merge_point(rows));
      }
      ++point;
    };
    const auto checked = [&] {
      if (run == 0 && started) started();
    };
    Sweep sweep = measure_sweep(renderer.get(), max_range, a, run, checked, measured);
    runs.push_back(std::move(sweep.rows));
    results.measurements_planned = sweep.points * run_count;
    results.measurements_made += runs.back().size();
    if (!sweep.complete) {
      results.interrupted = stop_signal();
      break;
    }
  }
  for (size_t i = 0; i < runs.front().size(); ++i)
    results.rows.push_back(merge_point(point_rows(runs, i)));
  results.compute_over_hardware = compute_over_hardware(results.rows);
  return results;
}

}  // namespace tessera
