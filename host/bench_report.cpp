#include "host/bench_report.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "core/bench_scenes.h"
#include "core/check.h"
#include "host/bench_compare.h"
#include "host/chart.h"

namespace tessera {
namespace {

std::string human_count(double v) {
  char buf[32];
  if (v >= 1e9)
    std::snprintf(buf, sizeof(buf), "%.2fG", v / 1e9);
  else if (v >= 1e6)
    std::snprintf(buf, sizeof(buf), "%.2fM", v / 1e6);
  else if (v >= 1e3)
    std::snprintf(buf, sizeof(buf), "%.1fk", v / 1e3);
  else
    std::snprintf(buf, sizeof(buf), "%.0f", v);
  return buf;
}

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (uint8_t(c) < 0x20) continue;
    out += c;
  }
  return out + "\"";
}

// A CSV cell holding `s` whatever it holds: quoted, with its quotes doubled (RFC 4180).
std::string csv_text(const std::string& s) {
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

// The settings every point was measured with, by the JSON's names: bench_settings (what
// --compare checks; strings as JSON writes them, double-quoted, which CSV reads as the string),
// then the rest of the JSON's. The CSV repeats them on every row, after the measured columns,
// so that the older columns keep their places.
std::vector<std::pair<std::string, std::string>> csv_settings(const BenchResults& results,
                                                              const BenchArgs& a) {
  std::vector<std::pair<std::string, std::string>> out = bench_settings(a);
  char lod_error[32], warmup_ms[32];
  std::snprintf(lod_error, sizeof(lod_error), "%g", a.lod_error_px);
  std::snprintf(warmup_ms, sizeof(warmup_ms), "%g", a.warmup_ms);
  out.insert(out.end(), {{"lod_error_px", lod_error},
                         {"generic_shading", a.generic_shading ? "true" : "false"},
                         {"warmup_min_frames", std::to_string(a.warmup)},
                         {"warmup_min_ms", warmup_ms},
                         {"driver", csv_text(results.driver)},
                         {"raster_shade", a.raster_shade ? "true" : "false"}});
  return out;
}

}  // namespace

// "medians of 5 frames", or "one frame each" for a single frame (no median to speak of).
static std::string frames_phrase(uint32_t repeat) {
  return repeat == 1 ? "one frame each" : "medians of " + std::to_string(repeat) + " frames";
}

// The frames each series' figures are of: the CPU reference times at most kReferenceMaxFrames
// (measure_reference), so beside a GPU backend with more it is named with its own.
static std::string chart_frames_phrase(const BenchArgs& a) {
  const auto has = [&](const char* backend) {
    return std::find(a.backends.begin(), a.backends.end(), backend) != a.backends.end();
  };
  const uint32_t reference = std::min(a.repeat, kReferenceMaxFrames);
  if (!has("reference")) return frames_phrase(a.repeat);
  if (!has("compute") && !has("hardware")) return frames_phrase(reference);
  if (reference == a.repeat) return frames_phrase(a.repeat);
  return frames_phrase(a.repeat) + "; reference: " + frames_phrase(reference);
}

// How the figures were taken: frames, warm-up rule and runs, for the backends measured (the
// CPU reference times fewer frames, without a warm-up: measure_reference).
static std::string method_phrase(const BenchArgs& a) {
  const auto has = [&](const char* backend) {
    return std::find(a.backends.begin(), a.backends.end(), backend) != a.backends.end();
  };
  std::string s;
  if (has("compute") || has("hardware")) {
    s = frames_phrase(a.repeat) + " after a warm-up of at least " + std::to_string(a.warmup) +
        " frames";
    if (a.warmup_ms > 0) {
      char ms[32];
      std::snprintf(ms, sizeof(ms), "%g", a.warmup_ms);
      s += std::string(" and ") + ms + " ms, until the frame time settles";
    }
  }
  if (has("reference")) {
    s += std::string(s.empty() ? "" : "; ") +
         (has("compute") || has("hardware") ? "the reference " : "") +
         frames_phrase(std::min(a.repeat, kReferenceMaxFrames)) + " of CPU wall time, no warm-up";
  }
  if (a.runs > 1)
    s += "; " + std::to_string(a.runs) + " runs, the median of their medians and their spread";
  // Timestamps between the passes would add to the frame (Timing::frame).
  if (has("compute"))
    s += "; compute frames timed whole, their passes (CSV, JSON, chart) in as many frames more";
  return s;
}

