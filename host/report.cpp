#include "host/report.h"

#include <cstdio>

#include "core/check.h"
#include "core/statistics.h"
#include "host/cli.h"

namespace tessera {

std::array<double, kPassCount> pass_medians(const std::vector<FrameStats>& frames) {
  std::array<double, kPassCount> out{};
  for (size_t p = 0; p < kPassCount; ++p) {
    std::vector<double> times;
    for (const FrameStats& f : frames) times.push_back(f.pass_ms[p]);
    out[p] = median(times);
  }
  return out;
}

void print_pass_times(const std::string& label, const std::vector<FrameStats>& frames) {
  TESSERA_CHECK(!frames.empty());
  std::printf("%s (ms):", label.c_str());
  const std::array<double, kPassCount> passes = pass_medians(frames);
  for (size_t p = 0; p < kPassCount; ++p) std::printf(" %s %.3f", pass_name(Pass(p)), passes[p]);
  std::vector<double> totals;
  for (const FrameStats& f : frames) totals.push_back(f.gpu_total_ms);
  const Summary total = summarize(totals);
  std::printf(" | total %.3f", total.median);
  if (total.count > 1) std::printf(" (min %.3f, max %.3f)", total.min, total.max);
  std::printf("\n");
}

ImageSizeError with_samples_source(const ImageSizeError& e, Quality quality, bool samples_given,
                                   uint32_t samples) {
  if (samples <= 1 || samples_given || quality == Quality::none) return e;
  return ImageSizeError(
      e.width, e.height,
      e.reason + " (" + option_source(quality, false, "--samples", std::to_string(samples)) + ")");
}

void throw_image_size_error(const ImageSizeError& e, bool size_given, const std::string& file_place,
                            const std::string& help_command) {
  const std::string size = std::to_string(e.width) + "x" + std::to_string(e.height);
  // The device's limit is known only once it is open, but the size is the command line's.
  if (size_given) throw UsageError("--size " + size + ": " + e.reason, help_command);
  if (!file_place.empty())
    throw Error(file_place + "the size " + size + " " + e.reason + " (--size overrides it)");
  throw e;
}

int validation_exit_status(const Context* ctx) {
  if (!ctx || !ctx->validation || (!ctx->validation->errors && !ctx->validation->warnings)) {
    return 0;
  }
  std::fprintf(stderr, "tessera: validation reported %u errors and %u warnings\n",
               ctx->validation->errors.load(), ctx->validation->warnings.load());
  return kExitValidationError;
}

}  // namespace tessera
