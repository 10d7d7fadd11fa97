#include "core/light_floor.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace tessera {
namespace {

double distance_to_segment(glm::dvec3 start, glm::dvec3 along, glm::dvec3 point) {
  const double length2 = glm::dot(along, along);
  const double t =
      length2 > 0.0 ? std::clamp(glm::dot(point - start, along) / length2, 0.0, 1.0) : 0.0;
  return glm::length(point - (start + t * along));
}

// The parallelogram corner + s u + t v, s and t in [0, 1]; u and v may be parallel or zero (a
// flat or empty box side), where its edges still cover it.
double distance_to_parallelogram(glm::dvec3 corner, glm::dvec3 u, glm::dvec3 v, glm::dvec3 point) {
  const glm::dvec3 w = point - corner;
  const glm::dvec3 n = glm::cross(u, v);
  const double n2 = glm::dot(n, n);  // = |u|^2 |v|^2 - (u.v)^2, the Gram determinant
  if (n2 > 0.0) {
    // The foot of the perpendicular, in (s, t), by the normal equations.
    const double uu = glm::dot(u, u), uv = glm::dot(u, v), vv = glm::dot(v, v);
    const double wu = glm::dot(w, u), wv = glm::dot(w, v);
    const double s = (vv * wu - uv * wv) / n2, t = (uu * wv - uv * wu) / n2;
    if (s >= 0.0 && s <= 1.0 && t >= 0.0 && t <= 1.0)
      return std::abs(glm::dot(w, n)) / std::sqrt(n2);
  }
  return std::min({distance_to_segment(corner, u, point), distance_to_segment(corner, v, point),
                   distance_to_segment(corner + u, v, point),
                   distance_to_segment(corner + v, u, point)});
}

// The triangle a, b, c: the foot of the perpendicular where it falls inside, else the nearest
// of its edges (which also cover a degenerate triangle).
double distance_to_triangle(glm::dvec3 a, glm::dvec3 b, glm::dvec3 c, glm::dvec3 point) {
  const glm::dvec3 u = b - a, v = c - a, w = point - a;
  const glm::dvec3 n = glm::cross(u, v);
  const double n2 = glm::dot(n, n);
  if (n2 > 0.0) {
    const double uu = glm::dot(u, u), uv = glm::dot(u, v), vv = glm::dot(v, v);
    const double wu = glm::dot(w, u), wv = glm::dot(w, v);
    const double s = (vv * wu - uv * wv) / n2, t = (uu * wv - uv * wu) / n2;
    if (s >= 0.0 && t >= 0.0 && s + t <= 1.0) return std::abs(glm::dot(w, n)) / std::sqrt(n2);
  }
  return std::min({distance_to_segment(a, u, point), distance_to_segment(a, v, point),
                   distance_to_segment(b, c - b, point)});
}

// Triangles lights_within_floor measures exactly, in all: beyond them (hundreds of lights
// inside the bounds of a mesh of millions of triangles) it keeps the boxes' distances, a
// fraction of a second on one core.
constexpr uint64_t kMaxTriangleTests = uint64_t(1) << 24;

// The nearest of `mesh`'s triangles placed by `m` to `point`, or `limit` where none is nearer;
// spends one of `budget` a triangle, and returns a negative value where it runs out.
double distance_to_mesh(const Mesh& mesh, const glm::dmat4& m, glm::dvec3 point, double limit,
                        uint64_t& budget) {
  if (budget < mesh.triangle_count()) return -1.0;
  budget -= mesh.triangle_count();
  const auto world = [&](uint32_t i) {
    return glm::dvec3(m * glm::dvec4(glm::dvec3(mesh.positions[i]), 1.0));
  };
  double nearest = limit;
  for (size_t t = 0; t < mesh.triangle_count() && nearest > 0.0; ++t) {
    nearest = std::min(
        nearest, distance_to_triangle(world(mesh.indices[3 * t]), world(mesh.indices[3 * t + 1]),
                                      world(mesh.indices[3 * t + 2]), point));
  }
  return nearest;
}

struct WorldBounds {
  glm::dvec3 lo{std::numeric_limits<double>::infinity()};
  glm::dvec3 hi{-std::numeric_limits<double>::infinity()};
};

}  // namespace