// "12 f, 503 ms", marked when the frame time had not settled.
static std::string warmup_text(const BenchRow& r, const BenchArgs& a) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%u f, %.0f ms%s", r.warmup.frames, r.warmup.ms,
                a.warmup_ms > 0 && !r.warmup.stable ? " (unsettled)" : "");
  return buf;
}

namespace {

// ", <coverage> coverage[, walk of N steps]" for several samples per pixel, else "".
std::string coverage_phrase(const BenchArgs& a) {
  if (a.samples == 1) return "";
  std::string out = std::string(", ") + aa_coverage_name(a.aa_coverage) + " coverage";
  if (a.aa_coverage == AaCoverage::silhouette && a.silhouette_steps != 0)
    out += ", walk of " + std::to_string(a.silhouette_steps) + " steps";
  return out;
}

// ", N segments" for a benchmark family, whose spheres --segments sets; "" for a scene by name
// or file, whose meshes are its own.
std::string segments_phrase(const BenchArgs& a) {
  for (const BenchFamilyInfo& f : bench_families()) {
    if (f.name == a.scene) return ", " + std::to_string(a.segments) + " segments";
  }
  return "";
}

}  // namespace

// ", small-triangle area 128, shading by tiles off, ...": the compute path's rasterizer
// settings, for a run that measures it; "" for the CPU reference and the hardware baseline,
// which have none of them (the reference rasterizes every triangle alike in one pass over the
// image, the baseline draws through the graphics pipeline).
static std::string raster_phrase(const BenchArgs& a) {
  if (std::find(a.backends.begin(), a.backends.end(), "compute") == a.backends.end()) return "";
  return ", small-triangle area " + std::to_string(a.small_triangle_area) + ", shading by tiles " +
         (a.shade_tiles ? "on" : "off") + ", " + tile_lists_name(a.tile_lists) +
         " tile lists, raster and shade in one pass " +
         (!a.raster_shade ? "off"
          : a.shade_tiles ? "off (not with shading by tiles)"
                          : "for small frames");
}

void print_bench_heading(const std::string& device, const std::string& driver, const BenchArgs& a) {
  std::printf("scene %s, %ux%u, %u sample%s per pixel%s%s%s, device '%s'%s,\n%s\n", a.scene.c_str(),
              a.width, a.height, a.samples, a.samples == 1 ? "" : "s", coverage_phrase(a).c_str(),
              segments_phrase(a).c_str(), raster_phrase(a).c_str(), device.c_str(),
              driver.empty() ? "" : (" (" + driver + ")").c_str(), method_phrase(a).c_str());
  std::printf("%9s %9s %10s %10s %10s %10s %10s %8s %11s %8s  %s\n", "objects", "backend",
              "triangles", "rasterized", "median ms", "min ms", "max ms", "spread", "triangles/s",
              "cpu ms", "warm-up");
}

void print_bench_row(const BenchRow& r, const BenchArgs& a) {
  if (r.skipped) {
    std::printf("%9u %9s %10s  skipped (over --reference-max-triangles)\n", r.objects,
                r.backend.c_str(), human_count(double(r.triangles_submitted)).c_str());
    return;
  }
  char spread[16] = "-";
  if (r.run_ms.size() > 1) std::snprintf(spread, sizeof(spread), "%.1f %%", r.run_spread_percent());
  // The reference records no command buffer and has no warm-up.
  const bool reference = r.backend == "reference";
  char cpu[32] = "-";
  if (!reference) std::snprintf(cpu, sizeof(cpu), "%.3f", r.cpu_record_ms);
  // A point an interruption left with fewer runs than asked says how many it has.
  const std::string runs =
      r.run_ms.size() < a.runs && !r.run_ms.empty()
          ? "  (" + std::to_string(r.run_ms.size()) + " of " + std::to_string(a.runs) + " runs)"
          : "";
  std::printf("%9u %9s %10s %10s %10.3f %10.3f %10.3f %8s %11s %8s  %s%s\n", r.objects,
              r.backend.c_str(), human_count(double(r.triangles_submitted)).c_str(),
              // The hardware path counts no rasterized triangles; a measured 0 is a 0.
              r.backend == "hardware" ? "-" : human_count(double(r.triangles_rasterized)).c_str(),
              r.total_ms, r.min_ms, r.max_ms, spread, human_count(r.triangles_per_second()).c_str(),
              cpu, reference ? "-" : warmup_text(r, a).c_str(), runs.c_str());
}

