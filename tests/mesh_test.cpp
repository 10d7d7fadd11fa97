// Procedural meshes: counts, winding, closedness, uv layout, bad parameters.
#include <map>
#include <tuple>

#include <gtest/gtest.h>

#include "core/check.h"
#include "core/mesh.h"
#include "core/mesh_adjacency.h"

namespace tessera {
namespace {

using Edge = std::tuple<float, float, float, float, float, float>;
Edge edge_key(glm::vec3 a, glm::vec3 b) {
  return {a.x, a.y, a.z, b.x, b.y, b.z};
}

// Every directed edge (by exact vertex position) must appear once and its reverse once: the
// surface is closed and consistently wound. Degenerate (pole) triangles are not allowed.
void expect_closed(const Mesh& mesh) {
  std::map<Edge, int> directed;
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    for (int k = 0; k < 3; ++k) {
      glm::vec3 a = mesh.positions[mesh.indices[t * 3 + k]];
      glm::vec3 b = mesh.positions[mesh.indices[t * 3 + (k + 1) % 3]];
      ASSERT_NE(a, b) << "triangle " << t << " has a zero-length edge";
      directed[edge_key(a, b)]++;
    }
  }
  for (const auto& [e, count] : directed) {
    EXPECT_EQ(count, 1);
    auto [ax, ay, az, bx, by, bz] = e;
    EXPECT_EQ(directed.count(edge_key({bx, by, bz}, {ax, ay, az})), 1u) << "open edge";
  }
}

// The geometric normal of every triangle points the way of its vertex normals (front side out).
void expect_outward_winding(const Mesh& mesh) {
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    uint32_t i0 = mesh.indices[t * 3], i1 = mesh.indices[t * 3 + 1], i2 = mesh.indices[t * 3 + 2];
    glm::vec3 n = glm::cross(mesh.positions[i1] - mesh.positions[i0],
                             mesh.positions[i2] - mesh.positions[i0]);
    glm::vec3 avg = mesh.normals[i0] + mesh.normals[i1] + mesh.normals[i2];
    EXPECT_GT(glm::dot(n, avg), 0.0f) << "triangle " << t << " winds clockwise from outside";
  }
}

TEST(Mesh, UvSphereIsClosedOutwardAndUnit) {
  Mesh m = make_uv_sphere(24, 12);
  EXPECT_EQ(m.triangle_count(), 2u * 24 * 11);
  expect_closed(m);
  expect_outward_winding(m);
  for (size_t v = 0; v < m.positions.size(); ++v) {
    EXPECT_NEAR(glm::length(m.positions[v]), 1.0f, 1e-6f);
    EXPECT_NEAR(glm::length(m.normals[v]), 1.0f, 1e-6f);
  }
}

TEST(Mesh, IcosphereIsClosedOutward) {
  for (uint32_t level : {0u, 1u, 3u}) {
    Mesh m = make_icosphere(level);
    EXPECT_EQ(m.triangle_count(), 20u << (2 * level));
    expect_closed(m);
    expect_outward_winding(m);
  }
}

TEST(Mesh, CubeIsClosedOutward) {
  Mesh m = make_cube();
  EXPECT_EQ(m.triangle_count(), 12u);
  expect_closed(m);
  expect_outward_winding(m);
}

TEST(Mesh, PlaneFacesPlusZ) {
  Mesh m = make_plane(3, 2);
  EXPECT_EQ(m.triangle_count(), 12u);
  expect_outward_winding(m);
}

// The uv of the vertex of `mesh` at `position` with normal `normal` (exactly one must match).
glm::vec2 uv_at(const Mesh& mesh, glm::vec3 position, glm::vec3 normal) {
  glm::vec2 uv(-1.0f);
  int found = 0;
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    if (glm::length(mesh.positions[v] - position) < 1e-6f && mesh.normals[v] == normal) {
      uv = mesh.uvs[v];
      ++found;
    }
  }
  EXPECT_EQ(found, 1) << "vertices at (" << position.x << ", " << position.y << ", " << position.z
                      << ")";
  return uv;
}

void expect_uv(const Mesh& mesh, glm::vec3 position, glm::vec3 normal, glm::vec2 want,
               const char* what) {
  const glm::vec2 uv = uv_at(mesh, position, normal);
  EXPECT_NEAR(uv.x, want.x, 1e-6f) << what;
  EXPECT_NEAR(uv.y, want.y, 1e-6f) << what;
}

// Texture convention (glTF's): uv (0, 0) is the image's top-left corner, v grows down the
// image. The plane, seen from +z with +y up, shows the image upright and unmirrored.
TEST(Mesh, PlaneUvsShowTheImageUpright) {
  const Mesh m = make_plane(3, 2);
  const glm::vec3 n(0, 0, 1);
  expect_uv(m, {-1, 1, 0}, n, {0, 0}, "top left");
  expect_uv(m, {1, 1, 0}, n, {1, 0}, "top right");
  expect_uv(m, {-1, -1, 0}, n, {0, 1}, "bottom left");
  expect_uv(m, {1, -1, 0}, n, {1, 1}, "bottom right");
  expect_uv(m, {1.0f / 3.0f, 0, 0}, n, {2.0f / 3.0f, 0.5f}, "inner vertex");
  // Tangent along +u (+x); bitangent along +v (-y) = -cross(n, t): w = -1.
  for (const glm::vec4& t : m.tangents) {
    EXPECT_NEAR(t.x, 1.0f, 1e-6f);
    EXPECT_EQ(t.w, -1.0f);
  }
}