double distance_to_placed_box(const MeshBox& box, const glm::dmat4& m, glm::dvec3 point) {
  if (box.min.x > box.max.x || box.min.y > box.max.y || box.min.z > box.max.z)
    return std::numeric_limits<double>::infinity();
  const glm::dvec3 lo(box.min), side = glm::dvec3(box.max) - lo;
  const glm::dvec3 corner(m * glm::dvec4(lo, 1.0));
  const glm::dvec3 a = glm::dvec3(m[0]) * side.x, b = glm::dvec3(m[1]) * side.y,
                   c = glm::dvec3(m[2]) * side.z;
  // Inside: the point's coordinates along a, b, c (Cramer's rule) all in [0, 1]. A flat
  // parallelepiped (volume 0) has no inside apart from its faces.
  const double volume = glm::dot(a, glm::cross(b, c));
  if (volume != 0.0) {
    const glm::dvec3 w = point - corner;
    const glm::dvec3 f(glm::dot(w, glm::cross(b, c)) / volume,
                       glm::dot(a, glm::cross(w, c)) / volume,
                       glm::dot(a, glm::cross(b, w)) / volume);
    if (glm::all(glm::greaterThanEqual(f, glm::dvec3(0.0))) &&
        glm::all(glm::lessThanEqual(f, glm::dvec3(1.0))))
      return 0.0;
  }
  // Outside, or on a flat one: the nearest of the six faces (which cover a flat one too).
  return std::min({distance_to_parallelogram(corner, b, c, point),
                   distance_to_parallelogram(corner + a, b, c, point),
                   distance_to_parallelogram(corner, a, c, point),
                   distance_to_parallelogram(corner + b, a, c, point),
                   distance_to_parallelogram(corner, a, b, point),
                   distance_to_parallelogram(corner + c, a, b, point)});
}

NearLights lights_within_floor(const Scene& scene) {
  std::vector<MeshBox> boxes;
  for (const Mesh& mesh : scene.meshes) boxes.push_back(mesh_box(mesh));
  // Each drawn object's world-space bounds, which contain its placed box: a pair whose bounds
  // lie beyond the floor needs no exact distance.
  std::vector<WorldBounds> bounds(scene.objects.size());
  for (size_t o = 0; o < scene.objects.size(); ++o) {
    const Object& obj = scene.objects[o];
    if (obj.mesh >= scene.meshes.size() || scene.meshes[obj.mesh].triangle_count() == 0) continue;
    const MeshBox& box = boxes[obj.mesh];
    for (int k = 0; k < 8; ++k) {
      const glm::dvec4 p((k & 1) ? box.max.x : box.min.x, (k & 2) ? box.max.y : box.min.y,
                         (k & 4) ? box.max.z : box.min.z, 1.0);
      const glm::dvec3 w(glm::dmat4(obj.transform) * p);
      bounds[o].lo = glm::min(bounds[o].lo, w);
      bounds[o].hi = glm::max(bounds[o].hi, w);
    }
  }
  NearLights near;
  uint64_t budget = kMaxTriangleTests;
  for (size_t l = 0; l < scene.lights.size(); ++l) {
    const Light& light = scene.lights[l];
    if (light.kind == LightKind::directional || light.falloff != Falloff::inverse_square) continue;
    // Beyond its range the light gives nothing, floored or not.
    const double reach = light.range > 0.0f ? std::min(kLightDistanceFloor, double(light.range))
                                            : kLightDistanceFloor;
    const glm::dvec3 at(light.position);
    double nearest = reach;
    size_t nearest_object = 0;
    for (size_t o = 0; o < scene.objects.size(); ++o) {
      const WorldBounds& b = bounds[o];
      if (b.lo.x > b.hi.x) continue;  // not drawn
      const glm::dvec3 outside = glm::max(glm::max(b.lo - at, at - b.hi), glm::dvec3(0.0));
      if (glm::length(outside) >= nearest) continue;
      const Object& obj = scene.objects[o];
      const glm::dmat4 m(obj.transform);
      double d = distance_to_placed_box(boxes[obj.mesh], m, at);
      // Within the box's reach: the surface itself, which may lie far from a light inside the
      // box (a lamp in a room, a light inside a sphere's box but off its surface).
      if (d < nearest) {
        const double exact = distance_to_mesh(scene.meshes[obj.mesh], m, at, nearest, budget);
        if (exact >= 0.0) {
          d = exact;
        } else {
          near.exact = false;
        }
      }
      if (d < nearest) {
        nearest = d;
        nearest_object = o;
        if (near.count > 0) break;  // only the first such light's nearest object is said
      }
    }
    if (nearest >= reach) continue;
    if (near.count++ == 0) {
      near.light = l;
      near.object = nearest_object;
      near.distance = nearest;
    }
  }
  return near;
}

}  // namespace tessera
