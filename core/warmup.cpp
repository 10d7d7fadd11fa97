#include "core/warmup.h"

#include <chrono>
#include <cmath>
#include <vector>

#include "core/statistics.h"

namespace tessera {

double steady_clock_ms() {
  return std::chrono::duration<double, std::milli>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

WarmupStats warm_up(const std::function<double()>& frame, const WarmupRule& rule,
                    const std::function<double()>& clock_ms) {
  const double start = clock_ms();
  // The rule's clock starts after the first frame, which may compile pipelines for seconds.
  double settle_start = start;
  WarmupStats stats;
  std::vector<double> times;
  const size_t w = std::max<uint32_t>(rule.window, 1);
  while (true) {
    const bool enough_frames = times.size() >= rule.min_frames;
    if (rule.ms <= 0.0 && enough_frames) break;
    const double elapsed = clock_ms() - settle_start;
    if (rule.ms > 0.0 && enough_frames && !times.empty() && elapsed >= rule.ms) {
      if (times.size() >= 2 * w) {
        const double last = median({times.end() - w, times.end()});
        const double before = median({times.end() - 2 * w, times.end() - w});
        if (std::abs(last - before) <= rule.tolerance * last) {
          stats.stable = true;
          break;
        }
      }
      if (elapsed >= rule.cap_factor * rule.ms) break;
    }
    times.push_back(frame());
    if (times.size() == 1) settle_start = clock_ms();
  }
  stats.frames = uint32_t(times.size());
  stats.ms = clock_ms() - start;
  return stats;
}

}  // namespace tessera
