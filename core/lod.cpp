#include "core/lod.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <meshoptimizer.h>

#include "core/check.h"
#include "core/mesh.h"

namespace tessera {
namespace {

constexpr double kPi = std::numbers::pi;

// The largest distance between the sphere of `sphere` and the facets of `mesh`, measured:
// sphere radius minus the smallest distance from its centre to the plane of a triangle. The
// mesh is convex and inscribed (its vertices on the sphere), so it contains the ball of that
// smaller radius and no point of the sphere is farther than this from it.
double measured_chord_error(const Mesh& mesh, const AnalyticSphere& sphere) {
  const glm::dvec3 centre(sphere.centre);
  double nearest = std::numeric_limits<double>::infinity();
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    const glm::dvec3 a(mesh.positions[mesh.indices[3 * t]]);
    const glm::dvec3 b(mesh.positions[mesh.indices[3 * t + 1]]);
    const glm::dvec3 c(mesh.positions[mesh.indices[3 * t + 2]]);
    const glm::dvec3 n = glm::cross(b - a, c - a);
    const double length = glm::length(n);
    if (!(length > 0.0)) continue;  // a degenerate triangle has no plane and covers nothing
    nearest = std::min(nearest, std::abs(glm::dot(a - centre, n)) / length);
  }
  return std::max(0.0, double(sphere.radius) - nearest);
}

// make_uv_sphere(segments, segments / 2) moved onto `sphere` (centre, radius, u at +x).
Mesh placed_uv_sphere(uint32_t segments, const AnalyticSphere& sphere) {
  Mesh m = make_uv_sphere(segments, segments / 2);
  for (glm::vec3& p : m.positions) p = sphere.centre + sphere.radius * p;
  // make_uv_sphere has u = 0 at +x; the shift keeps u's direction, so tangents stay valid.
  for (glm::vec2& uv : m.uvs) uv.x += sphere.u_at_plus_x;
  m.analytic_sphere = sphere;
  return m;
}

LodChain sphere_chain(const Mesh& mesh, const std::shared_ptr<const Mesh>& base) {
  const AnalyticSphere& sphere = *mesh.analytic_sphere;
  std::vector<LodLevel> candidates;
  candidates.push_back({base, true, true, measured_chord_error(mesh, sphere)});
  for (uint32_t s : kSphereLodSegments) {
    const double error = double(sphere.radius) * uv_sphere_chord_error(s, s / 2);
    auto level = std::make_shared<const Mesh>(placed_uv_sphere(s, sphere));
    // The base mesh when it is this very tessellation: the base is kept, so that choosing it
    // draws exactly the mesh without level of detail.
    const LodLevel& b = candidates.front();
    if (level->triangle_count() == mesh.triangle_count() &&
        std::abs(error - b.error) <= 1e-4 * std::max(error, b.error)) {
      continue;
    }
    candidates.push_back({std::move(level), false, false, error});
  }
  // Keep the levels no other level beats (no larger error and fewer triangles, or a smaller
  // error and no more triangles), finest first.
  std::vector<LodLevel> kept;
  for (const LodLevel& l : candidates) {
    bool dominated = false;
    for (const LodLevel& o : candidates) {
      const size_t lt = l.mesh->triangle_count(), ot = o.mesh->triangle_count();
      dominated |= (o.error <= l.error && ot < lt) || (o.error < l.error && ot <= lt);
    }
    if (!dominated) kept.push_back(l);
  }
  std::sort(kept.begin(), kept.end(),
            [](const LodLevel& a, const LodLevel& b) { return a.error < b.error; });
  LodChain chain;
  chain.levels = std::move(kept);
  chain.centre = glm::dvec3(sphere.centre);
  // The vertices lie on the sphere up to float rounding of their coordinates.
  chain.radius = double(sphere.radius) * (1.0 + 1e-6);
  return chain;
}

LodChain simplified_chain(const Mesh& mesh, const std::shared_ptr<const Mesh>& base) {
  LodChain chain;
  chain.levels.push_back({base, true, true, 0.0});
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
  for (const glm::vec3& p : mesh.positions) {
    lo = glm::min(lo, glm::dvec3(p));
    hi = glm::max(hi, glm::dvec3(p));
  }
  chain.centre = (lo + hi) * 0.5;
  for (const glm::vec3& p : mesh.positions)
    chain.radius = std::max(chain.radius, glm::length(glm::dvec3(p) - chain.centre));

  const float* positions = &mesh.positions[0].x;
  const double scale = meshopt_simplifyScale(positions, mesh.positions.size(), sizeof(glm::vec3));
  std::vector<uint32_t> out(mesh.indices.size());
  size_t previous = mesh.triangle_count();
  double previous_error = 0.0;
  while (previous >= 2) {
    float relative = 0.0f;
    const size_t n = meshopt_simplify(
        out.data(), mesh.indices.data(), mesh.indices.size(), positions, mesh.positions.size(),
        sizeof(glm::vec3), previous / 2 * 3, std::numeric_limits<float>::max(), 0, &relative);
    const size_t triangles = n / 3;
    // Stalled (locked borders, seams): a level that saves less than a tenth is not worth it.
    if (triangles == 0 || triangles * 10 > previous * 9) break;
    Mesh level = mesh;
    level.indices.assign(out.begin(), out.begin() + n);
    level.analytic_sphere.reset();
    // meshoptimizer's error need not grow with each level; a coarser level is never claimed
    // to be closer than a finer one.
    previous_error = std::max(previous_error, double(relative) * scale);
    chain.levels.push_back(
        {std::make_shared<const Mesh>(std::move(level)), true, false, previous_error});
    previous = triangles;
  }
  return chain;
}

}  // namespace

