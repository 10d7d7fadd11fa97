// Procedural meshes: counts, winding, closedness, bad parameters.
#include <map>
#include <tuple>

#include <gtest/gtest.h>

#include "core/check.h"
#include "core/mesh.h"

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

TEST(Mesh, BadParametersAreUserErrors) {
  EXPECT_THROW(make_uv_sphere(2, 8), Error);
  EXPECT_THROW(make_uv_sphere(8, 1), Error);
  EXPECT_THROW(make_icosphere(9), Error);
  EXPECT_THROW(make_plane(0, 4), Error);
}

}  // namespace
}  // namespace tessera
