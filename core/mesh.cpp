#include "core/mesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>

#include "core/check.h"
#include "core/texture.h"

namespace tessera {
namespace {

constexpr double kPi = std::numbers::pi;

void add_vertex(Mesh& mesh, glm::vec3 p, glm::vec3 n, glm::vec2 uv) {
  mesh.positions.push_back(p);
  mesh.normals.push_back(n);
  mesh.uvs.push_back(uv);
}

void add_triangle(Mesh& mesh, uint32_t a, uint32_t b, uint32_t c) {
  mesh.indices.insert(mesh.indices.end(), {a, b, c});
}

}  // namespace

Mesh make_uv_sphere(uint32_t segments, uint32_t rings) {
  if (segments < 3 || rings < 2) {
    throw Error("a uv sphere needs at least 3 segments and 2 rings (got " +
                std::to_string(segments) + " and " + std::to_string(rings) + ")");
  }
  Mesh mesh;
  // (segments + 1) columns so the seam has its own uv; column `segments` reuses column 0's
  // angle so its positions are bit-identical to column 0's.
  for (uint32_t r = 0; r <= rings; ++r) {
    double theta = kPi * r / rings;  // from +y down to -y
    for (uint32_t s = 0; s <= segments; ++s) {
      double phi = 2.0 * kPi * (s % segments) / segments;
      glm::vec3 p;
      if (r == 0 || r == rings) {
        p = glm::vec3(0.0f, r == 0 ? 1.0f : -1.0f, 0.0f);  // exact poles
      } else {
        p = glm::vec3(float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)),
                      float(-std::sin(theta) * std::sin(phi)));
      }
      add_vertex(mesh, p, p, glm::vec2(float(s) / segments, float(r) / rings));
    }
  }
  const uint32_t stride = segments + 1;
  for (uint32_t r = 0; r < rings; ++r) {
    for (uint32_t s = 0; s < segments; ++s) {
      uint32_t a = r * stride + s;  // upper left
      uint32_t b = a + stride;      // lower left
      uint32_t c = b + 1;           // lower right
      uint32_t d = a + 1;           // upper right
      // Counter-clockwise seen from outside; the pole quads degenerate to one triangle.
      if (r != 0) add_triangle(mesh, a, b, d);
      if (r != rings - 1) add_triangle(mesh, d, b, c);
    }
  }
  mesh.analytic_sphere = AnalyticSphere{};
  mesh.tangents = generate_tangents(mesh.positions, mesh.normals, mesh.uvs, mesh.indices);
  return mesh;
}

