#pragma once
// The Pareto front of settings measured by a cost (time) and an error: the settings no other
// setting beats on both. Used by `tessera tradeoff` to mark the settings worth choosing.

#include <cstddef>
#include <vector>

namespace tessera {

struct CostError {
  double cost = 0.0;   // e.g. GPU milliseconds; lower is better
  double error = 0.0;  // e.g. mean relative error; lower is better
};

/// For each point, whether it is on the Pareto front: no other point has cost <= and error <=
/// with at least one of them strictly lower. Equal points are all on the front. NaN costs or
/// errors are never on the front and never dominate. O(n^2): n is a few dozen settings.
inline std::vector<bool> pareto_front(const std::vector<CostError>& points) {
  std::vector<bool> front(points.size(), false);
  for (size_t i = 0; i < points.size(); ++i) {
    const CostError& p = points[i];
    if (!(p.cost == p.cost) || !(p.error == p.error)) continue;  // NaN
    bool dominated = false;
    for (size_t j = 0; j < points.size() && !dominated; ++j) {
      const CostError& q = points[j];
      dominated = q.cost <= p.cost && q.error <= p.error && (q.cost < p.cost || q.error < p.error);
    }
    front[i] = !dominated;
  }
  return front;
}

}  // namespace tessera
