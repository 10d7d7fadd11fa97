#include "host/bench_compare.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <type_traits>

#include <nlohmann/json.hpp>

#include "core/check.h"

namespace tessera {
namespace {

using nlohmann::json;

std::string point_name(const SavedPoint& p) {
  return p.scene + ", " + std::to_string(p.objects) +
         (p.objects == 1 ? " object, " : " objects, ") + std::to_string(p.width) + "x" +
         std::to_string(p.height) + ", " + p.backend;
}

bool same_point(const SavedPoint& a, const SavedPoint& b) {
  return a.scene == b.scene && a.objects == b.objects && a.width == b.width &&
         a.height == b.height && a.backend == b.backend;
}

// The member `key` of `object` (at JSON path `where`) as T; Error naming both if absent or of
// another type.
template <typename T>
T member(const json& object, const char* key, const std::string& where, const std::string& path) {
  const auto it = object.find(key);
  const bool ok = it != object.end() && (std::is_same_v<T, std::string> ? it->is_string()
                                         : std::is_floating_point_v<T>  ? it->is_number()
                                                                        : it->is_number_unsigned());
  if (!ok) {
    const char* kind = std::is_same_v<T, std::string> ? "a string"
                       : std::is_floating_point_v<T>  ? "a number"
                                                      : "a whole number";
    throw Error("--compare: '" + path + "': " + where + key + " is missing or not " + kind +
                " (not a `tessera bench --json` file?)");
  }
  if constexpr (std::is_floating_point_v<T> || std::is_same_v<T, std::string>) {
    return it->template get<T>();
  } else {
    const uint64_t v = it->template get<uint64_t>();
    if (v > UINT32_MAX) throw Error("--compare: '" + path + "': " + where + key + " is too large");
    return T(v);
  }
}

}  // namespace

SavedRun read_bench_json(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw Error("--compare: '" + path + "' is a folder, not a `tessera bench --json` file");
  std::ifstream f(path);
  if (!f) throw Error("--compare: cannot read '" + path + "': " + std::strerror(errno));
  json doc;
  try {
    doc = json::parse(f);
  } catch (const json::parse_error& e) {
    // nlohmann's message starts with its own tag, "[json.exception.parse_error.101] ".
    std::string what = e.what();
    if (const size_t end = what.find("] "); end != std::string::npos) what = what.substr(end + 2);
    throw Error("--compare: '" + path + "' is not valid JSON: " + what);
  }
  if (!doc.is_object())
    throw Error("--compare: '" + path + "' is not a `tessera bench --json` file (not an object)");
  SavedRun run;
  run.path = path;
  if (doc.contains("device") && doc["device"].is_string()) run.device = doc["device"];
  if (doc.contains("date") && doc["date"].is_string()) run.date = doc["date"];
  if (const auto it = doc.find("interrupted"); it != doc.end() && it->is_boolean())
    run.interrupted = it->get<bool>();
  for (const auto& [key, count] : {std::pair{"measurements_planned", &run.measurements_planned},
                                   {"measurements_made", &run.measurements_made}}) {
    if (const auto it = doc.find(key); it != doc.end() && it->is_number_unsigned())
      *count = it->get<uint64_t>();
  }
  for (const auto& [key, value] : bench_settings(BenchArgs{})) {
    if (const auto it = doc.find(key); it != doc.end()) run.settings.emplace_back(key, it->dump());
  }
  const std::string scene = member<std::string>(doc, "scene", "", path);
  const uint32_t width = member<uint32_t>(doc, "width", "", path);
  const uint32_t height = member<uint32_t>(doc, "height", "", path);
  const auto results = doc.find("results");
  if (results == doc.end() || !results->is_array())
    throw Error("--compare: '" + path +
                "': results is missing or not an array (not a `tessera bench --json` file?)");
  for (size_t i = 0; i < results->size(); ++i) {
    const json& r = (*results)[i];
    const std::string where = "results[" + std::to_string(i) + "].";
    if (!r.is_object()) throw Error("--compare: '" + path + "': " + where + " is not an object");
    SavedPoint p{scene,
                 member<uint32_t>(r, "objects", where, path),
                 width,
                 height,
                 member<std::string>(r, "backend", where, path),
                 member<double>(r, "total_ms", where, path)};
    for (const SavedPoint& q : run.points) {
      if (same_point(p, q))
        throw Error("--compare: '" + path + "': results[" + std::to_string(i) +
                    "] repeats the point " + point_name(p));
    }
    // A time is positive: 0 or less is no measurement (and old_ms < 0 marks a point the base
    // lacks, ComparedPoint).
    if (!(p.total_ms > 0.0) || !std::isfinite(p.total_ms)) {
      throw Error("--compare: '" + path + "': " + where + "total_ms is " + r["total_ms"].dump() +
                  ", not a time (> 0 ms)");
    }
    run.points.push_back(p);
    if (p.backend == "compute" && !r.contains("per_pass_total_ms"))
      run.compute_timed_by_pass = true;
  }
  return run;
}

std::vector<ComparedPoint> compare_runs(const SavedRun& base, const BenchResults& results,
                                        const BenchArgs& a) {
  std::vector<ComparedPoint> out;
  std::vector<bool> used(base.points.size(), false);
  for (const BenchRow& r : results.rows) {
    if (r.skipped) continue;
    ComparedPoint c;
    c.point = {a.scene, r.objects, a.width, a.height, r.backend, 0.0};
    c.new_ms = r.total_ms;
    for (size_t i = 0; i < base.points.size(); ++i) {
      if (!used[i] && same_point(base.points[i], c.point)) {
        c.old_ms = base.points[i].total_ms;
        used[i] = true;
      }
    }
    out.push_back(c);
  }
  for (size_t i = 0; i < base.points.size(); ++i) {
    if (used[i]) continue;
    ComparedPoint c;
    c.point = base.points[i];
    c.old_ms = base.points[i].total_ms;
    out.push_back(c);
  }
  return out;
}

std::vector<std::pair<std::string, std::string>> bench_settings(const BenchArgs& a) {
  return {{"samples", json(a.samples).dump()},
          {"aa_coverage", json(aa_coverage_name(a.aa_coverage)).dump()},
          {"aa_walk_steps", json(a.silhouette_steps).dump()},
          {"lod", json(a.lod == Lod::automatic ? "auto" : "off").dump()},
          {"segments", json(a.segments).dump()},
          {"small_triangle_area", json(a.small_triangle_area).dump()},
          {"tile_size", json(a.tile_size).dump()},
          {"depth_rejection", json(a.depth_rejection).dump()},
          {"shade_tiles", json(a.shade_tiles).dump()},
          {"tile_lists", json(tile_lists_name(a.tile_lists)).dump()},
          {"hdr_format", json(a.hdr_format == HdrFormat::fp32 ? "fp32" : "fp16").dump()}};
}

std::vector<std::string> differing_settings(const SavedRun& base, const BenchArgs& args) {
  std::vector<std::string> out;
  for (const auto& [key, value] : bench_settings(args)) {
    for (const auto& [base_key, base_value] : base.settings) {
      if (base_key == key && base_value != value)
        out.push_back(key + " " + value + " (base: " + base_value + ")");
    }
  }
  return out;
}

void print_comparison(const SavedRun& base, const std::vector<ComparedPoint>& points,
                      const std::vector<std::string>& differing, const std::string& device) {
  std::printf("compared with %s (device '%s', %s): new / old < 1 is faster\n", base.path.c_str(),
              base.device.c_str(), base.date.c_str());
  if (!base.device.empty() && base.device != device) {
    std::printf(
        "tessera: warning: the base was measured on device '%s', this run on '%s': the ratios "
        "compare devices\n",
        base.device.c_str(), device.c_str());
  }
  if (base.interrupted) {
    // Its missing points show below as "only in this run", which alone reads as a sweep that
    // was never asked for them.
    const std::string counts = base.measurements_planned > 0
                                   ? " after " + std::to_string(base.measurements_made) + " of " +
                                         std::to_string(base.measurements_planned) + " measurements"
                                   : "";
    std::printf(
        "tessera: warning: the base's sweep was interrupted%s: it lacks the points it did not "
        "reach, and its last points may be medians of fewer runs than it asked\n",
        counts.c_str());
  }
  const bool any_matched =
      std::any_of(points.begin(), points.end(), [](const ComparedPoint& c) { return c.matched(); });
  if (!base.points.empty() && !any_matched) {
    const SavedPoint& b = base.points.front();
    std::printf(
        "tessera: warning: no point of this run is in the base, which measured %s at %ux%u\n",
        b.scene.c_str(), b.width, b.height);
  }
  if (!differing.empty()) {
    std::string list;
    for (const std::string& d : differing) list += (list.empty() ? "" : ", ") + d;
    std::printf(
        "tessera: warning: this run's settings differ from the base's: %s; the ratios compare "
        "unlike frames\n",
        list.c_str());
  }
  if (base.compute_timed_by_pass) {
    std::printf(
        "tessera: note: the base timed its compute frames pass by pass (it has no "
        "per_pass_total_ms), "
        "with timestamps between the passes that add to a frame; this run times them whole\n");
  }
  // The table of ratios only where there is a ratio: no empty header.
  if (any_matched) {
    std::printf("%9s %9s %10s %10s %10s\n", "objects", "backend", "old ms", "new ms", "new / old");
  }
  for (const ComparedPoint& c : points) {
    if (c.matched()) {
      std::printf("%9u %9s %10.3f %10.3f %10.3f\n", c.point.objects, c.point.backend.c_str(),
                  c.old_ms, c.new_ms, c.ratio());
    }
  }
  for (const ComparedPoint& c : points) {
    if (c.matched()) continue;
    std::printf("%s: %s\n", c.new_ms >= 0 ? "only in this run" : "only in the base",
                point_name(c.point).c_str());
  }
}

}  // namespace tessera
