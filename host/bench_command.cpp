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
  BenchResults results;
  try {
    results = measure_bench(ctx.get(), a);
  } catch (const ImageSizeError& e) {
    throw_image_size_error(with_samples_source(e, a.quality, a.samples_given, a.samples),
                           a.size_given, "", "tessera bench --help");
  }

  if (!a.quiet) print_bench_table(results, a);
  if (!a.compare.empty())
    print_comparison(base, compare_runs(base, results, a), differing_settings(base, a),
                     results.device);
  if (!a.csv.empty()) write_bench_csv(a.csv, results, a);
  if (!a.json.empty()) write_bench_json(a.json, results, a, command_line);
  if (!a.chart.empty()) write_bench_chart(a.chart, results, a);
  if (!a.quiet) {
    for (const std::string* p : {&a.csv, &a.json, &a.chart}) {
      if (!p->empty()) std::printf("wrote %s\n", p->c_str());
    }
  }
  return validation_exit_status(ctx.get());
}

}  // namespace tessera
