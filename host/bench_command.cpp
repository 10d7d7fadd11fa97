#include "host/bench_command.h"

#include <algorithm>
#include <cstdio>
#include <memory>

#include "compute/context.h"
#include "compute/renderer.h"
#include "core/check.h"
#include "core/image.h"
#include "host/bench_compare.h"
#include "host/bench_measure.h"
#include "host/bench_report.h"
#include "host/report.h"
#include "host/stop_signal.h"

namespace tessera {

int run_bench(const BenchArgs& given, const std::string& command_line) {
  BenchArgs a = given;
  // Check outputs before spending time on a sweep.
  for (const std::string* path : {&a.csv, &a.json, &a.chart}) {
    if (std::string why = path->empty() ? "" : unwritable_reason(*path); !why.empty())
      throw Error("cannot write output file '" + *path + "': " + why);
  }
  // A bad base file is found before the sweep, too.
  const SavedRun base = a.compare.empty() ? SavedRun{} : read_bench_json(a.compare);
  catch_stop_signals();
  const bool gpu_backends =
      std::any_of(a.backends.begin(), a.backends.end(),
                  [](const std::string& b) { return b == "compute" || b == "hardware"; });
  std::unique_ptr<Context> ctx;
  if (gpu_backends) {
    ContextOptions options;
    options.device = a.device;
    options.validation = a.validate;
    ctx = create_context(options);
    // The device's rasterizer settings where the command line gave none; the report and the
    // JSON say which were used.
    const VkPhysicalDeviceType type = ctx->properties.deviceType;
    const RasterTuning tuned = raster_tuning(type);
    const bool preset_area = a.quality != Quality::none && preset_sets_small_triangle_area(type);
    if (!a.small_triangle_area_given && !preset_area)
      a.small_triangle_area = tuned.small_triangle_max_area;
    if (!a.depth_rejection_given) a.depth_rejection = tuned.depth_rejection;
    if (!a.shade_tiles_given) a.shade_tiles = tuned.shade_tiles;
    if (!a.raster_shade_given) a.raster_shade = tuned.raster_shade;
    if (!a.tile_lists_given) a.tile_lists = tuned.tile_lists;
  }
  // Each row is printed as its point is measured; Ctrl+C or SIGTERM stops the sweep at the next
  // point, and what it measured is printed and written as a whole sweep's would be.
  // The heading once the counts have passed their checks: a count refused is refused alone.
  const auto print_heading = [&] {
    if (!a.quiet)
      print_bench_heading(ctx ? ctx->properties.deviceName : BenchResults{}.device,
                          ctx ? ctx->driver : "", a);
  };
  size_t printed = 0;
  const auto print_row = [&](const BenchRow& row) {
    if (!a.quiet) print_bench_row(row, a);
    ++printed;
  };
  BenchResults results;
  try {
    results = measure_bench(ctx.get(), a, print_heading, print_row);
  } catch (const ImageSizeError& e) {
    throw_image_size_error(with_samples_source(e, a.quality, a.samples_given, a.samples),
                           a.size_given, "", "tessera bench --help");
  }
  if (!a.quiet) {
    // An interrupted run's points measured in fewer runs than asked.
    for (size_t i = printed; i < results.rows.size(); ++i) print_bench_row(results.rows[i], a);
    print_bench_ratios(results);
  }
  if (!a.compare.empty())
    print_comparison(base, compare_runs(base, results, a), differing_settings(base, a),
                     results.device);
  const bool any = !results.rows.empty();
  std::string written;
  if (any) {
    if (!a.csv.empty()) write_bench_csv(a.csv, results, a);
    if (!a.json.empty()) write_bench_json(a.json, results, a, command_line);
    if (!a.chart.empty()) write_bench_chart(a.chart, results, a);
    for (const std::string* p : {&a.csv, &a.json, &a.chart}) {
      if (p->empty()) continue;
      if (!a.quiet) std::printf("wrote %s\n", p->c_str());
      written += (written.empty() ? "" : ", ") + *p;
    }
  }
  if (results.interrupted) {
    const size_t fewer =
        size_t(std::count_if(results.rows.begin(), results.rows.end(), [&](const BenchRow& r) {
          return r.run_ms.size() < std::max(a.runs, 1u);
        }));
    std::string message =
        "tessera: interrupted by " + std::string(stop_signal_name(results.interrupted)) +
        " after " + std::to_string(results.measurements_made) + " of " +
        std::to_string(results.measurements_planned) +
        (a.runs > 1 ? " measurements (" + std::to_string(a.runs) + " runs of " +
                          std::to_string(results.measurements_planned / a.runs) + " points)"
                    : " points");
    if (!any) {
      message += "; none was complete, no file written";
    } else {
      message += "; " + std::string(written.empty() ? "printed" : "wrote") + " the " +
                 std::to_string(results.rows.size()) + " measured" +
                 (fewer > 0 ? " (" + std::to_string(fewer) + " in fewer runs)" : "") +
                 (written.empty() ? "" : " to " + written);
    }
    std::fprintf(stderr, "%s\n", message.c_str());
    const int status = validation_exit_status(ctx.get());
    return status != 0 ? status : interrupted_exit_status(results.interrupted);
  }
  return validation_exit_status(ctx.get());
}

}  // namespace tessera
