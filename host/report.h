#pragma once
// What `tessera render` and `tessera bench` report in the same way: GPU time per pass over
// repeated frames, and the exit status after the validation layer's reports.

#include <array>
#include <string>
#include <vector>

#include "compute/context.h"
#include "compute/renderer.h"

namespace tessera {

/// The median GPU time of each pass over `frames`, in ms (0 for none).
std::array<double, kPassCount> pass_medians(const std::vector<FrameStats>& frames);

/// Prints one line: `label`, then the median time of each pass over `frames` and of their
/// totals, in ms, and with more than one frame the fastest and slowest totals.
/// `frames` must not be empty and must have timestamps.
void print_pass_times(const std::string& label, const std::vector<FrameStats>& frames);

/// 0 if `ctx` is null, ran without validation or the layer reported nothing; otherwise prints
/// the counts to stderr and returns kExitValidationError.
int validation_exit_status(const Context* ctx);

}  // namespace tessera
