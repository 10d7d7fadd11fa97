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

void print_tradeoff_table(const TradeoffResults& results, const TradeoffArgs& args) {
  std::printf("scene '%s', %ux%u, device '%s' (%s)\n", args.scene.c_str(), args.frame.width,
              args.frame.height, results.device.c_str(), results.driver.c_str());
  std::printf("truth: %s (%.1f s of CPU wall time)\n", results.truth.c_str(),
              results.truth_seconds);
  std::printf(
      "GPU ms: median of %u round%s x %u frame%s (min..max); errors against the truth: mean and\n"
      "99th percentile relative error of linear radiance over all pixels and over the interior\n"
      "(pixels the truth shows one object in), PSNR of the 8-bit image, silhouette error\n",
      args.rounds, args.rounds == 1 ? "" : "s", args.repeat, args.repeat == 1 ? "" : "s");
  std::printf("%-15s %-13s %9s %17s %9s %9s %9s %8s %8s  %s\n", "knob", "setting", "GPU ms",
              "(min..max)", "mean rel", "interior", "p99 rel", "PSNR dB", "silh px", "");
  for (const TradeoffPoint& p : results.points) {
    std::string marks;
    if (p.setting.is_default) marks += "default ";
    if (p.on_front) marks += "front ";
    if (p.precompute_ms > 0) {
      char buf[64];
      std::snprintf(buf, sizeof(buf), "precompute %.3f ms ", p.precompute_ms);
      marks += buf;
    }
    if (p.setting.speed_only)
      marks +=
          p.identical_to_default ? "(image identical to default)" : "(IMAGE DIFFERS FROM DEFAULT)";
    std::printf("%-15s %-13s %9.3f %8.3f..%-8.3f %9.4f %9.4f %9.4f %8.2f %8.3f  %s\n",
                p.setting.knob.c_str(), p.setting.label.c_str(), p.gpu_ms.median, p.gpu_ms.min,
                p.gpu_ms.max, p.error.mean_relative, p.interior_mean_relative, p.error.p99_relative,
                p.error.psnr_db, p.error.silhouette_px, marks.c_str());
  }
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
    std::printf(
        "warm-up per setting and round (at least %u frames and %g ms, then until the median of\n"
        "5 frames is within 2 %% of the 5 before): %u..%u frames, %.0f..%.0f ms; %u of %u "
        "unsettled\n",
        args.warmup, args.warmup_ms, frames_min, frames_max, ms_min, ms_max, unsettled, count);
  } else if (count > 0) {
    // --warmup-ms 0: the --warmup frames alone, with no settling rule.
    std::printf("warm-up per setting and round: %u frames, %.0f..%.0f ms\n", args.warmup, ms_min,
                ms_max);
  }
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
  j["width"] = args.frame.width;
  j["height"] = args.frame.height;
  j["rounds"] = args.rounds;
  j["frames_per_round"] = args.repeat;
  j["warmup"] = {{"min_frames", args.warmup}, {"min_ms", args.warmup_ms}};
  j["hdr_format"] = args.frame.hdr_format == HdrFormat::fp32 ? "fp32" : "fp16";
  j["tile_size"] = args.tile_size;
  j["truth"] = {{"description", results.truth}, {"cpu_seconds", results.truth_seconds}};
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
                      {"speed_only", p.setting.speed_only},
                      {"identical_to_default", p.identical_to_default},
                      {"pareto_front", p.on_front},
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
  chart.title = "speed against accuracy: '" + args.scene + "', " +
                std::to_string(args.frame.width) + "x" + std::to_string(args.frame.height) + ", " +
                results.device;
  chart.x_label = "GPU time per frame, ms (median)";
  chart.y_label = "mean relative error against the truth";
  for (const TradeoffPoint& p : results.points) {
    if (chart.series.empty() || chart.series.back().name != p.setting.knob)
      chart.series.push_back({p.setting.knob, {}});
    chart.series.back().points.push_back(
        {p.gpu_ms.median, p.error.mean_relative, p.setting.label, p.on_front});
  }
  write_scatter_chart(path, chart);
}

}  // namespace tessera
