#include "core/mesh_adjacency.h"

#include <algorithm>
#include <array>
#include <tuple>

namespace tessera {

namespace {

// Corner index -> one index per distinct position (the lowest corner index holding it).
std::vector<uint32_t> weld_by_position(const std::vector<glm::vec3>& positions) {
  std::vector<uint32_t> order(positions.size());
  for (uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  const auto key = [&](uint32_t i) {
    const glm::vec3& p = positions[i];
    return std::tuple(p.x, p.y, p.z, i);
  };
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return key(a) < key(b); });
  std::vector<uint32_t> welded(positions.size());
  for (size_t k = 0; k < order.size(); ++k) {
    const bool same = k > 0 && positions[order[k]] == positions[order[k - 1]];
    welded[order[k]] = same ? welded[order[k - 1]] : order[k];
  }
  return welded;
}

struct DirectedEdge {
  uint32_t from, to, triangle;
  auto operator<=>(const DirectedEdge&) const = default;
};

}  // namespace

std::vector<uint32_t> triangle_adjacency(const Mesh& mesh) {
  const std::vector<uint32_t> welded = weld_by_position(mesh.positions);
  const size_t triangles = mesh.triangle_count();
  std::vector<DirectedEdge> edges;
  edges.reserve(3 * triangles);
  for (uint32_t t = 0; t < triangles; ++t) {
    for (uint32_t e = 0; e < 3; ++e) {
      const uint32_t a = welded[mesh.indices[3 * t + e]];
      const uint32_t b = welded[mesh.indices[3 * t + (e + 1) % 3]];
      if (a != b) edges.push_back({a, b, t});
    }
  }
  std::sort(edges.begin(), edges.end());
  std::vector<uint32_t> adjacency(3 * triangles, kNoNeighbour);
  for (uint32_t t = 0; t < triangles; ++t) {
    for (uint32_t e = 0; e < 3; ++e) {
      const uint32_t a = welded[mesh.indices[3 * t + e]];
      const uint32_t b = welded[mesh.indices[3 * t + (e + 1) % 3]];
      if (a == b) continue;
      // The first triangle with the edge b -> a, other than t itself (which has it too if
      // two of its corners share a position).
      auto it = std::lower_bound(edges.begin(), edges.end(), DirectedEdge{b, a, 0});
      while (it != edges.end() && it->from == b && it->to == a && it->triangle == t) ++it;
      if (it != edges.end() && it->from == b && it->to == a) adjacency[3 * t + e] = it->triangle;
    }
  }
  return adjacency;
}

}  // namespace tessera