// make_uv_sphere(s, r) on the unit sphere: ring k of stacks (k = 0 .. r - 1) runs from polar
// angle t1 = k D to t2 = t1 + D, D = pi / r, and each of its cells spans the longitudes
// phi0 +- d, d = pi / s. In the frame with x towards longitude phi0 and y the pole axis, the
// cell's corners are (sin t cos d, cos t, +-sin t sin d) for t = t1, t2: two chords parallel
// to z, symmetric about the plane z = 0, so the four corners (three at the poles, where
// sin t = 0) lie in one plane, which contains the z direction. Its distance from the centre
// is that of the line through (sin t1 cos d, cos t1) and (sin t2 cos d, cos t2) in the xy
// plane from the origin:
//   |sin t1 cos t2 - cos t1 sin t2| cos d / sqrt(cos^2 d (sin t1 - sin t2)^2 + (cos t1 - cos t2)^2)
// and with m = (t1 + t2) / 2, sin t1 - sin t2 = -2 cos m sin(D/2), cos t1 - cos t2 =
// 2 sin m sin(D/2), sin(t2 - t1) = 2 sin(D/2) cos(D/2):
//   dist(m) = cos d cos(D/2) / sqrt(1 - sin^2 d cos^2 m).
// The sphere's farthest point from the mesh is the foot of the normal of the nearest plane,
// so the chord error is 1 - min over the rings of dist(m_k), m_k = (k + 1/2) D, the ring
// nearest the equator. For odd r a ring is centred on the equator and the error is
// 1 - cos(pi/s) cos(pi/(2r)), sin^2(pi/s) for r = s/2: about twice r (1 - cos(pi/s)), the
// sagitta of the outline seen along the equatorial plane (which bounds only that view).
double uv_sphere_chord_error(uint32_t segments, uint32_t rings) {
  TESSERA_CHECK(segments >= 3 && rings >= 2);
  const double d = kPi / segments, half = kPi / (2.0 * rings);
  double nearest = 1.0;
  for (uint32_t k = 0; k < rings; ++k) {
    const double m = (k + 0.5) * (kPi / rings);
    const double s = std::sin(d) * std::cos(m);
    nearest = std::min(nearest, std::cos(d) * std::cos(half) / std::sqrt(1.0 - s * s));
  }
  return 1.0 - nearest;
}

LodChain build_lod_chain(const Mesh& mesh) {
  TESSERA_CHECK(mesh.triangle_count() > 0);
  auto base = std::make_shared<const Mesh>(mesh);
  LodChain chain = mesh.analytic_sphere ? sphere_chain(mesh, base) : simplified_chain(mesh, base);
  for (size_t i = 0; i < chain.levels.size(); ++i) {
    if (chain.levels[i].is_base) chain.base_level = uint32_t(i);
  }
  return chain;
}

// A point at view depth z and lateral offsets (x, y) projects to f (x/z, y/z), f = (height/2)
// / tan(fovy/2) pixels. Moving it by a small e moves the image point by (f/z) M e, M = [[1, 0,
// -x/z], [0, 1, -y/z]], whose norm is sqrt(1 + (x/z)^2 + (y/z)^2) (M M^T has eigenvalues 1
// and that squared): at most sqrt(1 + tan^2(fovy/2) (1 + aspect^2)) inside the view. So an
// object-space error e at depth >= z moves no visible point by more than e K / z pixels.
double lod_pixels_per_unit(const Camera& camera, uint32_t width, uint32_t height) {
  const double t = std::tan(double(camera.vertical_fov) / 2.0);
  const double aspect = double(width) / double(height);
  return (double(height) / 2.0) / t * std::sqrt(1.0 + t * t * (1.0 + aspect * aspect));
}

uint32_t select_lod_level(const LodChain& chain, const glm::mat4& transform, const Camera& camera,
                          uint32_t width, uint32_t height, double max_error_px) {
  TESSERA_CHECK(!chain.levels.empty() && max_error_px > 0.0);
  const glm::dmat4 model(transform);
  const glm::dvec3 centre = glm::dvec3(model * glm::dvec4(chain.centre, 1.0));
  const double scale =
      std::max({glm::length(glm::dvec3(model[0])), glm::length(glm::dvec3(model[1])),
                glm::length(glm::dvec3(model[2]))});
  const glm::dvec3 forward =
      glm::normalize(glm::dvec3(camera.target) - glm::dvec3(camera.position));
  const double depth = glm::dot(centre - glm::dvec3(camera.position), forward);
  const double near_side = std::max(depth - chain.radius * scale, double(camera.near_plane));
  const double per_unit = scale * lod_pixels_per_unit(camera, width, height) / max_error_px;
  for (uint32_t l = uint32_t(chain.levels.size()); l-- > 1;) {
    if (chain.levels[l].error * per_unit <= near_side) return l;
  }
  return 0;
}

std::vector<LodChain> build_lod_chains(const Scene& scene) {
  std::vector<LodChain> chains(scene.meshes.size());
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    if (scene.meshes[m].triangle_count() > 0) chains[m] = build_lod_chain(scene.meshes[m]);
  }
  return chains;
}

uint64_t lod_triangle_count(const Scene& scene, const std::vector<LodChain>& chains,
                            const FrameSettings& settings) {
  uint64_t total = 0;
  for (const Object& o : scene.objects) {
    const Mesh& mesh = scene.meshes[o.mesh];
    if (settings.lod == Lod::off || mesh.triangle_count() == 0) {
      total += mesh.triangle_count();
      continue;
    }
    const LodChain& chain = chains[o.mesh];
    const uint32_t l = select_lod_level(chain, o.transform, scene.camera, settings.width,
                                        settings.height, settings.lod_error_px);
    total += chain.levels[l].mesh->triangle_count();
  }
  return total;
}

}  // namespace tessera