void print_bench_ratios(const BenchResults& results) {
  for (const auto& [n, ratio] : results.compute_over_hardware) {
    std::printf("objects %u: compute / hardware = %.3f (compute %.2fx %s)\n", n, ratio,
                ratio < 1 ? 1 / ratio : ratio, ratio < 1 ? "faster" : "slower");
  }
}

void print_bench_table(const BenchResults& results, const BenchArgs& a) {
  print_bench_heading(results.device, results.driver, a);
  for (const BenchRow& r : results.rows) print_bench_row(r, a);
  print_bench_ratios(results);
}

void write_bench_csv(const std::string& path, const BenchResults& results, const BenchArgs& a) {
  std::ofstream f(path);
  f << "scene,objects,backend,width,height,triangles_submitted,triangles_rasterized,pixels_shaded,"
       "total_ms,cpu_record_ms,triangles_per_s,min_ms,max_ms,runs,run_spread_pct,warmup_frames,"
       "warmup_ms,warmup_stable,per_pass_total_ms";
  for (size_t p = 0; p < kPassCount; ++p) f << "," << pass_name(Pass(p)) << "_ms";
  f << ",batches,tile_entries,tile_list_stride,frames,device,note";
  const std::vector<std::pair<std::string, std::string>> settings = csv_settings(results, a);
  for (const auto& [name, value] : settings) f << "," << name;
  // Measured, but added after the settings: new columns go at the end (docs/performance.md).
  f << ",rasterized_and_shaded\n";
  for (const BenchRow& r : results.rows) {
    if (r.skipped) continue;
    // The hardware baseline counts no rasterized triangles, and only the compute path is timed
    // pass by pass and renders in batches: those cells are empty for the others, not a
    // measured 0.
    const bool compute = r.backend == "compute";
    // The scene may be a file's path, which may hold a comma: quoted, as the device and note are.
    f << csv_text(a.scene) << "," << r.objects << "," << r.backend << "," << a.width << ","
      << a.height << "," << r.triangles_submitted << ",";
    if (r.backend != "hardware") f << r.triangles_rasterized;
    // A spread needs two runs; the reference has no warm-up and records no command buffer.
    const bool timed_on_device = r.backend != "reference";
    f << "," << r.pixels_shaded << "," << r.total_ms << ",";
    if (timed_on_device) f << r.cpu_record_ms;
    f << "," << r.triangles_per_second() << "," << r.min_ms << "," << r.max_ms << ","
      << r.run_ms.size() << ",";
    if (r.run_ms.size() > 1) f << r.run_spread_percent();
    f << ",";
    if (timed_on_device)
      f << r.warmup.frames << "," << r.warmup.ms << "," << (r.warmup.stable ? "true" : "false");
    else
      f << ",,";
    f << ",";
    if (compute) f << r.per_pass_total_ms;
    for (double ms : r.pass_ms) {
      f << ",";
      if (compute) f << ms;
    }
    f << ",";
    if (compute) f << r.batches << "," << r.tile_entries << "," << r.tile_list_stride;
    if (!compute) f << ",,";
    f << "," << r.frames << "," << csv_text(results.device) << "," << csv_text(r.note);
    for (const auto& [name, value] : settings) f << "," << value;
    f << ",";
    if (compute) f << (r.rasterized_and_shaded ? "true" : "false");
    f << "\n";
  }
  if (!f) throw Error("cannot write CSV '" + path + "'");
}

