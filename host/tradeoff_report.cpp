// Reporting `tessera tradeoff`: the table, the JSON file and the chart.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>

#include <nlohmann/json.hpp>

#include "core/check.h"
#include "host/chart.h"
#include "host/tradeoff.h"

namespace tessera {
namespace {

// JSON has no infinity or NaN: identical images have infinite PSNR, frames without a
// silhouette error NaN; both are written as null.
nlohmann::json finite_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

}  // namespace

// printf into a std::string.
template <typename... T>
std::string format(const char* f, T... values) {
  const int n = std::snprintf(nullptr, 0, f, values...);
  std::string out(size_t(std::max(n, 0)), '\0');
  std::snprintf(out.data(), out.size() + 1, f, values...);
  return out;
}

// "12.3 s", "45 ms", "under 1 ms" of CPU wall time: a small truth takes a fraction of a second,
// which one decimal of seconds would show as 0.0.
std::string wall_time(double seconds) {
  if (seconds >= 0.95) return format("%.1f s of CPU wall time", seconds);
  if (seconds >= 0.001) return format("%.0f ms of CPU wall time", seconds * 1000.0);
  return "under 1 ms of CPU wall time";
}

// Settings of one knob whose GPU times this run did not tell apart: next to each other in
// time (by median), with ranges (min..max over every timed frame of every round) that overlap.
// Their order in time, and so the Pareto front between them, may be this run's noise (a short
// run, a loaded machine). "" if none.
std::string overlapping_times_note(const TradeoffResults& results) {
  std::string pairs;
  size_t count = 0;
  for (const auto& [first, end] : knob_runs(results.points)) {
    std::vector<const TradeoffPoint*> by_time;
    for (size_t i = first; i < end; ++i) {
      if (results.points[i].gpu_ms.count > 0) by_time.push_back(&results.points[i]);
    }
    std::stable_sort(by_time.begin(), by_time.end(), [](const auto* a, const auto* b) {
      return a->gpu_ms.median < b->gpu_ms.median;
    });
    for (size_t i = 1; i < by_time.size(); ++i) {
      const TradeoffPoint& faster = *by_time[i - 1];
      const TradeoffPoint& slower = *by_time[i];
      if (faster.gpu_ms.max < slower.gpu_ms.min) continue;
      pairs += format("  %s: %s (%.3f..%.3f) and %s (%.3f..%.3f)\n", faster.setting.knob.c_str(),
                      faster.setting.label.c_str(), faster.gpu_ms.min, faster.gpu_ms.max,
                      slower.setting.label.c_str(), slower.gpu_ms.min, slower.gpu_ms.max);
      ++count;
    }
  }
  if (count == 0) return "";
  return format(
             "note: %zu pair%s of settings next to each other in time whose GPU times "
             "overlap (min..max):\n",
             count, count == 1 ? "" : "s") +
         pairs +
         "  their order in time, and the front between them, may be noise: more --rounds and "
         "--repeat,\n"
         "  on an idle machine, show whether it holds (settings that cost the same stay mixed)\n";
}

std::string tradeoff_table(const TradeoffResults& results, const TradeoffArgs& args) {
  std::string out;
  out += format("scene '%s', %ux%u, device '%s' (%s)\n", args.scene.c_str(), results.width,
                results.height, results.device.c_str(), results.driver.c_str());
  out += "truth: " + results.truth + " (" + wall_time(results.truth_seconds) + ")\n";
  if (!results.skipped.empty()) {
    out += "not measured, as they cannot matter for this scene:\n";
    for (const SkippedKnob& s : results.skipped) out += "  " + s.knob + ": " + s.reason + "\n";
  }
  // An interruption leaves some settings with fewer rounds; their rows say how many.
  const bool fewer =
      std::any_of(results.points.begin(), results.points.end(),
                  [&](const TradeoffPoint& p) { return p.warmups.size() < args.rounds; });
  out += format(
      "GPU ms: median of %u round%s%s x %u frame%s (min..max); errors against the truth: mean\n"
      "and 99th percentile relative error of linear radiance over all pixels and over the\n"
      "interior (pixels the truth shows one object in), PSNR of the 8-bit image, silhouette "
      "error\n",
      args.rounds, args.rounds == 1 ? "" : "s", fewer ? " (fewer where a row says so)" : "",
      args.repeat, args.repeat == 1 ? "" : "s");
  // Every cell as text first, so that each column is as wide as its widest cell: a setting's
  // label ("4 samples, silhouette") or a time of several digits shifts no column after it.
  const std::vector<std::string> header = {"knob",       "setting",  "GPU ms",
                                           "(min..max)", "mean rel", "interior",
                                           "p99 rel",    "PSNR dB",  "silh px"};
  const std::vector<bool> left = {true, true, false, false, false, false, false, false, false};
  std::vector<std::vector<std::string>> rows;
  size_t min_width = 0, max_width = 0;
  for (const TradeoffPoint& p : results.points) {
    min_width = std::max(min_width, format("%.3f", p.gpu_ms.min).size());
    max_width = std::max(max_width, format("%.3f", p.gpu_ms.max).size());
  }
  for (const TradeoffPoint& p : results.points) {
    // The ".." of every row in one column.
    const std::string range =
        format("%*.3f..%-*.3f", int(min_width), p.gpu_ms.min, int(max_width), p.gpu_ms.max);
    rows.push_back({p.setting.knob, p.setting.label, format("%.3f", p.gpu_ms.median), range,
                    format("%.4f", p.error.mean_relative), format("%.4f", p.interior_mean_relative),
                    format("%.4f", p.error.p99_relative), format("%.2f", p.error.psnr_db),
                    format("%.3f", p.error.silhouette_px)});
  }
  std::vector<size_t> width(header.size());
  for (size_t c = 0; c < header.size(); ++c) {
    width[c] = header[c].size();
    for (const auto& row : rows) width[c] = std::max(width[c], row[c].size());
  }
  auto line = [&](const std::vector<std::string>& cells) {
    std::string l;
    for (size_t c = 0; c < cells.size(); ++c) {
      const size_t pad = width[c] - cells[c].size();
      if (c > 0) l += "  ";  // two spaces: headers such as "p99 rel" have one
      if (!left[c]) l.append(pad, ' ');
      l += cells[c];
      if (left[c]) l.append(pad, ' ');
    }
    return l;
  };
  out += line(header);
  while (!out.empty() && out.back() == ' ') out.pop_back();
  out += "\n";
  for (size_t i = 0; i < rows.size(); ++i) {
    const TradeoffPoint& p = results.points[i];
    std::string marks;
    if (p.setting.is_default) marks += "default ";
    if (p.on_front) marks += "front ";
    if (p.precompute_ms > 0) marks += format("precompute %.3f ms ", p.precompute_ms);
    // A setting an interruption left with fewer rounds than asked.
    if (p.warmups.size() < args.rounds)
      marks += format("(%zu of %u rounds) ", p.warmups.size(), args.rounds);
    // The default is what the others are compared with: that it equals itself says nothing.
    if (p.setting.speed_only && !p.setting.is_default)
      marks +=
          p.identical_to_default ? "(image identical to default)" : "(IMAGE DIFFERS FROM DEFAULT)";
    while (!marks.empty() && marks.back() == ' ') marks.pop_back();
    out += line(rows[i]) + (marks.empty() ? "" : "  " + marks) + "\n";
  }
  out += overlapping_times_note(results);
  // The warm-ups, over every setting and round.
  uint32_t frames_min = ~0u, frames_max = 0, unsettled = 0, count = 0;
  double ms_min = INFINITY, ms_max = 0.0;
  for (const TradeoffPoint& p : results.points) {
    for (const WarmupStats& w : p.warmups) {
      frames_min = std::min(frames_min, w.frames);
      frames_max = std::max(frames_max, w.frames);
      ms_min = std::min(ms_min, w.ms);
      ms_max = std::max(ms_max, w.ms);
      unsettled += args.warmup_ms > 0 && !w.stable;
      ++count;
    }
  }
  if (count > 0 && args.warmup_ms > 0) {
    out += format(
        "warm-up per setting and round (at least %u frames and %g ms, then until the median of\n"
        "5 frames is within 2 %% of the 5 before): %u..%u frames, %.0f..%.0f ms; %u of %u "
        "unsettled\n",
        args.warmup, args.warmup_ms, frames_min, frames_max, ms_min, ms_max, unsettled, count);
  } else if (count > 0) {
    // --warmup-ms 0: the --warmup frames alone, with no settling rule.
    out += format("warm-up per setting and round: %u frames, %.0f..%.0f ms\n", args.warmup, ms_min,
                  ms_max);
  }
  return out;
}

void print_tradeoff_table(const TradeoffResults& results, const TradeoffArgs& args) {
  std::fputs(tradeoff_table(results, args).c_str(), stdout);
}

void write_tradeoff_json(const std::string& path, const TradeoffResults& results,
                         const TradeoffArgs& args, const std::string& command_line) {
  char date[32];
  const std::time_t now = std::time(nullptr);
  std::strftime(date, sizeof(date), "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  nlohmann::json j;
  j["device"] = results.device;
  j["driver"] = results.driver;
  j["command"] = command_line;
  j["date"] = date;
  j["scene"] = args.scene;
  j["width"] = results.width;
  j["height"] = results.height;
  j["rounds"] = args.rounds;
  j["interrupted"] = results.interrupted != 0;
  j["measurements_planned"] = results.measurements_planned;
  j["measurements_made"] = results.measurements_made;
  j["frames_per_round"] = args.repeat;
  j["warmup"] = {{"min_frames", args.warmup}, {"min_ms", args.warmup_ms}};
  j["hdr_format"] = args.frame.hdr_format == HdrFormat::fp32 ? "fp32" : "fp16";
  j["tile_size"] = args.tile_size;
  j["truth"] = {{"description", results.truth}, {"cpu_seconds", results.truth_seconds}};
  nlohmann::json skipped = nlohmann::json::array();
  for (const SkippedKnob& s : results.skipped)
    skipped.push_back({{"knob", s.knob}, {"reason", s.reason}});
  j["skipped_knobs"] = skipped;
  nlohmann::json points = nlohmann::json::array();
  for (const TradeoffPoint& p : results.points) {
    nlohmann::json warmups = nlohmann::json::array();
    for (const WarmupStats& w : p.warmups)
      warmups.push_back({{"frames", w.frames}, {"ms", w.ms}, {"stable", w.stable}});
    points.push_back({{"knob", p.setting.knob},
                      {"setting", p.setting.label},
                      {"default", p.setting.is_default},
                      {"gpu_ms",
                       {{"median", p.gpu_ms.median},
                        {"min", p.gpu_ms.min},
                        {"max", p.gpu_ms.max},
                        {"frames", p.gpu_ms.count}}},
                      {"triangles_rasterized", p.triangles_rasterized},
                      {"environment_precompute_ms", p.precompute_ms},
                      {"mean_relative_error", finite_or_null(p.error.mean_relative)},
                      {"interior_mean_relative_error", finite_or_null(p.interior_mean_relative)},
                      {"p99_relative_error", finite_or_null(p.error.p99_relative)},
                      {"psnr_db", finite_or_null(p.error.psnr_db)},
                      {"silhouette_px", finite_or_null(p.error.silhouette_px)},
                      {"truth_brdf", p.truth_brdf.empty() ? nlohmann::json(nullptr)
                                                          : nlohmann::json(p.truth_brdf)},
                      {"speed_only", p.setting.speed_only},
                      {"identical_to_default", p.identical_to_default},
                      {"pareto_front", p.on_front},
                      {"rounds", p.warmups.size()},
                      {"warmups", warmups}});
  }
  j["points"] = points;
  std::ofstream f(path);
  f << j.dump(2) << "\n";
  if (!f) throw Error("cannot write '" + path + "'");
}

void write_tradeoff_chart(const std::string& path, const TradeoffResults& results,
                          const TradeoffArgs& args) {
  ScatterChart chart;
  chart.title = "speed against accuracy: '" + args.scene + "', " + std::to_string(results.width) +
                "x" + std::to_string(results.height) + ", " + results.device +
                (results.interrupted
                     ? ", interrupted (" + std::to_string(results.measurements_made) + " of " +
                           std::to_string(results.measurements_planned) + " measured)"
                     : "");
  // The knobs left out, under the legend, as the table says why.
  if (!results.skipped.empty()) {
    chart.notes = {"", "not measured (cannot matter", "for this scene):"};
    for (const SkippedKnob& s : results.skipped) chart.notes.push_back("  " + s.knob);
  }
  // The brdf knob's truth shades with filament+ec, the others' with the settings' BRDF
  // (truth_shading): said under the legend, so that no one reads the errors as against one truth.
  std::string brdf_truth, others_truth;
  for (const TradeoffPoint& p : results.points)
    (p.setting.knob == "brdf" ? brdf_truth : others_truth) = p.truth_brdf;
  if (!brdf_truth.empty() || !others_truth.empty()) {
    chart.notes.insert(chart.notes.end(), {"", "truth's BRDF:"});
    if (!brdf_truth.empty()) chart.notes.push_back("  brdf knob: " + brdf_truth);
    if (!others_truth.empty())
      chart.notes.push_back((brdf_truth.empty() ? "  " : "  other knobs: ") + others_truth);
  }
  chart.x_label = "GPU time per frame, ms (median)";
  chart.y_label = "mean relative error against the knob's truth";
  for (const TradeoffPoint& p : results.points) {
    if (chart.series.empty() || chart.series.back().name != p.setting.knob)
      chart.series.push_back({p.setting.knob, {}});
    chart.series.back().points.push_back(
        {p.gpu_ms.median, p.error.mean_relative, p.setting.label, p.on_front});
  }
  write_scatter_chart(path, chart);
}

}  // namespace tessera
