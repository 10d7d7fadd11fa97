#include <algorithm>
#include <cstdio>
#include <memory>

#include "compute/context.h"
#include "core/check.h"
#include "core/image.h"
#include "host/report.h"
#include "host/stop_signal.h"
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
  if (const std::string coarse = coarse_truth_warning(args.knobs, args.frame, args.truth_samples);
      !coarse.empty() && !args.quiet)
    std::fprintf(stderr, "tessera: warning: %s\n", coarse.c_str());
  if (scene.skipped.size() == args.knobs.size()) {
    std::string why;
    for (const SkippedKnob& s : scene.skipped) why += "\n  " + s.knob + ": " + s.reason;
    throw Error("nothing to measure: no knob asked for can matter for scene '" + args.scene +
                "':" + why);
  }
  // Ctrl+C or SIGTERM stops the rounds at the next setting; the settings timed so far are
  // finished against their ground truth, printed and written as a whole run's would be.
  catch_stop_signals();
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
  const bool any = !results.points.empty();
  if (!args.quiet && any) print_tradeoff_table(results, args);
  std::string written;
  if (any) {
    if (!args.json.empty()) write_tradeoff_json(args.json, results, args, command_line);
    if (!args.chart.empty()) write_tradeoff_chart(args.chart, results, args);
    for (const std::string* p : {&args.json, &args.chart}) {
      if (p->empty()) continue;
      if (!args.quiet) std::printf("wrote %s\n", p->c_str());
      written += (written.empty() ? "" : ", ") + *p;
    }
  }
  if (results.interrupted) {
    std::string message = "tessera: interrupted by " +
                          std::string(stop_signal_name(results.interrupted)) + " after " +
                          std::to_string(results.measurements_made) + " of " +
                          std::to_string(results.measurements_planned) + " measurements (" +
                          std::to_string(results.measurements_planned / args.rounds) +
                          " settings x " + std::to_string(args.rounds) + " rounds)";
    if (!any) {
      message += "; no setting was timed, no file written";
    } else {
      const size_t fewer = size_t(
          std::count_if(results.points.begin(), results.points.end(),
                        [&](const TradeoffPoint& p) { return p.warmups.size() < args.rounds; }));
      message += "; " + std::string(written.empty() ? "printed" : "wrote") + " the " +
                 std::to_string(results.points.size()) +
                 (results.points.size() == 1 ? " setting timed" : " settings timed") +
                 (fewer > 0 ? " (" + std::to_string(fewer) + " in fewer rounds)" : "") +
                 (written.empty() ? "" : " to " + written);
    }
    std::fprintf(stderr, "%s\n", message.c_str());
    const int status = validation_exit_status(ctx.get());
    return status != 0 ? status : interrupted_exit_status(results.interrupted);
  }
  return validation_exit_status(ctx.get());
}

}  // namespace tessera
