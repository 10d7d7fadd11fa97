#pragma once
// What `tessera render` and `tessera bench` report in the same way: GPU time per pass over
// repeated frames, a size the device cannot render, and the exit status after the validation
// layer's reports.

#include <array>
#include <string>
#include <vector>

#include "compute/context.h"
#include "compute/renderer.h"
#include "host/quality.h"

namespace tessera {

/// The median GPU time of each pass over `frames`, in ms (0 for none).
std::array<double, kPassCount> pass_medians(const std::vector<FrameStats>& frames);

/// Prints one line: `label`, then the median time of each pass over `frames` and of their
/// totals, in ms, and with more than one frame the fastest and slowest totals.
/// `frames` must not be empty and must have timestamps.
void print_pass_times(const std::string& label, const std::vector<FrameStats>& frames);

/// `e` with " (--quality reference sets --samples 16)" after its reason where the preset set the
/// frame's `samples` (above 1, where the reason names them) and the command line did not: the
/// size may fit at the samples the user meant.
ImageSizeError with_samples_source(const ImageSizeError& e, Quality quality, bool samples_given,
                                   uint32_t samples);

/// Reports `e`, a size the device cannot render: as a bad command line (UsageError "--size WxH:
/// why", whose usage `help_command` shows) when the command line gave the size
/// (`size_given`); else at the scene file's "render" block that gave it (`file_place`,
/// RenderDefaults::size_place), saying that --size overrides it; else as it is.
[[noreturn]] void throw_image_size_error(const ImageSizeError& e, bool size_given,
                                         const std::string& file_place,
                                         const std::string& help_command);

/// 0 if `ctx` is null, ran without validation or the layer reported nothing; otherwise prints
/// the counts to stderr and returns kExitValidationError.
int validation_exit_status(const Context* ctx);

}  // namespace tessera