void write_bench_json(const std::string& path, const BenchResults& results, const BenchArgs& a,
                      const std::string& command_line) {
  std::ofstream f(path);
  f.precision(9);  // sub-microsecond digits of milliseconds, for --compare and spreads
  const std::time_t now = std::time(nullptr);
  char date[32];
  std::strftime(date, sizeof(date), "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  f << "{\n  \"device\": " << json_string(results.device)
    << ",\n  \"driver\": " << json_string(results.driver)
    << ",\n  \"command\": " << json_string(command_line) << ",\n  \"date\": " << json_string(date)
    << ",\n  \"scene\": " << json_string(a.scene) << ",\n  \"width\": " << a.width
    << ",\n  \"height\": " << a.height << ",\n  \"samples\": " << a.samples
    << ",\n  \"aa_coverage\": " << json_string(aa_coverage_name(a.aa_coverage))
    << ",\n  \"aa_walk_steps\": " << a.silhouette_steps
    << ",\n  \"lod\": " << json_string(a.lod == Lod::automatic ? "auto" : "off")
    << ",\n  \"lod_error_px\": " << a.lod_error_px << ",\n  \"segments\": " << a.segments
    << ",\n  \"small_triangle_area\": " << a.small_triangle_area
    << ",\n  \"tile_size\": " << a.tile_size
    << ",\n  \"depth_rejection\": " << (a.depth_rejection ? "true" : "false")
    << ",\n  \"shade_tiles\": " << (a.shade_tiles ? "true" : "false")
    << ",\n  \"raster_shade\": " << (a.raster_shade ? "true" : "false")
    << ",\n  \"tile_lists\": " << json_string(tile_lists_name(a.tile_lists))
    << ",\n  \"hdr_format\": " << json_string(a.hdr_format == HdrFormat::fp32 ? "fp32" : "fp16")
    << ",\n  \"generic_shading\": " << (a.generic_shading ? "true" : "false")
    << ",\n  \"frames\": " << a.repeat << ",\n  \"runs\": " << a.runs
    << ",\n  \"warmup\": {\"min_frames\": " << a.warmup << ", \"min_ms\": " << a.warmup_ms
    << "},\n  \"statistic\": \"median\",\n  \"interrupted\": "
    << (results.interrupted ? "true" : "false")
    << ",\n  \"measurements_planned\": " << results.measurements_planned
    << ",\n  \"measurements_made\": " << results.measurements_made << ",\n  \"results\": [";
  bool first = true;
  for (const BenchRow& r : results.rows) {
    if (r.skipped) continue;
    // What only the compute path counts is null for the other backends, as the CSV leaves it
    // empty; the hardware baseline counts no rasterized triangles either.
    const bool compute = r.backend == "compute";
    const auto counted = [](bool known, uint64_t n) {
      return known ? std::to_string(n) : std::string("null");
    };
    f << (first ? "\n" : ",\n") << "    {\"objects\": " << r.objects
      << ", \"backend\": " << json_string(r.backend)
      << ", \"triangles_submitted\": " << r.triangles_submitted
      << ", \"triangles_rasterized\": " << counted(r.backend != "hardware", r.triangles_rasterized)
      << ", \"small_triangles\": " << counted(compute, r.small_triangles)
      << ", \"bin_entries\": " << counted(compute, r.bin_entries)
      << ", \"tile_entries\": " << counted(compute, r.tile_entries)
      << ", \"rejected_entries\": " << counted(compute, r.rejected_entries)
      << ", \"rejected_small\": " << counted(compute, r.rejected_small)
      << ", \"tile_list_stride\": " << counted(compute, r.tile_list_stride)
      << ", \"rasterized_and_shaded\": "
      << (!compute                  ? "null"
          : r.rasterized_and_shaded ? "true"
                                    : "false")
      << ", \"pixels_shaded\": " << r.pixels_shaded << ", \"total_ms\": " << r.total_ms;
    if (r.backend == "compute") f << ", \"per_pass_total_ms\": " << r.per_pass_total_ms;
    f << ", \"min_ms\": " << r.min_ms << ", \"max_ms\": " << r.max_ms << ", \"run_ms\": [";
    for (size_t i = 0; i < r.run_ms.size(); ++i) f << (i ? ", " : "") << r.run_ms[i];
    // A spread needs two runs; the reference has no warm-up and records no command buffer.
    const bool timed_on_device = r.backend != "reference";
    f << "], \"run_spread_pct\": ";
    if (r.run_ms.size() > 1)
      f << r.run_spread_percent();
    else
      f << "null";
    if (timed_on_device) {
      f << ", \"warmup_frames\": " << r.warmup.frames << ", \"warmup_ms\": " << r.warmup.ms
        << ", \"warmup_stable\": " << (r.warmup.stable ? "true" : "false")
        << ", \"cpu_record_ms\": " << r.cpu_record_ms;
    } else {
      f << ", \"warmup_frames\": null, \"warmup_ms\": null, \"warmup_stable\": null"
        << ", \"cpu_record_ms\": null";
    }
    f << ", \"triangles_per_s\": " << r.triangles_per_second()
      << ", \"batches\": " << counted(compute, r.batches) << ", \"frames\": " << r.frames
      << ", \"passes_ms\": ";
    if (compute) {
      f << "{";
      for (size_t p = 0; p < kPassCount; ++p)
        f << (p ? ", " : "") << json_string(pass_name(Pass(p))) << ": " << r.pass_ms[p];
      f << "}";
    } else {
      f << "null";
    }
    f << ", \"note\": " << json_string(r.note) << "}";
    first = false;
  }
  f << "\n  ],\n  \"compute_over_hardware\": [";
  const auto& ratios = results.compute_over_hardware;
  for (size_t i = 0; i < ratios.size(); ++i) {
    f << (i ? ", " : "") << "{\"objects\": " << ratios[i].first
      << ", \"ratio\": " << ratios[i].second << "}";
  }
  f << "]\n}\n";
  if (!f) throw Error("cannot write JSON '" + path + "'");
}

void write_bench_chart(const std::string& path, const BenchResults& results, const BenchArgs& a) {
  ChartSpec spec;
  spec.title = "tessera bench: " + a.scene + ", " + std::to_string(a.width) + "x" +
               std::to_string(a.height) +
               (a.samples > 1 ? ", " + std::to_string(a.samples) + " samples" : "") +
               coverage_phrase(a) + (a.lod == Lod::automatic ? ", --lod auto" : "") + ", " +
               results.device + " (" + chart_frames_phrase(a) +
               // An interrupted sweep's last points come from fewer runs (its table says how
               // many).
               (a.runs > 1 ? std::string(", median of ") + (results.interrupted ? "up to " : "") +
                                 std::to_string(a.runs) + " runs"
                           : "") +
               ")" +
               (results.interrupted
                    ? ", interrupted (" + std::to_string(results.measurements_made) + " of " +
                          std::to_string(results.measurements_planned) + " measured)"
                    : "");
  spec.x_label = "objects";
  spec.y_label = "frame time (ms)";
  for (const std::string& backend : a.backends) {
    Series s;
    s.name = backend == "reference" ? "reference (CPU wall)" : backend;
    for (const BenchRow& r : results.rows) {
      if (r.backend != backend) continue;
      s.x.push_back(r.objects);
      s.y.push_back(r.skipped ? 0.0 : r.total_ms);
    }
    spec.lines.push_back(s);
  }
  if (std::find(a.backends.begin(), a.backends.end(), "compute") != a.backends.end()) {
    spec.bars_title = "compute path, GPU time per pass";
    spec.bars_y_label = "ms";
    // Only the passes that ran at some point: the palette's ten colours then name each one
    // (with all seventeen, two passes shared a colour).
    std::vector<size_t> ran;
    for (size_t p = 0; p < kPassCount; ++p) {
      for (const BenchRow& r : results.rows) {
        if (r.backend == "compute" && r.pass_ms[p] > 0.0) {
          ran.push_back(p);
          break;
        }
      }
    }
    for (size_t p : ran) spec.bars.layers.push_back(pass_name(Pass(p)));
    for (const BenchRow& r : results.rows) {
      if (r.backend != "compute") continue;
      spec.bars.categories.push_back(human_count(r.objects));
      std::vector<double> values;
      for (size_t p : ran) values.push_back(r.pass_ms[p]);
      spec.bars.values.push_back(values);
    }
  }
  write_chart(path, spec);
}

}  // namespace tessera
