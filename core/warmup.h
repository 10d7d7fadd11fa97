#pragma once
// Warming a device up before timing it: untimed frames until the frame time settles (a GPU
// starts at idle clocks and takes a while to reach its working clocks; a fixed frame count
// does not cover that). Used by `tessera bench` and bench/minimal_graphics.cpp.

#include <cstdint>
#include <functional>

namespace tessera {

/// When the untimed frames before a point's timed ones stop (`tessera bench --warmup`,
/// `--warmup-ms`). With `ms` = 0: after `min_frames` frames. Otherwise after at least
/// `min_frames` frames and `ms` of wall time after the first frame (which may compile
/// pipelines), once the median frame time of the last `window` frames is within `tolerance`
/// (relative) of the median of the `window` frames before them, or when `cap_factor` * `ms`
/// of wall time have passed without that (then not stable).
struct WarmupRule {
  uint32_t min_frames = 2;
  double ms = 500.0;
  uint32_t window = 5;
  double tolerance = 0.02;
  double cap_factor = 4.0;
};

/// What a warm-up took: untimed frames, their wall time (ms), and whether the frame time had
/// settled (false: stopped at the cap, or the rule asked for no settling, `ms` = 0).
struct WarmupStats {
  uint32_t frames = 0;
  double ms = 0.0;
  bool stable = false;
};

/// Milliseconds of std::chrono::steady_clock (from an arbitrary origin).
double steady_clock_ms();

/// Renders untimed frames with `frame` (which renders one and returns its time in ms, the
/// figure whose settling is watched) as `rule` says, reading wall time from `clock_ms`
/// (milliseconds; tests pass a clock of their own).
WarmupStats warm_up(const std::function<double()>& frame, const WarmupRule& rule,
                    const std::function<double()>& clock_ms = steady_clock_ms);

}  // namespace tessera
