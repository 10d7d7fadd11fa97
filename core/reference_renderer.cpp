#include "core/reference_renderer.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <thread>

#include <glm/gtc/matrix_transform.hpp>

#include "core/check.h"
#include "core/lod.h"
#include "core/mesh_adjacency.h"
#include "core/pixel_coverage.h"
#include "core/reference_brdf.h"
#include "core/texture.h"
#include "shaders/shared/constants.h"

namespace tessera {
namespace {

using glm::dmat3;
using glm::dmat4;
using glm::dvec2;
using glm::dvec3;
using glm::dvec4;

constexpr int64_t kSubpixelOne = TS_SUBPIXEL_ONE;  // int64 for the edge arithmetic

struct CameraModel {
  dmat4 view_proj;
  dvec3 position, forward, right, up;
  double tan_x, tan_y, near_plane;
  double width, height;
  double guard_x, guard_y;  // guard band in NDC units
};

CameraModel make_camera(const Camera& c, uint32_t width, uint32_t height) {
  CameraModel m;
  m.width = width;
  m.height = height;
  m.position = dvec3(c.position);
  m.forward = glm::normalize(dvec3(c.target) - m.position);
  m.right = glm::normalize(glm::cross(m.forward, dvec3(c.up)));
  m.up = glm::cross(m.right, m.forward);
  m.tan_y = std::tan(double(c.vertical_fov) / 2.0);
  m.tan_x = m.tan_y * m.width / m.height;
  m.near_plane = c.near_plane;
  // Clip space: x right, y down (Vulkan), w = distance along the view axis.
  dmat4 view = glm::lookAtRH(m.position, dvec3(c.target), dvec3(c.up));
  dmat4 proj(0.0);
  proj[0][0] = 1.0 / m.tan_x;
  proj[1][1] = -1.0 / m.tan_y;
  proj[2][3] = -1.0;
  m.view_proj = proj * view;
  m.guard_x = 2.0 * TS_GUARD_BAND_PX / m.width - 1.0;
  m.guard_y = 2.0 * TS_GUARD_BAND_PX / m.height - 1.0;
  return m;
}

// Unit ray direction through the point (px, py) of the image, in pixels.
dvec3 camera_ray_at(const CameraModel& cam, double px, double py) {
  double ndc_x = px / cam.width * 2.0 - 1.0;
  double ndc_y = py / cam.height * 2.0 - 1.0;
  return glm::normalize(cam.forward + ndc_x * cam.tan_x * cam.right - ndc_y * cam.tan_y * cam.up);
}

// Unit ray direction through the centre of pixel (x, y).
dvec3 camera_ray(const CameraModel& cam, uint32_t x, uint32_t y) {
  return camera_ray_at(cam, x + 0.5, y + 0.5);
}

struct Instance {
  const Mesh* mesh;
  const Material* material;
  dmat4 model;
  dmat3 normal_matrix;
  uint64_t first_triangle;
  uint32_t slot;
  bool mirrored;  // is_mirroring(transform): front faces wind clockwise, tangent frames flip
  const std::vector<glm::vec4>* tangents = nullptr;  // the mesh's, or generated; null if unused
  // triangle_adjacency of `mesh`, under silhouette coverage only (else null).
  const std::vector<uint32_t>* adjacency = nullptr;
};

std::vector<Instance> make_instances(const Scene& scene, const ObjectNumbering& numbering) {
  std::vector<Instance> out;
  for (size_t slot = 0; slot < numbering.objects.size(); ++slot) {
    const Object& o = scene.objects[numbering.objects[slot]];
    dmat4 model(o.transform);
    out.push_back({&scene.meshes[o.mesh], &scene.materials[o.material], model,
                   glm::transpose(glm::inverse(dmat3(model))), numbering.first_triangle[slot],
                   uint32_t(slot), is_mirroring(o.transform)});
  }
  return out;
}

// Level of detail (FrameSettings::lod automatic): each instance takes the level
// select_lod_level chooses (in double; the GPU's float choice agrees but within rounding of a
// level's bound) and the triangles are numbered again in slot order, as the GPU's lod passes
// do. `chains` keeps the level meshes the instances point to; `base_of` maps a level sharing
// its base mesh's vertices to the base mesh (whose tangents the GPU uses for it).
void apply_lod(const Scene& scene, const FrameSettings& frame, const std::vector<LodChain>& chains,
               ObjectNumbering& numbering, std::vector<Instance>& instances,
               std::map<const Mesh*, const Mesh*>& base_of) {
  uint64_t next = 0;
  for (size_t slot = 0; slot < instances.size(); ++slot) {
    const Object& o = scene.objects[numbering.objects[slot]];
    const LodChain& chain = chains[o.mesh];
    const LodLevel& level = chain.levels[select_lod_level(
        chain, o.transform, scene.camera, frame.width, frame.height, frame.lod_error_px)];
    instances[slot].mesh = level.mesh.get();
    if (level.shares_base_vertices) base_of[level.mesh.get()] = &scene.meshes[o.mesh];
    instances[slot].first_triangle = numbering.first_triangle[slot] = next;
    next += level.mesh->triangle_count();
  }
  numbering.triangle_count = next;
}

// The scene's instances as a frame with `frame`'s level-of-detail settings draws them.
struct FrameInstances {
  ObjectNumbering numbering;
  std::vector<Instance> instances;
  std::vector<LodChain> lod_chains;  // owns the level meshes `instances` point to
  std::map<const Mesh*, const Mesh*> base_of;
  std::map<const Mesh*, std::vector<uint32_t>> adjacency;  // what the instances point to
};
FrameInstances frame_instances(const Scene& scene, const FrameSettings& frame) {
  FrameInstances f;
  f.numbering = number_objects(scene);
  f.instances = make_instances(scene, f.numbering);
  if (frame.lod == Lod::automatic) {
    f.lod_chains = build_lod_chains(scene);
    apply_lod(scene, frame, f.lod_chains, f.numbering, f.instances, f.base_of);
  }
  if (frame.samples > 1 && frame.aa_coverage == AaCoverage::silhouette) {
    for (Instance& inst : f.instances) {
      auto [it, added] = f.adjacency.try_emplace(inst.mesh);
      if (added) it->second = triangle_adjacency(*inst.mesh);
      inst.adjacency = &it->second;
    }
  }
  return f;
}

const Instance& instance_of(const std::vector<Instance>& instances, uint64_t id) {
  auto it = std::upper_bound(instances.begin(), instances.end(), id,
                             [](uint64_t v, const Instance& i) { return v < i.first_triangle; });
  TESSERA_CHECK(it != instances.begin());
  return *(it - 1);
}

std::array<uint32_t, 3> corner_indices(const Instance& inst, uint64_t id) {
  const size_t t = size_t(id - inst.first_triangle);
  return {inst.mesh->indices[t * 3], inst.mesh->indices[t * 3 + 1], inst.mesh->indices[t * 3 + 2]};
}

// --- Coverage -----------------------------------------------------------------------------

// Signed distance of clip-space point c to clip plane `plane` (inside >= 0): the near plane,
// then the four guard-band planes.
double plane_distance(const CameraModel& cam, dvec4 c, int plane) {
  switch (plane) {
    case 0:
      return c.w - cam.near_plane;
    case 1:
      return cam.guard_x * c.w - c.x;
    case 2:
      return cam.guard_x * c.w + c.x;
    case 3:
      return cam.guard_y * c.w - c.y;
    default:
      return cam.guard_y * c.w + c.y;
  }
}

// The triangle as the convex polygon left after clipping to the near plane and guard band
// (Sutherland & Hodgman 1974); empty when it is trivially outside the view.
std::vector<dvec4> clipped_polygon(const CameraModel& cam, const std::array<dvec4, 3>& c) {
  for (int axis = 0; axis < 2; ++axis) {
    if (c[0][axis] > c[0].w && c[1][axis] > c[1].w && c[2][axis] > c[2].w) return {};
    if (c[0][axis] < -c[0].w && c[1][axis] < -c[1].w && c[2][axis] < -c[2].w) return {};
  }
  std::vector<dvec4> poly(c.begin(), c.end());
  for (int plane = 0; plane < 5 && !poly.empty(); ++plane) {
    std::vector<dvec4> next;
    for (size_t i = 0; i < poly.size(); ++i) {
      dvec4 a = poly[i], b = poly[(i + 1) % poly.size()];
      double da = plane_distance(cam, a, plane), db = plane_distance(cam, b, plane);
      if (da >= 0) next.push_back(a);
      if ((da >= 0) != (db >= 0)) {
        // From the inside end towards the outside end, whichever way the edge is walked: the
        // two triangles sharing an edge walk it in opposite directions and must get the same
        // crossing, or samples on the edge are covered twice or missed.
        const bool a_in = da >= 0;
        const dvec4 p_in = a_in ? a : b, p_out = a_in ? b : a;
        const double d_in = a_in ? da : db, d_out = a_in ? db : da;
        next.push_back(p_in + (p_out - p_in) * (d_in / (d_in - d_out)));
      }
    }
    poly = std::move(next);
  }
  return poly;
}

dvec2 to_pixels(const CameraModel& cam, dvec4 c) {
  return {(c.x / c.w * 0.5 + 0.5) * cam.width, (c.y / c.w * 0.5 + 0.5) * cam.height};
}

struct FixedPoint {
  int64_t x, y;
};

int64_t edge(FixedPoint a, FixedPoint b, FixedPoint p) {
  return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
}

// Top-left rule: 0 if a sample exactly on edge a->b belongs to the (positively oriented)
// triangle, 1 if it does not.
int64_t edge_threshold(FixedPoint a, FixedPoint b) {
  bool top = a.y == b.y && b.x > a.x;
  bool left = b.y < a.y;
  return (top || left) ? 0 : 1;
}

int64_t floor_div(int64_t v, int64_t one) {
  return v >= 0 ? v / one : -((-v + one - 1) / one);
}
int64_t floor_shift(int64_t v) {
  return floor_div(v, kSubpixelOne);
}

// The samples of a pixel: their positions from its top-left corner in fixed-point units, `one`
// units per pixel (the triangles' snapping grid).
struct SamplePattern {
  int64_t one = kSubpixelOne;
  std::vector<FixedPoint> offsets;
  // Position of sample s of pixel (x, y), in pixels.
  dvec2 point(int64_t x, int64_t y, size_t s) const {
    return {double(x) + double(offsets[s].x) / double(one),
            double(y) + double(offsets[s].y) / double(one)};
  }
};

// The compute path's anti-aliasing pattern of `samples` per pixel (TS_SAMPLES_*, constants.h),
// on its 1/256 px grid.
SamplePattern msaa_pattern(uint32_t samples) {
  std::vector<glm::ivec2> grid;
  switch (samples) {
    case 4:
      grid = {TS_SAMPLES_4(glm::ivec2)};
      break;
    case 8:
      grid = {TS_SAMPLES_8(glm::ivec2)};
      break;
    case 16:
      grid = {TS_SAMPLES_16(glm::ivec2)};
      break;
    default:
      grid = {TS_SAMPLES_1(glm::ivec2)};
      break;
  }
  TESSERA_CHECK(grid.size() == samples);
  SamplePattern p{kSubpixelOne, {}};
  const int64_t scale = kSubpixelOne / TS_SAMPLE_GRID;
  for (glm::ivec2 g : grid) p.offsets.push_back({g.x * scale, g.y * scale});
  return p;
}

// Where a triangle's samples are: the compute path's (`compute`, one at each pixel centre or its
// anti-aliasing pattern), or, with `compute` null, the ground truth's N x N per pixel
// (GroundTruthOptions) on a finer grid.
struct SampleGrid {
  int64_t one = kSubpixelOne;  // fixed-point units per pixel
  const SamplePattern* compute = nullptr;
  // With `compute`: the smallest and largest of its offsets on each axis, the reach of a
  // pixel's samples that setup's boxes use.
  FixedPoint first{0, 0}, last{0, 0};
};

// The compute path's grid of `pattern` (which must outlive it).
SampleGrid compute_grid(const SamplePattern& pattern) {
  SampleGrid grid{kSubpixelOne, &pattern, pattern.offsets[0], pattern.offsets[0]};
  for (const FixedPoint& o : pattern.offsets) {
    grid.first = {std::min(grid.first.x, o.x), std::min(grid.first.y, o.y)};
    grid.last = {std::max(grid.last.x, o.x), std::max(grid.last.y, o.y)};
  }
  return grid;
}

struct RasterTriangle {
  FixedPoint v[3];  // positively oriented
  double depth[3];  // near / w
  int64_t box_min_x, box_min_y, box_max_x, box_max_y;
  uint32_t id;
  uint32_t slot;  // its object's
};

// Snaps to `grid`, culls by facing and area, and computes the box of pixels that may hold a
// covered sample; false if nothing remains. `mirrored`: the object's transform has a negative
// determinant.
bool make_raster_triangle(const CameraModel& cam, CullMode cull, dvec4 c0, dvec4 c1, dvec4 c2,
                          uint32_t id, bool mirrored, SampleGrid grid, RasterTriangle& t) {
  const dvec4 c[3] = {c0, c1, c2};
  FixedPoint v[3];
  double d[3];
  const double one = double(grid.one);
  for (int k = 0; k < 3; ++k) {
    dvec2 p = to_pixels(cam, c[k]);
    v[k] = {int64_t(std::floor(p.x * one + 0.5)), int64_t(std::floor(p.y * one + 0.5))};
    d[k] = cam.near_plane / c[k].w;
  }
  const int64_t area = edge(v[0], v[1], v[2]);
  if (area == 0) return false;
  // Counter-clockwise in the world is clockwise in y-down pixels; a mirroring transform has
  // reversed the winding once more, and glTF 2.0 makes its clockwise faces the front ones.
  const bool clockwise = area < 0;
  const bool front = clockwise != mirrored;
  if ((front && cull == CullMode::front) || (!front && cull == CullMode::back)) return false;
  const int second = clockwise ? 2 : 1, third = clockwise ? 1 : 2;
  t.v[0] = v[0];
  t.v[1] = v[second];
  t.v[2] = v[third];
  t.depth[0] = d[0];
  t.depth[1] = d[second];
  t.depth[2] = d[third];
  t.id = id;
  int64_t lo_x = std::min({v[0].x, v[1].x, v[2].x}), hi_x = std::max({v[0].x, v[1].x, v[2].x});
  int64_t lo_y = std::min({v[0].y, v[1].y, v[2].y}), hi_y = std::max({v[0].y, v[1].y, v[2].y});
  if (!grid.compute) {  // any pixel the snapped box touches
    t.box_min_x = std::max<int64_t>(floor_div(lo_x, grid.one), 0);
    t.box_min_y = std::max<int64_t>(floor_div(lo_y, grid.one), 0);
    t.box_max_x = std::min<int64_t>(floor_div(hi_x, grid.one), int64_t(cam.width) - 1);
    t.box_max_y = std::min<int64_t>(floor_div(hi_y, grid.one), int64_t(cam.height) - 1);
    return t.box_min_x <= t.box_max_x && t.box_min_y <= t.box_max_y;
  }
  // The compute path's box and its test of small boxes (prepare_triangle, setup_common.glsl),
  // so that both count the same raster triangles (ReferenceFrame::raster_triangles): pixel x
  // holds samples from x * one + first to x * one + last.
  const FixedPoint first = grid.first, last = grid.last;
  t.box_min_x = std::max<int64_t>(floor_shift(lo_x - last.x + kSubpixelOne - 1), 0);
  t.box_min_y = std::max<int64_t>(floor_shift(lo_y - last.y + kSubpixelOne - 1), 0);
  t.box_max_x = std::min<int64_t>(floor_shift(hi_x - first.x), int64_t(cam.width) - 1);
  t.box_max_y = std::min<int64_t>(floor_shift(hi_y - first.y), int64_t(cam.height) - 1);
  if (t.box_min_x > t.box_max_x || t.box_min_y > t.box_max_y) return false;
  if (t.box_max_x - t.box_min_x > 1 || t.box_max_y - t.box_min_y > 1) return true;
  // A box of up to 2 x 2 pixels: kept only if it covers a sample (slivers and sub-pixel
  // triangles often cover none), as rasterize_rows and rasterize_samples test them.
  const int64_t th0 = edge_threshold(t.v[1], t.v[2]);
  const int64_t th1 = edge_threshold(t.v[2], t.v[0]);
  const int64_t th2 = edge_threshold(t.v[0], t.v[1]);
  for (int64_t y = t.box_min_y; y <= t.box_max_y; ++y) {
    for (int64_t x = t.box_min_x; x <= t.box_max_x; ++x) {
      for (const FixedPoint& o : grid.compute->offsets) {
        const FixedPoint p{x * kSubpixelOne + o.x, y * kSubpixelOne + o.y};
        if (edge(t.v[1], t.v[2], p) >= th0 && edge(t.v[2], t.v[0], p) >= th1 &&
            edge(t.v[0], t.v[1], p) >= th2)
          return true;
      }
    }
  }
  return false;
}

std::array<dvec4, 3> clip_coords(const CameraModel& cam, const Instance& inst, uint64_t id) {
  const auto idx = corner_indices(inst, id);
  const dmat4 to_clip = cam.view_proj * inst.model;
  return {to_clip * dvec4(dvec3(inst.mesh->positions[idx[0]]), 1.0),
          to_clip * dvec4(dvec3(inst.mesh->positions[idx[1]]), 1.0),
          to_clip * dvec4(dvec3(inst.mesh->positions[idx[2]]), 1.0)};
}

void setup_triangle(const CameraModel& cam, CullMode cull, const Instance& inst, uint64_t id,
                    SampleGrid grid, std::vector<RasterTriangle>& out) {
  const std::array<dvec4, 3> c = clip_coords(cam, inst, id);
  const CullMode facing_cull = inst.material->double_sided ? CullMode::none : cull;
  RasterTriangle t;
  t.slot = inst.slot;
  bool inside = true;
  for (const dvec4& v : c) {
    for (int plane = 0; plane < 5; ++plane) inside = inside && plane_distance(cam, v, plane) >= 0;
  }
  if (inside) {
    if (make_raster_triangle(cam, facing_cull, c[0], c[1], c[2], uint32_t(id), inst.mirrored, grid,
                             t))
      out.push_back(t);
    return;
  }
  std::vector<dvec4> poly = clipped_polygon(cam, c);
  for (size_t k = 1; k + 1 < poly.size(); ++k) {
    if (make_raster_triangle(cam, facing_cull, poly[0], poly[k], poly[k + 1], uint32_t(id),
                             inst.mirrored, grid, t))
      out.push_back(t);
  }
}

// Rasterizes every triangle into rows [y0, y1): nearest depth wins, ties to the lower id.
void rasterize_rows(const std::vector<RasterTriangle>& tris, uint32_t width, int64_t y0, int64_t y1,
                    ReferenceFrame& f) {
  for (const RasterTriangle& t : tris) {
    const int64_t ya = std::max(t.box_min_y, y0), yb = std::min(t.box_max_y, y1 - 1);
    if (ya > yb) continue;
    const int64_t th0 = edge_threshold(t.v[1], t.v[2]);
    const int64_t th1 = edge_threshold(t.v[2], t.v[0]);
    const int64_t th2 = edge_threshold(t.v[0], t.v[1]);
    for (int64_t y = ya; y <= yb; ++y) {
      for (int64_t x = t.box_min_x; x <= t.box_max_x; ++x) {
        const FixedPoint p{x * kSubpixelOne + kSubpixelOne / 2,
                           y * kSubpixelOne + kSubpixelOne / 2};
        const int64_t e0 = edge(t.v[1], t.v[2], p), e1 = edge(t.v[2], t.v[0], p),
                      e2 = edge(t.v[0], t.v[1], p);
        if (e0 < th0 || e1 < th1 || e2 < th2) continue;
        const size_t i = size_t(y) * width + size_t(x);
        f.coverage[i]++;
        // Screen-space barycentrics interpolate near / w exactly: it is affine in the image.
        const double d =
            (double(e0) * t.depth[0] + double(e1) * t.depth[1] + double(e2) * t.depth[2]) /
            double(e0 + e1 + e2);
        if (d > f.depth[i] || (d == f.depth[i] && t.id < f.owner[i])) {
          f.depth[i] = d;
          f.owner[i] = t.id;
        }
      }
    }
  }
}

}  // namespace
namespace {

// Reflected radiance towards v from light arriving along l with radiance `incident`, with or
// without energy compensation.
dvec3 reflected(Brdf variant, dvec3 n, dvec3 v, dvec3 l, const Material& m, dvec3 incident,
                bool energy_compensation) {
  const double n_dot_l = glm::dot(n, l);
  if (n_dot_l <= 0.0) return dvec3(0.0);
  const BrdfLobes lobes = energy_compensation ? reference_compensated_lobes(variant, n, v, l, m)
                                              : reference_brdf_lobes(variant, n, v, l, m);
  return (lobes.diffuse + lobes.specular) * incident * n_dot_l;
}

// Incident radiance scale of a light with a position at squared distance d2 (its Falloff).
double distance_attenuation(const Light& light, double d2) {
  if (light.falloff == Falloff::classic) {
    const glm::dvec3 k(light.attenuation);
    return 1.0 / std::max(k.x + k.y * std::sqrt(d2) + k.z * d2, TS_MIN_ATTENUATION_DENOMINATOR);
  }
  double a = 1.0 / std::max(d2, TS_MIN_LIGHT_DISTANCE_SQUARED);  // inverse square
  if (light.range > 0.0f) {
    const double r = light.range;
    const double fade = std::clamp(1.0 - (d2 * d2) / (r * r * r * r), 0.0, 1.0);
    a *= fade * fade;  // Karis 2013 window
  }
  return a;
}

// The light arriving at a surface point from one light: unit direction l towards it and the
// incident radiance along l. One case per LightKind.
struct LightArrival {
  dvec3 l, incident;
};
LightArrival light_arrival(const Light& light, dvec3 position, dvec3 normal) {
  const dvec3 power = dvec3(light.color) * double(light.intensity);
  if (light.kind == LightKind::directional) return {-glm::normalize(dvec3(light.direction)), power};
  const dvec3 to_light = dvec3(light.position) - position;
  const double d2 = glm::dot(to_light, to_light);
  const dvec3 l = d2 > 0.0 ? to_light / std::sqrt(d2) : normal;
  double a = distance_attenuation(light, d2);
  if (light.kind == LightKind::spot) {
    const double cos_inner = std::cos(double(light.inner_angle)),
                 cos_outer = std::cos(double(light.outer_angle));
    const double c = glm::dot(glm::normalize(dvec3(light.direction)), -l);
    const double t = std::clamp(
        (c - cos_outer) / std::max(cos_inner - cos_outer, TS_MIN_SPOT_COSINE_GAP), 0.0, 1.0);
    a *= t * t;
  }
  return {l, power * a};
}

struct Surface {
  dvec3 position, normal;
  dvec2 uv;
  dvec2 duv_dx, duv_dy;         // uv change for one pixel step right and down (ray differentials)
  dvec2 uv1, duv1_dx, duv1_dy;  // the same of uv set 1, if the mesh has it (else set 0's)
  glm::dvec4 tangent;           // world tangent (unnormalised) and handedness, if the mesh has them
};

// Unclamped barycentrics of the hit of the ray (origin, dir) on the plane of p0 p1 p2 by
// Cramer's rule; false if the ray is parallel to the plane.
bool plane_barycentrics(const dvec3 p[3], dvec3 origin, dvec3 dir, dvec3& b) {
  const dvec3 e1 = p[1] - p[0], e2 = p[2] - p[0], s = origin - p[0];
  const dvec3 q = glm::cross(dir, e2);
  const double det = glm::dot(e1, q);
  if (det == 0.0 || !std::isfinite(1.0 / det)) return false;
  const double u = glm::dot(s, q) / det;
  const double v = glm::dot(dir, glm::cross(s, e1)) / det;
  b = dvec3(1.0 - u - v, u, v);
  return true;
}

// The point of the triangle seen through the pixel: barycentrics of the ray's hit on its plane
// by Cramer's rule, clamped to the triangle (snapping can cover a centre just outside it).
Surface surface_at(const Instance& inst, uint64_t id, dvec3 origin, dvec3 dir, dvec3 dir_dx,
                   dvec3 dir_dy) {
  const auto idx = corner_indices(inst, id);
  dvec3 p[3], n[3];
  dvec2 uv[3], uv1[3];
  const bool has_uv1 = !inst.mesh->uvs1.empty(), has_uv = !inst.mesh->uvs.empty();
  for (int k = 0; k < 3; ++k) {
    uv1[k] = has_uv1 ? dvec2(inst.mesh->uvs1[idx[k]]) : dvec2(0.0);
    p[k] = dvec3(inst.model * dvec4(dvec3(inst.mesh->positions[idx[k]]), 1.0));
    n[k] = inst.normal_matrix * dvec3(inst.mesh->normals[idx[k]]);
    uv[k] = has_uv ? dvec2(inst.mesh->uvs[idx[k]]) : dvec2(0.0);
  }
  const dvec3 e1 = p[1] - p[0], e2 = p[2] - p[0], s = origin - p[0];
  const dvec3 q = glm::cross(dir, e2);
  const double det = glm::dot(e1, q);
  dvec3 b(1.0 / 3.0);
  if (det != 0.0 && std::isfinite(1.0 / det)) {
    const double u = glm::dot(s, q) / det;
    const double v = glm::dot(dir, glm::cross(s, e1)) / det;
    b = glm::max(dvec3(1.0 - u - v, u, v), dvec3(0.0));
    b /= b.x + b.y + b.z;
  }
  Surface out;
  out.position = b.x * p[0] + b.y * p[1] + b.z * p[2];
  const dvec3 normal = b.x * n[0] + b.y * n[1] + b.z * n[2];
  const double length2 = glm::dot(normal, normal);
  out.normal = length2 > 1e-20 ? normal / std::sqrt(length2) : glm::normalize(glm::cross(e1, e2));
  // Texture footprint: where the neighbouring pixels' rays meet the triangle's plane. A ray
  // parallel to the plane gives an infinite footprint (the coarsest mip level).
  const double inf = std::numeric_limits<double>::infinity();
  dvec3 bx, by;
  const bool has_dx = plane_barycentrics(p, origin, dir_dx, bx);
  const bool has_dy = plane_barycentrics(p, origin, dir_dy, by);
  const auto footprint = [&](const dvec2 t[3], dvec2& at, dvec2& d_dx, dvec2& d_dy) {
    at = b.x * t[0] + b.y * t[1] + b.z * t[2];
    d_dx = has_dx ? bx.x * t[0] + bx.y * t[1] + bx.z * t[2] - at : dvec2(inf);
    d_dy = has_dy ? by.x * t[0] + by.y * t[1] + by.z * t[2] - at : dvec2(inf);
  };
  footprint(uv, out.uv, out.duv_dx, out.duv_dy);
  footprint(has_uv1 ? uv1 : uv, out.uv1, out.duv1_dx, out.duv1_dy);
  out.tangent = glm::dvec4(0.0);
  if (inst.tangents) {
    const glm::dmat3 model3(inst.model);
    dvec3 t(0.0);
    for (int k = 0; k < 3; ++k) t += b[k] * (model3 * dvec3(glm::vec3((*inst.tangents)[idx[k]])));
    // A mirroring transform flips the handedness of the tangent frame.
    const double w = (*inst.tangents)[idx[0]].w * (inst.mirrored ? -1.0 : 1.0);
    out.tangent = glm::dvec4(t, w);
  }
  // A double-sided material's back face is shaded as a front face turned toward the viewer
  // (glTF 2.0 3.9.5): normal and tangent frame flipped, the bitangent too through w. Front
  // faces wind counter-clockwise seen from the camera, clockwise if mirrored.
  const bool back = (glm::dot(glm::cross(e1, e2), dir) > 0.0) != inst.mirrored;
  if (back && inst.material->double_sided) {
    out.normal = -out.normal;
    out.tangent = -out.tangent;
  }
  return out;
}

// What a pixel's shading reads besides the scene.
struct ShadeContext {
  const Scene& scene;
  const CameraModel& cam;
  const std::vector<Instance>& instances;
  const std::vector<MipChain>& chains;  // per Scene::textures
  const ReferenceSettings& settings;
};

// The material at the surface point with its texture maps applied, and the shading normal
// (normal-mapped when the material has a normal map).
Material resolve_material(const ShadeContext& c, const Material& base, Surface& s, dvec3 v) {
  Material m = base;
  // Map `bit` (texture `map`) through the uv set it reads (Material::uv1_maps).
  auto sample = [&](uint32_t map, uint32_t bit) {
    const bool set1 = (base.uv1_maps & bit) != 0u;
    return sample_texture(c.chains[map], set1 ? s.uv1 : s.uv, set1 ? s.duv1_dx : s.duv_dx,
                          set1 ? s.duv1_dy : s.duv_dy, c.settings.frame.max_anisotropy);
  };
  if (m.base_color_map != kNoTexture) {
    m.base_color *= glm::vec3(sample(m.base_color_map, TS_MAP_BASE_COLOR));
  }
  if (m.metallic_roughness_map != kNoTexture) {
    const glm::dvec4 t = sample(m.metallic_roughness_map, TS_MAP_METALLIC_ROUGHNESS);
    m.roughness = float(m.roughness * t.g);
    m.metallic = float(m.metallic * t.b);
  }
  if (m.occlusion_map != kNoTexture) {
    m.occlusion = float(m.occlusion * sample(m.occlusion_map, TS_MAP_OCCLUSION).r);
  }
  if (m.emissive_map != kNoTexture) {
    m.emissive *= glm::vec3(sample(m.emissive_map, TS_MAP_EMISSIVE));
  }
  if (m.normal_map != kNoTexture) {
    const glm::dvec4 t = sample(m.normal_map, TS_MAP_NORMAL);
    const dvec3 local(dvec2(t) * 2.0 - 1.0, t.z * 2.0 - 1.0);
    const dvec3 n = s.normal;
    dvec3 tangent = dvec3(s.tangent) - n * glm::dot(n, dvec3(s.tangent));
    const double t2 = glm::dot(tangent, tangent);
    if (t2 > 1e-20) {
      tangent /= std::sqrt(t2);
      const dvec3 bitangent = s.tangent.w * glm::cross(n, tangent);
      const dvec3 mapped = tangent * (local.x * base.normal_scale) +
                           bitangent * (local.y * base.normal_scale) + n * local.z;
      const double m2 = glm::dot(mapped, mapped);
      if (m2 > 1e-20) {
        dvec3 nm = mapped / std::sqrt(m2);
        const double nv = glm::dot(nm, v);
        if (nv < TS_MIN_MAPPED_N_DOT_V) nm = glm::normalize(nm + v * (TS_MIN_MAPPED_N_DOT_V - nv));
        s.normal = nm;
      }
    }
  }
  return m;
}

// Radiance towards the camera from surface point `s` of triangle-instance `id` of `inst`,
// seen along the unit ray `dir`.
dvec3 shade_surface(const ShadeContext& c, const Instance& inst, uint64_t id, Surface s,
                    dvec3 dir) {
  const Scene& scene = c.scene;
  const Brdf brdf = c.settings.frame.brdf;
  const Material m = resolve_material(c, *inst.material, s, -dir);
  switch (c.settings.frame.view) {
    case View::normal:
      return s.normal * 0.5 + 0.5;
    case View::uv:
      return dvec3(s.uv, 0.0);
    case View::triangle:
      return dvec3(id_colour(uint32_t(id)));
    case View::object:
      return dvec3(id_colour(inst.slot));
    case View::shaded:
      break;
  }
  const dvec3 v = -dir;
  dvec3 color =
      dvec3(scene.ambient) * dvec3(m.base_color) * double(m.occlusion) + dvec3(m.emissive);
  for (const Light& light : scene.lights) {
    const LightArrival a = light_arrival(light, s.position, s.normal);
    color += reflected(brdf, s.normal, v, a.l, m, a.incident, c.settings.frame.energy_compensation);
  }
  if (scene.environment) {
    color += double(m.occlusion) *
             reference_environment_light(*scene.environment, brdf, s.normal, v, m, dvec3(1.0),
                                         c.settings.environment_samples,
                                         c.settings.frame.energy_compensation);
  }
  return color;
}

dvec3 shade_pixel(const ShadeContext& c, uint64_t id, uint32_t x, uint32_t y) {
  const Instance& inst = instance_of(c.instances, id);
  const dvec3 dir = camera_ray(c.cam, x, y);
  const Surface s =
      surface_at(inst, id, c.cam.position, dir, camera_ray_at(c.cam, x + 1.5, y + 0.5),
                 camera_ray_at(c.cam, x + 0.5, y + 1.5));
  return shade_surface(c, inst, id, s, dir);
}

// --- Resolve -------------------------------------------------------------------------------

double tone_curve(double x, ToneMap op) {
  switch (op) {
    case ToneMap::aces:  // Narkowicz 2015, fit of the ACES RRT + ODT
      return std::clamp(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
    case ToneMap::reinhard:
      return x / (1.0 + x);  // Reinhard et al. 2002
    case ToneMap::clamp:
      break;
  }
  return std::clamp(x, 0.0, 1.0);
}

double srgb_encode(double linear) {  // IEC 61966-2-1
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

// Calls fn(y0, y1) over blocks of rows that together cover [0, height), on `threads` threads.
// Blocks are handed out as threads free up: rows cost very unequal amounts (sky against
// textured spheres), and with one contiguous share per thread the others idle while the one
// holding the costly rows works. About 8 blocks per thread keep the per-call setup (the plain
// path walks every triangle per call) small.
template <typename Fn>
void parallel_rows(uint32_t height, unsigned threads, Fn&& fn) {
  threads = std::max(1u, std::min(threads, height));
  const uint32_t block = std::max(1u, height / (threads * 8u));
  std::atomic<uint32_t> next{0};
  auto work = [&] {
    for (uint32_t y0; (y0 = next.fetch_add(block)) < height;) fn(y0, std::min(height, y0 + block));
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (std::thread& th : pool) th.join();
}

// The display pixel of linear radiance `c`: pre-exposure, as the compute path (the exposed
// value meets the fp16 clamp, and the HDR output divides the exposure back out), tone curve,
// sRGB.
void resolve_pixel(const FrameSettings& frame, dvec3 c, glm::vec4& hdr, glm::u8vec4& ldr) {
  const bool shaded = frame.view == View::shaded;
  const double exposure = shaded ? std::exp2(double(frame.exposure_ev)) : 1.0;
  const ToneMap op = shaded ? frame.tonemap : ToneMap::clamp;
  const dvec3 exposed = glm::min(c * exposure, dvec3(hdr_max(frame.hdr_format)));
  hdr = glm::vec4(glm::vec3(exposed / exposure), 1.0f);
  ldr = glm::u8vec4(0, 0, 0, 255);
  for (int ch = 0; ch < 3; ++ch) {
    const double display = srgb_encode(tone_curve(std::max(exposed[ch], 0.0), op));
    ldr[ch] = uint8_t(std::floor(std::clamp(display, 0.0, 1.0) * 255.0 + 0.5));
  }
}

// Radiance of a ray that meets no surface.
dvec3 miss_radiance(const Scene& scene, const ReferenceSettings& settings, dvec3 dir) {
  if (scene.environment && settings.frame.view == View::shaded)
    return environment_radiance(*scene.environment, dir);
  return dvec3(scene.background);
}

// --- Ground truth (GroundTruthOptions) -------------------------------------------------------

// Fixed-point units per pixel of the ground truth's snapping: vertices move by at most
// 1/8192 px, far below the errors it measures, and edge products of coordinates within the
// guard band (2^28 units) stay within int64.
constexpr int64_t kTruthOne = 4096;

// The ground truth's N x N grid: sample (i, j) at ((i + 0.5) / N, (j + 0.5) / N) rounded to
// 1/kTruthOne px, numbered j * N + i.
SamplePattern truth_pattern(uint32_t n) {
  SamplePattern p{kTruthOne, {}};
  std::vector<int64_t> steps(n);
  for (uint32_t i = 0; i < n; ++i)
    steps[i] = int64_t(std::floor((i + 0.5) / n * double(kTruthOne) + 0.5));
  for (uint32_t j = 0; j < n; ++j) {
    for (uint32_t i = 0; i < n; ++i) p.offsets.push_back({steps[i], steps[j]});
  }
  return p;
}

// An object drawn as the exact ellipsoid its transform makes of its mesh's sphere.
struct AnalyticObject {
  const Instance* inst;
  dmat4 to_object;  // world -> object
  dvec3 centre;
  double radius, u_at_plus_x;
  bool front_visible, back_visible;                    // not culled by facing
  int64_t box_min_x, box_min_y, box_max_x, box_max_y;  // pixels its projection may touch
};

AnalyticObject make_analytic_object(const CameraModel& cam, CullMode cull, const Instance& inst) {
  const AnalyticSphere& sphere = *inst.mesh->analytic_sphere;
  AnalyticObject a{&inst,
                   glm::inverse(inst.model),
                   dvec3(sphere.centre),
                   double(sphere.radius),
                   double(sphere.u_at_plus_x),
                   true,
                   true,
                   0,
                   0,
                   int64_t(cam.width) - 1,
                   int64_t(cam.height) - 1};
  // The outside is the front, mirrored or not: a mirroring transform reverses the winding
  // and the rule for which winding is in front alike.
  if (!inst.material->double_sided) {
    a.front_visible = cull != CullMode::front;
    a.back_visible = cull != CullMode::back;
  }
  // Box: the projection of the cube around the sphere, which holds the ellipsoid, is the hull
  // of its corners' projections while all are in front of the camera.
  dvec2 lo(std::numeric_limits<double>::infinity()), hi(-lo);
  for (int k = 0; k < 8; ++k) {
    const dvec3 corner =
        a.centre + a.radius * dvec3(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1);
    const dvec4 c = cam.view_proj * inst.model * dvec4(corner, 1.0);
    if (!(c.w > 0.0)) return a;  // reaches behind the camera: the whole image
    const dvec2 p = to_pixels(cam, c);
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  a.box_min_x = int64_t(std::max(std::floor(lo.x), 0.0));
  a.box_min_y = int64_t(std::max(std::floor(lo.y), 0.0));
  a.box_max_x = int64_t(std::min(std::floor(hi.x), cam.width - 1.0));
  a.box_max_y = int64_t(std::min(std::floor(hi.y), cam.height - 1.0));
  return a;
}

// The ray parameters where `origin + t dir` enters and leaves the ellipsoid, t_in <= t_out;
// false if it misses. In object space the ellipsoid is the sphere, and t is the same there
// because the transform is affine.
bool ellipsoid_hits(const AnalyticObject& a, dvec3 origin, dvec3 dir, double& t_in, double& t_out) {
  const dvec3 o = dvec3(a.to_object * dvec4(origin, 1.0)) - a.centre;
  const dvec3 d = dmat3(a.to_object) * dir;
  const double qa = glm::dot(d, d), qb = glm::dot(o, d), qc = glm::dot(o, o) - a.radius * a.radius;
  const double disc = qb * qb - qa * qc;
  if (!(disc >= 0.0) || qa == 0.0) return false;
  // The root formula without cancellation between qb and the square root (pbrt-v4, 6.2.2).
  const double q = -(qb + std::copysign(std::sqrt(disc), qb));
  if (q == 0.0) {  // the origin on the surface, the ray tangent to it
    t_in = t_out = 0.0;
    return true;
  }
  t_in = q / qa;
  t_out = qc / q;
  if (t_in > t_out) std::swap(t_in, t_out);
  return true;
}

// The surface point of the analytic object at ray parameter t, with make_uv_sphere's uv
// parametrisation, its footprint from the neighbouring rays' hits on the tangent plane, and
// the tangent along +u. `back`: the ray leaves the ellipsoid there.
Surface analytic_surface(const AnalyticObject& a, dvec3 origin, dvec3 dir, double t, bool back,
                         dvec3 dir_dx, dvec3 dir_dy) {
  const Instance& inst = *a.inst;
  auto uv_of = [&](dvec3 world) {
    const dvec3 n = glm::normalize(dvec3(a.to_object * dvec4(world, 1.0)) - a.centre);
    const double u = std::atan2(-n.z, n.x) / (2.0 * std::numbers::pi) + a.u_at_plus_x;
    return dvec2(u - std::floor(u), std::acos(std::clamp(n.y, -1.0, 1.0)) / std::numbers::pi);
  };
  Surface s;
  s.position = origin + t * dir;
  const dvec3 n_object = (dvec3(a.to_object * dvec4(s.position, 1.0)) - a.centre) / a.radius;
  s.normal = glm::normalize(inst.normal_matrix * n_object);
  s.uv = uv_of(s.position);
  const double inf = std::numeric_limits<double>::infinity();
  auto footprint = [&](dvec3 d) {
    const double denom = glm::dot(s.normal, d);
    if (denom == 0.0) return dvec2(inf);
    const double tp = glm::dot(s.normal, s.position - origin) / denom;
    dvec2 delta = uv_of(origin + tp * d) - s.uv;
    delta.x -= std::round(delta.x);  // across the seam, the short way round
    return delta;
  };
  s.duv_dx = footprint(dir_dx);
  s.duv_dy = footprint(dir_dy);
  s.tangent = glm::dvec4(0.0);
  if (inst.tangents) {
    // d/du of (sin v cos u, cos v, -sin v sin u), up to a positive factor; the frame
    // (t, n x t) has bitangent along -v, hence w = -1, flipped again by a mirroring transform.
    const dvec3 t_object(n_object.z, 0.0, -n_object.x);
    s.tangent = glm::dvec4(dmat3(inst.model) * t_object, inst.mirrored ? 1.0 : -1.0);
  }
  if (back) {  // only visible if double-sided or front faces culled
    if (inst.material->double_sided) {
      s.normal = -s.normal;
      s.tangent = -s.tangent;
    }
  }
  return s;
}

// What one sample sees: the nearest surface (near / w largest, ties to the lower id).
struct SampleHit {
  double depth = 0.0;
  uint32_t id = kNoTriangle;
  uint32_t slot = kNoObject;
  int32_t analytic = -1;  // index into the analytic objects, or -1 for a triangle
  double t = 0.0;         // ray parameter of an analytic hit
  bool back = false;      // an analytic hit on the side facing away
  uint32_t covered = 0;   // surfaces covering the sample, culled ones not counted
};

// Counts a surface covering the sample and keeps it if it is nearer; true if it was kept.
bool keep_nearest(SampleHit& h, double depth, uint32_t id, uint32_t slot) {
  h.covered++;
  if (!(depth > h.depth || (depth == h.depth && id < h.id))) return false;
  h.depth = depth;
  h.id = id;
  h.slot = slot;
  h.analytic = -1;
  return true;
}

// Rasterizes every triangle into the samples of pixel row y (hits[x * n + s] is sample s of
// pixel x, n the pattern's sample count).
void rasterize_samples(const std::vector<RasterTriangle>& tris, int64_t y,
                       const SamplePattern& pattern, std::vector<SampleHit>& hits) {
  const size_t n = pattern.offsets.size();
  for (const RasterTriangle& t : tris) {
    if (y < t.box_min_y || y > t.box_max_y) continue;
    const int64_t th0 = edge_threshold(t.v[1], t.v[2]);
    const int64_t th1 = edge_threshold(t.v[2], t.v[0]);
    const int64_t th2 = edge_threshold(t.v[0], t.v[1]);
    for (int64_t x = t.box_min_x; x <= t.box_max_x; ++x) {
      for (size_t s = 0; s < n; ++s) {
        const FixedPoint p{x * pattern.one + pattern.offsets[s].x,
                           y * pattern.one + pattern.offsets[s].y};
        const int64_t e0 = edge(t.v[1], t.v[2], p), e1 = edge(t.v[2], t.v[0], p),
                      e2 = edge(t.v[0], t.v[1], p);
        if (e0 < th0 || e1 < th1 || e2 < th2) continue;
        const double d =
            (double(e0) * t.depth[0] + double(e1) * t.depth[1] + double(e2) * t.depth[2]) /
            double(e0 + e1 + e2);
        keep_nearest(hits[size_t(x) * n + s], d, t.id, t.slot);
      }
    }
  }
}

// Intersects every analytic object with the rays of the samples of pixel row y.
void intersect_analytic(const CameraModel& cam, const std::vector<AnalyticObject>& objects,
                        int64_t y, const SamplePattern& pattern, std::vector<SampleHit>& hits) {
  const size_t n = pattern.offsets.size();
  for (size_t k = 0; k < objects.size(); ++k) {
    const AnalyticObject& a = objects[k];
    if (y < a.box_min_y || y > a.box_max_y) continue;
    const uint32_t id = uint32_t(a.inst->first_triangle);
    for (int64_t x = a.box_min_x; x <= a.box_max_x; ++x) {
      for (size_t s = 0; s < n; ++s) {
        const dvec2 point = pattern.point(x, y, s);
        const dvec3 dir = camera_ray_at(cam, point.x, point.y);
        double t[2];
        if (!ellipsoid_hits(a, cam.position, dir, t[0], t[1])) continue;
        SampleHit& h = hits[size_t(x) * n + s];
        for (int side = 0; side < 2; ++side) {
          // Kept where the rasterizer keeps triangles: on or beyond the near plane.
          const double w = t[side] * glm::dot(dir, cam.forward);
          if (!(side == 0 ? a.front_visible : a.back_visible) || !(w >= cam.near_plane)) continue;
          if (keep_nearest(h, cam.near_plane / w, id, a.inst->slot)) {
            h.analytic = int32_t(k);
            h.t = t[side];
            h.back = side == 1;
          }
        }
      }
    }
  }
}

// Radiance of one sample at (px, py) in pixels; `step`: the distance to the next sample.
dvec3 shade_sample(const ShadeContext& c, const std::vector<AnalyticObject>& objects,
                   const SampleHit& h, double px, double py, double step) {
  const dvec3 dir = camera_ray_at(c.cam, px, py);
  if (h.id == kNoTriangle) return miss_radiance(c.scene, c.settings, dir);
  const dvec3 dir_dx = camera_ray_at(c.cam, px + step, py),
              dir_dy = camera_ray_at(c.cam, px, py + step);
  if (h.analytic >= 0) {
    const AnalyticObject& a = objects[size_t(h.analytic)];
    return shade_surface(c, *a.inst, h.id,
                         analytic_surface(a, c.cam.position, dir, h.t, h.back, dir_dx, dir_dy),
                         dir);
  }
  const Instance& inst = instance_of(c.instances, h.id);
  return shade_surface(c, inst, h.id, surface_at(inst, h.id, c.cam.position, dir, dir_dx, dir_dy),
                       dir);
}

// Ownership shares of one pixel from its samples' objects (`slots` is reordered).
void append_shares(std::vector<uint32_t>& slots, std::vector<OwnerShare>& out) {
  std::sort(slots.begin(), slots.end());
  for (size_t k = 0; k < slots.size(); ++k) {
    if (k > 0 && slots[k] == slots[k - 1])
      out.back().samples++;
    else
      out.push_back({slots[k], 1});
  }
}

// Pixel i's owner (the id most of its `n` samples `hits` see, ties to the lower id, kNoTriangle
// the highest), the owner's largest depth among them, and the covered samples. `ids` is scratch.
void set_owner(const SampleHit* hits, size_t n, std::vector<std::pair<uint32_t, uint32_t>>& ids,
               size_t i, ReferenceFrame& f) {
  ids.clear();
  for (size_t s = 0; s < n; ++s) {
    f.coverage[i] += hits[s].covered;
    auto it = std::find_if(ids.begin(), ids.end(), [&](auto& p) { return p.first == hits[s].id; });
    if (it == ids.end())
      ids.push_back({hits[s].id, 1});
    else
      it->second++;
  }
  const auto best = std::min_element(ids.begin(), ids.end(), [](auto& a, auto& b) {
    return a.second != b.second ? a.second > b.second : a.first < b.first;
  });
  f.owner[i] = best->first;
  if (f.owner[i] == kNoTriangle) return;
  for (size_t s = 0; s < n; ++s) {
    if (hits[s].id == f.owner[i]) f.depth[i] = std::max(f.depth[i], hits[s].depth);
  }
}

// Triangle instance `id` as the rasterizer saw it, relative to pixel (x, y), in pixels: clipped
// to the near plane and guard band, its corners snapped to the 1/kSubpixelOne px grid (what
// shaders/coverage.glsl rebuilds).
std::vector<dvec2> pixel_polygon(const ShadeContext& c, uint32_t id, int64_t x, int64_t y) {
  const Instance& inst = instance_of(c.instances, id);
  std::vector<dvec2> corners;
  const double one = double(kSubpixelOne);
  for (const dvec4& corner : clipped_polygon(c.cam, clip_coords(c.cam, inst, id))) {
    const dvec2 p = to_pixels(c.cam, corner);
    corners.push_back(dvec2(std::floor(p.x * one + 0.5) - double(x * kSubpixelOne),
                            std::floor(p.y * one + 0.5) - double(y * kSubpixelOne)) /
                      one);
  }
  return corners;
}

// The triangle instances across the three edges of instance `id` (kNoNeighbourId: none), from
// its mesh's adjacency (silhouette coverage).
std::array<uint64_t, 3> neighbours_of(const std::vector<Instance>& instances, uint64_t id) {
  const Instance& inst = instance_of(instances, id);
  TESSERA_CHECK(inst.adjacency != nullptr);
  std::array<uint64_t, 3> out;
  for (size_t e = 0; e < 3; ++e) {
    const uint32_t across = (*inst.adjacency)[size_t(id - inst.first_triangle) * 3 + e];
    out[e] = across == kNoNeighbour ? kNoNeighbourId : inst.first_triangle + across;
  }
  return out;
}

// Renders rows [y0, y1) with the compute path's anti-aliasing (FrameSettings::samples > 1),
// as docs/architecture.md ("Anti-aliasing") states it: each distinct id among a pixel's
// samples, in increasing order with the empty one last, is shaded once, at the pixel centre if
// it holds every sample and else at the mean of its samples' positions; its radiance, exposed
// and clamped to the fp16 maximum as the compute path stores it, is weighted by its share of
// the samples, or, under analytic coverage where they see one triangle and the background, by
// its outline coverage (outline_coverage).
void render_msaa_rows(const ShadeContext& c, const std::vector<RasterTriangle>& tris, uint32_t y0,
                      uint32_t y1, ReferenceFrame& f) {
  const FrameSettings& frame = c.settings.frame;
  const uint32_t w = frame.width, n = frame.samples;
  const SamplePattern pattern = msaa_pattern(n);
  const double exposure = frame.view == View::shaded ? std::exp2(double(frame.exposure_ev)) : 1.0;
  std::vector<SampleHit> hits(size_t(w) * n);
  std::vector<std::pair<uint32_t, uint32_t>> ids;
  std::vector<uint32_t> order(n);
  std::vector<uint32_t> ids_held, held;  // per group of the pixel's triangles
  std::vector<dvec3> colours;
  std::vector<dvec2> empty_points, covered_points;
  for (uint32_t y = y0; y < y1; ++y) {
    std::fill(hits.begin(), hits.end(), SampleHit{});
    rasterize_samples(tris, y, pattern, hits);
    for (uint32_t x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      const SampleHit* px = &hits[size_t(x) * n];
      for (uint32_t s = 0; s < n; ++s) f.sample_ids[i * n + s] = px[s].id;
      set_owner(px, n, ids, i, f);
      for (uint32_t s = 0; s < n; ++s) order[s] = s;
      std::stable_sort(order.begin(), order.end(),
                       [&](uint32_t a, uint32_t b) { return px[a].id < px[b].id; });
      ids_held.clear();
      held.clear();
      colours.clear();
      empty_points.clear();
      covered_points.clear();
      uint32_t empty = 0;
      dvec3 empty_colour(0.0);
      for (uint32_t k = 0; k < n;) {
        uint32_t end = k;
        dvec2 mean(0.0);
        while (end < n && px[order[end]].id == px[order[k]].id) {
          mean += pattern.point(x, y, order[end]);
          (px[order[end]].id == kNoTriangle ? empty_points : covered_points)
              .push_back(pattern.point(x, y, order[end]) - dvec2(x, y));
          ++end;
        }
        const uint32_t count = end - k;
        const dvec2 point = count == n ? dvec2(x + 0.5, y + 0.5) : mean / double(count);
        const dvec3 radiance = shade_sample(c, {}, px[order[k]], point.x, point.y, 1.0);
        const dvec3 stored = glm::min(radiance * exposure, dvec3(hdr_max(frame.hdr_format)));
        const uint32_t id = px[order[k]].id;
        if (id == kNoTriangle) {
          empty = count;
          empty_colour = stored;
        } else {
          ids_held.push_back(id);
          held.push_back(count);
          colours.push_back(stored);
        }
        k = end;
      }
      std::vector<double> weights(held.size() + 1);
      for (size_t g = 0; g < held.size(); ++g) weights[g] = double(held[g]) / n;
      weights.back() = double(empty) / n;
      // Analytic coverage where the samples see one triangle and the background: the
      // triangle's outline coverage if it has an outline edge and an area there.
      if (frame.aa_coverage == AaCoverage::analytic && held.size() == 1 && empty > 0) {
        const double covered =
            outline_coverage(pixel_polygon(c, ids_held[0], x, y), empty_points, covered_points);
        if (covered > 0.0) weights = {covered, 1.0 - covered};
      }
      // Silhouette coverage where they see triangles of one surface and the background: the
      // surface's share, divided among its triangles as their samples are.
      if (frame.aa_coverage == AaCoverage::silhouette && !held.empty() && empty > 0) {
        const double covered = silhouette_coverage(
            std::vector<uint64_t>(ids_held.begin(), ids_held.end()),
            [&](uint64_t id) { return pixel_polygon(c, uint32_t(id), x, y); },
            [&](uint64_t id) { return neighbours_of(c.instances, id); }, TS_SILHOUETTE_TRIANGLES,
            frame.silhouette_steps == 0 ? SIZE_MAX : frame.silhouette_steps);
        if (covered > 0.0) {
          for (size_t g = 0; g < held.size(); ++g)
            weights[g] = covered * (double(held[g]) / double(n - empty));
          weights.back() = 1.0 - covered;
        }
      }
      dvec3 sum(0.0);
      for (size_t g = 0; g < held.size(); ++g) sum += colours[g] * weights[g];
      sum += empty_colour * weights.back();
      resolve_pixel(frame, sum / exposure, f.hdr.pixels[i], f.ldr.pixels[i]);
    }
  }
}

// Renders rows [y0, y1) of the ground truth into f; `shares[y]` receives row y's ownership
// shares, `share_counts` how many each pixel has.
void render_truth_rows(const ShadeContext& c, const std::vector<RasterTriangle>& tris,
                       const std::vector<AnalyticObject>& objects, uint32_t y0, uint32_t y1,
                       std::vector<std::vector<OwnerShare>>& shares,
                       std::vector<uint32_t>& share_counts, ReferenceFrame& f) {
  const uint32_t w = c.settings.frame.width, n = c.settings.ground_truth.supersampling;
  const SamplePattern pattern = truth_pattern(n);
  std::vector<SampleHit> hits(size_t(w) * n * n);
  std::vector<uint32_t> slots(size_t(n) * n);
  std::vector<std::pair<uint32_t, uint32_t>> ids;  // (id, samples)
  for (uint32_t y = y0; y < y1; ++y) {
    std::fill(hits.begin(), hits.end(), SampleHit{});
    rasterize_samples(tris, y, pattern, hits);
    intersect_analytic(c.cam, objects, y, pattern, hits);
    for (uint32_t x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      dvec3 sum(0.0);
      for (uint32_t s = 0; s < n * n; ++s) {
        const SampleHit& h = hits[size_t(x) * n * n + s];
        const dvec2 point = pattern.point(x, y, s);
        sum += shade_sample(c, objects, h, point.x, point.y, 1.0 / n);
        slots[s] = h.slot;
      }
      set_owner(&hits[size_t(x) * n * n], size_t(n) * n, ids, i, f);
      resolve_pixel(c.settings.frame, sum / double(n * n), f.hdr.pixels[i], f.ldr.pixels[i]);
      const size_t before = shares[y].size();
      append_shares(slots, shares[y]);
      share_counts[i] = uint32_t(shares[y].size() - before);
    }
  }
}

void check_size(const ReferenceSettings& settings) {
  if (settings.frame.width == 0 || settings.frame.height == 0 ||
      settings.frame.width > TS_MAX_IMAGE_SIDE || settings.frame.height > TS_MAX_IMAGE_SIDE) {
    throw Error("image size " + std::to_string(settings.frame.width) + "x" +
                std::to_string(settings.frame.height) + " is outside 1.." +
                std::to_string(TS_MAX_IMAGE_SIDE) + " per side");
  }
}

}  // namespace

ReferenceFrame render_reference(const Scene& scene, const ReferenceSettings& settings) {
  validate_scene(scene);
  check_size(settings);
  const GroundTruthOptions& truth = settings.ground_truth;
  if (truth.supersampling < 1 || truth.supersampling > 32) {
    throw Error("supersampling " + std::to_string(truth.supersampling) +
                " is outside 1..32 samples per pixel side");
  }
  const bool ground_truth = truth.analytic_spheres || truth.supersampling > 1;
  validate_samples(settings.frame.samples);
  if (ground_truth && settings.frame.samples > 1) {
    throw Error("anti-aliasing (" + std::to_string(settings.frame.samples) +
                " samples per pixel) and the ground truth's options are exclusive: supersampling "
                "is the ground truth's own anti-aliasing");
  }
  const bool msaa = settings.frame.samples > 1;
  const uint32_t w = settings.frame.width, h = settings.frame.height;
  const size_t pixels = size_t(w) * h;
  const CameraModel cam = make_camera(scene.camera, w, h);
  FrameInstances prepared = frame_instances(scene, settings.frame);
  auto& [numbering, instances, lod_chains, base_of, adjacency] = prepared;
  std::vector<MipChain> chains;
  for (const Texture& t : scene.textures) chains.push_back(build_mip_chain(t));
  std::map<const Mesh*, std::vector<glm::vec4>> generated;  // by the mesh whose vertices they are
  for (Instance& inst : instances) {
    if (inst.material->normal_map == kNoTexture) continue;
    const auto base = base_of.find(inst.mesh);
    const Mesh* vertices = base == base_of.end() ? inst.mesh : base->second;
    if (!vertices->tangents.empty()) {
      inst.tangents = &vertices->tangents;
      continue;
    }
    std::vector<glm::vec4>& t = generated[vertices];
    if (t.empty()) {
      t = generate_tangents(vertices->positions, vertices->normals, vertices->uvs,
                            vertices->indices);
    }
    inst.tangents = &t;
  }
  const ShadeContext context{scene, cam, instances, chains, settings};
  const unsigned threads =
      settings.threads ? settings.threads : std::max(1u, std::thread::hardware_concurrency());

  // One sample and anti-aliasing snap and box triangles like the compute path; the ground
  // truth snaps to its finer grid, its boxes every pixel the snapped box touches.
  const SamplePattern compute_samples = msaa_pattern(msaa ? settings.frame.samples : 1);
  const SampleGrid grid =
      ground_truth ? SampleGrid{kTruthOne, nullptr} : compute_grid(compute_samples);
  std::vector<RasterTriangle> tris;
  std::vector<AnalyticObject> analytic;
  for (const Instance& inst : instances) {
    if (truth.analytic_spheres && inst.mesh->analytic_sphere) {
      analytic.push_back(make_analytic_object(cam, settings.cull, inst));
      continue;
    }
    for (uint64_t t = 0; t < inst.mesh->triangle_count(); ++t) {
      setup_triangle(cam, settings.cull, inst, inst.first_triangle + t, grid, tris);
    }
  }

  ReferenceFrame f;
  f.numbering = numbering;
  f.raster_triangles = tris.size();
  f.owner.assign(pixels, kNoTriangle);
  f.depth.assign(pixels, 0.0);
  f.coverage.assign(pixels, 0);
  f.hdr = {w, h, std::vector<glm::vec4>(pixels)};
  f.ldr = {w, h, std::vector<glm::u8vec4>(pixels)};
  if (ground_truth) {
    std::vector<std::vector<OwnerShare>> shares(h);
    std::vector<uint32_t> share_counts(pixels);
    parallel_rows(h, threads, [&](uint32_t y0, uint32_t y1) {
      render_truth_rows(context, tris, analytic, y0, y1, shares, share_counts, f);
    });
    Ownership& o = f.ownership;
    o = {w, h, truth.supersampling * truth.supersampling, {}, {}};
    o.first.reserve(pixels + 1);
    o.first.push_back(0);
    for (uint32_t count : share_counts) o.first.push_back(o.first.back() + count);
    for (const std::vector<OwnerShare>& row : shares)
      o.shares.insert(o.shares.end(), row.begin(), row.end());
    return f;
  }
  if (msaa) {
    f.sample_ids.assign(pixels * settings.frame.samples, kNoTriangle);
    parallel_rows(h, threads,
                  [&](uint32_t y0, uint32_t y1) { render_msaa_rows(context, tris, y0, y1, f); });
    return f;
  }
  parallel_rows(h, threads, [&](uint32_t y0, uint32_t y1) {
    rasterize_rows(tris, w, y0, y1, f);
    for (uint32_t y = y0; y < y1; ++y) {
      for (uint32_t x = 0; x < w; ++x) {
        const size_t i = size_t(y) * w + x;
        const dvec3 c = f.owner[i] != kNoTriangle
                            ? shade_pixel(context, f.owner[i], x, y)
                            : miss_radiance(scene, settings, camera_ray(cam, x, y));
        resolve_pixel(settings.frame, c, f.hdr.pixels[i], f.ldr.pixels[i]);
      }
    }
  });
  return f;
}

std::vector<uint32_t> object_ids(const ObjectNumbering& numbering,
                                 const std::vector<uint32_t>& triangle_ids) {
  std::vector<uint32_t> out(triangle_ids.size(), kNoObject);
  for (size_t i = 0; i < triangle_ids.size(); ++i) {
    const uint32_t id = triangle_ids[i];
    if (id == kNoTriangle) continue;
    TESSERA_CHECK(id < numbering.triangle_count);
    const auto it = std::upper_bound(numbering.first_triangle.begin(),
                                     numbering.first_triangle.end(), uint64_t(id));
    out[i] = uint32_t(it - numbering.first_triangle.begin() - 1);
  }
  return out;
}

ReferenceProbe probe_reference(const Scene& scene, const ReferenceSettings& settings,
                               uint32_t triangle_id, uint32_t x, uint32_t y) {
  check_size(settings);
  const CameraModel cam = make_camera(scene.camera, settings.frame.width, settings.frame.height);
  FrameInstances prepared = frame_instances(scene, settings.frame);
  auto& [numbering, instances, lod_chains, base_of, adjacency] = prepared;
  TESSERA_CHECK(triangle_id < numbering.triangle_count);
  const Instance& inst = instance_of(instances, triangle_id);

  ReferenceProbe probe{std::numeric_limits<double>::infinity(), 0.0};
  const std::vector<dvec4> poly = clipped_polygon(cam, clip_coords(cam, inst, triangle_id));
  const dvec2 centre(x + 0.5, y + 0.5);
  for (size_t i = 0; i < poly.size(); ++i) {
    const dvec2 a = to_pixels(cam, poly[i]), b = to_pixels(cam, poly[(i + 1) % poly.size()]);
    const dvec2 ab = b - a;
    const double len2 = glm::dot(ab, ab);
    const double t = len2 > 0.0 ? std::clamp(glm::dot(centre - a, ab) / len2, 0.0, 1.0) : 0.0;
    probe.edge_distance_px = std::min(probe.edge_distance_px, glm::length(centre - (a + t * ab)));
  }
  // Depth of the triangle's plane along the pixel's ray.
  const auto idx = corner_indices(inst, triangle_id);
  dvec3 p[3];
  for (int k = 0; k < 3; ++k)
    p[k] = dvec3(inst.model * dvec4(dvec3(inst.mesh->positions[idx[k]]), 1.0));
  const dvec3 dir = camera_ray(cam, x, y);
  const dvec3 normal = glm::cross(p[1] - p[0], p[2] - p[0]);
  const double denom = glm::dot(normal, dir);
  if (denom != 0.0) {
    const double t = glm::dot(normal, p[0] - cam.position) / denom;
    const double w = t * glm::dot(dir, cam.forward);
    if (t > 0.0 && w > 0.0) probe.depth = cam.near_plane / w;
  }
  return probe;
}

}  // namespace tessera
