#pragma once
// Which triangle of a mesh lies across each edge of each triangle, for silhouette coverage
// (FrameSettings::aa_coverage silhouette; docs/architecture.md, "Anti-aliasing"): the walk
// from the triangle a pixel's samples see to the neighbours they miss. No Vulkan here.

#include <cstdint>
#include <vector>

#include "core/scene.h"

namespace tessera {

/// Adjacency entry of an edge with no triangle across it (an open boundary).
inline constexpr uint32_t kNoNeighbour = 0xFFFFFFFFu;

/// Per edge of each triangle of `mesh` (3 entries per triangle, parallel to Mesh::indices:
/// entry 3t + e is the edge from corner e to corner (e + 1) % 3 of triangle t), the index of
/// the triangle across it, or kNoNeighbour. Corners are welded by exact position first, so
/// seams that duplicate vertices for their normals or uvs still join. The neighbour is a
/// triangle with the same edge walked the other way (consistently wound); where several have
/// it (a non-manifold edge) the one of lowest index, so the result depends on the mesh
/// alone. A degenerate edge (both ends at one position) has none. O(n log n) in the triangles.
std::vector<uint32_t> triangle_adjacency(const Mesh& mesh);

}  // namespace tessera