// Each side face of the cube, seen from outside with +y up, shows the image upright and
// unmirrored. The top and bottom faces lie as in a cross-shaped net unfolded from the front
// (+z) face: the top's image top edge at the back (-z), the bottom's at the front (+z).
TEST(Mesh, CubeUvsShowTheImageUprightOnEveryFace) {
  struct FaceCorners {
    const char* name;
    glm::vec3 n, top_left, top_right, bottom_left;  // as a viewer of the face sees them
  };
  const FaceCorners faces[] = {
      {"front +z", {0, 0, 1}, {-1, 1, 1}, {1, 1, 1}, {-1, -1, 1}},
      {"back -z", {0, 0, -1}, {1, 1, -1}, {-1, 1, -1}, {1, -1, -1}},
      {"right +x", {1, 0, 0}, {1, 1, 1}, {1, 1, -1}, {1, -1, 1}},
      {"left -x", {-1, 0, 0}, {-1, 1, -1}, {-1, 1, 1}, {-1, -1, -1}},
      {"top +y", {0, 1, 0}, {-1, 1, -1}, {1, 1, -1}, {-1, 1, 1}},
      {"bottom -y", {0, -1, 0}, {-1, -1, 1}, {1, -1, 1}, {-1, -1, -1}},
  };
  const Mesh m = make_cube();
  for (const FaceCorners& f : faces) {
    SCOPED_TRACE(f.name);
    const glm::vec3 bottom_right = f.top_right + f.bottom_left - f.top_left;
    expect_uv(m, f.top_left, f.n, {0, 0}, "top left");
    expect_uv(m, f.top_right, f.n, {1, 0}, "top right");
    expect_uv(m, f.bottom_left, f.n, {0, 1}, "bottom left");
    expect_uv(m, bottom_right, f.n, {1, 1}, "bottom right");
  }
  // Tangents along +u (image right), bitangents along +v (image down) = -cross(n, t): w = -1
  // on every face, as on the uv sphere.
  for (size_t v = 0; v < m.positions.size(); ++v) {
    EXPECT_EQ(m.tangents[v].w, -1.0f) << "vertex " << v;
    EXPECT_NEAR(glm::dot(glm::vec3(m.tangents[v]), m.normals[v]), 0.0f, 1e-6f);
  }
}

TEST(Mesh, BadParametersAreUserErrors) {
  EXPECT_THROW(make_uv_sphere(2, 8), Error);
  EXPECT_THROW(make_uv_sphere(8, 1), Error);
  EXPECT_THROW(make_icosphere(9), Error);
  EXPECT_THROW(make_plane(0, 4), Error);
}

TEST(MeshAdjacency, AQuadWithSplitCornersJoinsAcrossItsDiagonal) {
  // Two triangles of the square (0,0)-(1,1) with their own copies of the diagonal's corners
  // (as a seam makes them): 0 = (0,0,0), 1 = (1,0,0), 2 = (1,1,0); 3 = (0,0,0), 4 = (1,1,0),
  // 5 = (0,1,0). Triangle 0's edge 2 -> 0 (its corner 2's edge) is triangle 1's edge 3 -> 4
  // (corner 0's); every other edge is open.
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  m.indices = {0, 1, 2, 3, 4, 5};
  const std::vector<uint32_t> expected = {kNoNeighbour, kNoNeighbour, 1, 0,
                                          kNoNeighbour, kNoNeighbour};
  EXPECT_EQ(triangle_adjacency(m), expected);
  // Wound the same way twice (no consistent winding): no neighbour, not a wrong one.
  m.indices = {0, 1, 2, 4, 3, 5};
  EXPECT_EQ(triangle_adjacency(m), std::vector<uint32_t>(6, kNoNeighbour));
}

TEST(MeshAdjacency, ClosedMeshesHaveANeighbourAcrossEveryEdgeThatPointsBack) {
  // The cube (24 corners for 8 positions) and a uv sphere (a seam of duplicated corners, and
  // the poles: one position for a ring of corners): closed and consistently wound (as
  // expect_closed checks), so every edge has a neighbour, whose own edge with the same two
  // positions points back.
  for (const Mesh& m : {make_cube(), make_uv_sphere(16, 8)}) {
    const std::vector<uint32_t> adj = triangle_adjacency(m);
    ASSERT_EQ(adj.size(), m.indices.size());
    for (size_t t = 0; t < m.triangle_count(); ++t) {
      for (size_t e = 0; e < 3; ++e) {
        const uint32_t n = adj[3 * t + e];
        ASSERT_NE(n, kNoNeighbour) << "triangle " << t << " edge " << e;
        const glm::vec3 a = m.positions[m.indices[3 * t + e]];
        const glm::vec3 b = m.positions[m.indices[3 * t + (e + 1) % 3]];
        bool back = false;
        for (size_t f = 0; f < 3; ++f) {
          const glm::vec3 c = m.positions[m.indices[3 * n + f]];
          const glm::vec3 d = m.positions[m.indices[3 * n + (f + 1) % 3]];
          if (c == b && d == a) back = adj[3 * n + f] == t;
        }
        EXPECT_TRUE(back) << "triangle " << t << " edge " << e << " -> " << n;
      }
    }
  }
}

}  // namespace
}  // namespace tessera
