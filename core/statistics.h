#pragma once
// Summaries of repeated measurements (frame times), shared by the tool, the benchmarks and the
// tests. Medians rather than means: a rare slow frame (a clock change, other work on the
// device) should not move the figure.

#include <algorithm>
#include <cstddef>
#include <vector>

namespace tessera {

struct Summary {
  double median = 0.0;
  double min = 0.0;
  double max = 0.0;
  size_t count = 0;  // 0: no values; then every figure is 0
};

/// The median of `values` (the mean of the middle two for an even count); 0 if empty.
inline double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const size_t n = values.size();
  std::nth_element(values.begin(), values.begin() + n / 2, values.end());
  const double upper = values[n / 2];
  if (n % 2) return upper;
  const double lower = *std::max_element(values.begin(), values.begin() + n / 2);
  return 0.5 * (lower + upper);
}

inline Summary summarize(const std::vector<double>& values) {
  if (values.empty()) return {};
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  return {median(values), *lo, *hi, values.size()};
}

}  // namespace tessera