Mesh make_icosphere(uint32_t level) {
  if (level > 8) throw Error("icosphere level " + std::to_string(level) + " is above 8");
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<glm::dvec3> points = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                                    {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                                    {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (auto& p : points) p = glm::normalize(p);
  std::vector<std::array<uint32_t, 3>> faces = {
      {0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
      {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
      {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (uint32_t l = 0; l < level; ++l) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoints;
    auto midpoint = [&](uint32_t a, uint32_t b) {
      auto key = std::minmax(a, b);
      auto [it, inserted] = midpoints.try_emplace({key.first, key.second}, 0);
      if (inserted) {
        it->second = uint32_t(points.size());
        points.push_back(glm::normalize(points[a] + points[b]));
      }
      return it->second;
    };
    std::vector<std::array<uint32_t, 3>> next;
    next.reserve(faces.size() * 4);
    for (auto [a, b, c] : faces) {
      uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      next.insert(next.end(), {{a, ab, ca}, {b, bc, ab}, {c, ca, bc}, {ab, bc, ca}});
    }
    faces = std::move(next);
  }
  Mesh mesh;
  for (const auto& p : points) {
    glm::vec3 n(p);
    // Equirectangular uv; the seam is not split, which is fine for untextured use.
    double u = 0.5 + std::atan2(-p.z, p.x) / (2.0 * kPi);
    double v = std::acos(std::clamp(p.y, -1.0, 1.0)) / kPi;
    add_vertex(mesh, n, n, glm::vec2(float(u), float(v)));
  }
  for (auto [a, b, c] : faces) add_triangle(mesh, a, b, c);
  mesh.analytic_sphere = AnalyticSphere{glm::vec3(0.0f), 1.0f, 0.5f};
  mesh.tangents = generate_tangents(mesh.positions, mesh.normals, mesh.uvs, mesh.indices);
  return mesh;
}

Mesh make_cube() {
  // Each face: its normal, and the directions in which u (image right) and v (image down)
  // grow. The side faces show the image upright and unmirrored seen from outside with +y up;
  // the top and bottom faces as they lie in a cross-shaped net unfolded from the front face:
  // the top's image top edge at the back (-z), the bottom's at the front (+z). right x down =
  // -n on every face, so the generated tangents have w = -1, as the uv sphere's do.
  struct Face {
    glm::vec3 n, right, down;
  };
  const std::array<Face, 6> faces = {
      Face{{1, 0, 0}, {0, 0, -1}, {0, -1, 0}}, Face{{-1, 0, 0}, {0, 0, 1}, {0, -1, 0}},
      Face{{0, 1, 0}, {1, 0, 0}, {0, 0, 1}},   Face{{0, -1, 0}, {1, 0, 0}, {0, 0, -1}},
      Face{{0, 0, 1}, {1, 0, 0}, {0, -1, 0}},  Face{{0, 0, -1}, {-1, 0, 0}, {0, -1, 0}}};
  Mesh mesh;
  for (const Face& f : faces) {
    const glm::vec3 n = f.n;
    // Two axes spanning the face, chosen so that u x v = n (counter-clockwise from outside).
    glm::vec3 u = std::abs(n.y) > 0.5f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    glm::vec3 v = glm::cross(n, u);
    u = glm::cross(v, n);
    uint32_t first = uint32_t(mesh.positions.size());
    const std::array<glm::vec2, 4> corners = {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1),
                                              glm::vec2(-1, 1)};
    for (glm::vec2 c : corners) {
      const glm::vec3 p = n + c.x * u + c.y * v;
      // Exact: p's coordinates are +-1, so the uvs are 0 or 1.
      add_vertex(mesh, p, n, glm::vec2(glm::dot(p, f.right), glm::dot(p, f.down)) * 0.5f + 0.5f);
    }
    add_triangle(mesh, first, first + 1, first + 2);
    add_triangle(mesh, first, first + 2, first + 3);
  }
  mesh.tangents = generate_tangents(mesh.positions, mesh.normals, mesh.uvs, mesh.indices);
  return mesh;
}

Mesh make_plane(uint32_t nx, uint32_t ny) {
  if (nx == 0 || ny == 0) {
    throw Error("a plane needs at least 1 x 1 quads (got " + std::to_string(nx) + " x " +
                std::to_string(ny) + ")");
  }
  Mesh mesh;
  for (uint32_t y = 0; y <= ny; ++y) {
    for (uint32_t x = 0; x <= nx; ++x) {
      const glm::vec2 grid(float(x) / nx, float(y) / ny);
      // v = 0 at the top (+y) edge: the image upright seen from +z (glTF's uv convention).
      const glm::vec2 uv(grid.x, float(ny - y) / ny);
      add_vertex(mesh, glm::vec3(grid * 2.0f - 1.0f, 0.0f), glm::vec3(0, 0, 1), uv);
    }
  }
  for (uint32_t y = 0; y < ny; ++y) {
    for (uint32_t x = 0; x < nx; ++x) {
      uint32_t a = y * (nx + 1) + x;
      uint32_t b = a + 1;
      uint32_t c = a + nx + 1;
      add_triangle(mesh, a, b, c + 1);
      add_triangle(mesh, a, c + 1, c);
    }
  }
  mesh.tangents = generate_tangents(mesh.positions, mesh.normals, mesh.uvs, mesh.indices);
  return mesh;
}

MeshShape shape_of(const Mesh& mesh) {
  using Kind = MeshShape::Kind;
  const uint64_t v = mesh.positions.size(), t = mesh.triangle_count();
  // The counts pick the candidates; only the whole mesh compared decides.
  if (t == 12 && mesh == make_cube()) return {Kind::cube};
  for (uint32_t level = 0; level <= 8; ++level)
    if (t == 20ull << (2 * level) && mesh == make_icosphere(level)) return {Kind::icosphere, level};
  // uv sphere: (segments + 1)(rings + 1) vertices, 2 segments (rings - 1) triangles.
  for (uint64_t s = 3; s + 1 <= v / 3; ++s) {
    if (v % (s + 1) != 0) continue;
    const uint64_t rings = v / (s + 1) - 1;
    if (rings >= 2 && t == 2 * s * (rings - 1) &&
        mesh == make_uv_sphere(uint32_t(s), uint32_t(rings)))
      return {Kind::uv_sphere, uint32_t(s), uint32_t(rings)};
  }
  // plane: (nx + 1)(ny + 1) vertices, 2 nx ny triangles.
  for (uint64_t nx = 1; nx + 1 <= v / 2; ++nx) {
    if (v % (nx + 1) != 0) continue;
    const uint64_t ny = v / (nx + 1) - 1;
    if (ny >= 1 && t == 2 * nx * ny && mesh == make_plane(uint32_t(nx), uint32_t(ny)))
      return {Kind::plane, uint32_t(nx), uint32_t(ny)};
  }
  return {};
}

}  // namespace tessera
