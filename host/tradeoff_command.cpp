#include <cstdio>
#include <memory>

#include "compute/context.h"
#include "core/check.h"
#include "core/image.h"
#include "host/report.h"
#include "host/tradeoff.h"

namespace tessera {

int run_tradeoff(const TradeoffArgs& args, const std::string& command_line) {
  // Check outputs and knobs before spending minutes on the measurements.
  for (const std::string* path : {&args.json, &args.chart}) {
    if (std::string why = path->empty() ? "" : unwritable_reason(*path); !why.empty())
      throw Error("cannot write output file '" + *path + "': " + why);
  }
  for (const std::string& knob : args.knobs) knob_settings(knob, args.frame, {});
  // The scene before the device, as `tessera render`: its faults are found without one.
  const TradeoffScene scene = load_tradeoff_scene(args);
  if (scene.skipped.size() == args.knobs.size()) {
    std::string why;
    for (const SkippedKnob& s : scene.skipped) why += "\n  " + s.knob + ": " + s.reason;
    throw Error("nothing to measure: no knob asked for can matter for scene '" + args.scene +
                "':" + why);
  }
  ContextOptions options;
  options.device = args.device;
  options.validation = args.validate;
  std::unique_ptr<Context> ctx = create_context(options);
  TradeoffResults results;
  try {
    results = measure_tradeoff(*ctx, args, scene);
  } catch (const ImageSizeError& e) {
    // A command-line size is a bad command line; a scene file's is reported at its place.
    throw_image_size_error(e, args.size_given, scene.size_place, "tessera tradeoff --help");
  }
  if (!args.quiet) print_tradeoff_table(results, args);
  if (!args.json.empty()) write_tradeoff_json(args.json, results, args, command_line);
  if (!args.chart.empty()) write_tradeoff_chart(args.chart, results, args);
  if (!args.quiet) {
    for (const std::string* p : {&args.json, &args.chart})
      if (!p->empty()) std::printf("wrote %s\n", p->c_str());
  }
  return validation_exit_status(ctx.get());
}

}  // namespace tessera
