// Ground truth in the reference renderer: analytic spheres and supersampling
// (GroundTruthOptions), checked against areas and coverages computed by hand.
#include <cmath>
#include <cstdio>
#include <numbers>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "core/check.h"
#include "core/image_metrics.h"
#include "core/mesh.h"
#include "core/procedural_textures.h"
#include "core/reference_renderer.h"

namespace tessera {
namespace {

constexpr double kPi = std::numbers::pi;

// One object of uniform radiance 1 (emissive, nothing else lights it) on black, seen from
// `distance` along +z, so that each pixel's HDR value is the fraction of it the object covers.
Scene emissive_scene(Mesh mesh, glm::mat4 transform, float distance, float vertical_fov) {
  Scene s;
  s.camera.position = {0.0f, 0.0f, distance};
  s.camera.vertical_fov = vertical_fov;
  s.camera.near_plane = 0.01f;
  s.meshes.push_back(std::move(mesh));
  Material m;
  m.base_color = glm::vec3(0.0f);
  m.emissive = glm::vec3(1.0f);
  s.materials.push_back(m);
  s.objects.push_back({0, 0, transform});
  return s;
}

ReferenceSettings truth_settings(uint32_t size, uint32_t supersampling, bool analytic) {
  ReferenceSettings rs;
  rs.frame.width = rs.frame.height = size;
  rs.ground_truth.analytic_spheres = analytic;
  rs.ground_truth.supersampling = supersampling;
  rs.threads = 2;
  return rs;
}

// Pixels of the image object 0 covers, from the ownership and from the radiance.
double covered_area(const ReferenceFrame& f, double* radiance_sum = nullptr) {
  double area = 0.0, sum = 0.0;
  const Ownership& o = f.ownership;
  for (size_t i = 0; i + 1 < o.first.size(); ++i) {
    for (size_t k = o.first[i]; k < o.first[i + 1]; ++k)
      if (o.shares[k].object == 0) area += double(o.shares[k].samples) / o.samples;
    sum += f.hdr.pixels[i].r;
  }
  if (radiance_sum) *radiance_sum = sum;
  return area;
}

// A stratified N x N count of a convex region of diameter d px errs by at most the area of
// the sub-cells its outline crosses: each monotone quarter of the outline crosses at most
// (d/2) N + 1 columns plus rows of sub-cells, each of area 1/N^2.
double stratified_area_bound(double diameter_px, uint32_t n) {
  return 4.0 * (diameter_px * n + 2.0) / (double(n) * n);
}

TEST(GroundTruth, AnalyticEllipsoidAreaMatchesItsProjection) {
  // The cone from the eye at distance D tangent to the ellipsoid x^2/a^2 + y^2/b^2 + z^2/c^2
  // = 1 touches it in the plane z = c^2 / D, where x^2/a^2 + y^2/b^2 = 1 - c^2/D^2; projected
  // onto the plane at distance 1 that is the ellipse of semi-axes a / sqrt(D^2 - c^2) and
  // b / sqrt(D^2 - c^2) (for a sphere, tan of its angular radius). Rotating about the view
  // axis keeps the area.
  const double a = 1.5, b = 0.75, c = 1.2, distance = 5.0;
  const uint32_t size = 64, n = 8;
  const float fov = glm::radians(40.0f);
  const double scale = (size / 2.0) / std::tan(double(fov) / 2.0);  // px per unit at distance 1
  const double s = std::sqrt(distance * distance - c * c);
  const double rx = a / s * scale, ry = b / s * scale;
  const double expected = kPi * rx * ry;
  glm::mat4 transform = glm::rotate(glm::mat4(1.0f), 0.4f, glm::vec3(0, 0, 1));
  transform = glm::scale(transform, glm::vec3(float(a), float(b), float(c)));
  const Scene scene = emissive_scene(make_uv_sphere(16, 8), transform, float(distance), fov);
  const ReferenceFrame f = render_reference(scene, truth_settings(size, n, true));
  double radiance = 0.0;
  const double area = covered_area(f, &radiance);
  const double bound = stratified_area_bound(2.0 * rx, n);
  EXPECT_NEAR(area, expected, bound) << "ellipse of " << rx << " x " << ry << " px";
  std::printf("GROUND_TRUTH ellipse area %.3f px^2, expected %.3f, bound %.1f\n", area, expected,
              bound);
  EXPECT_NEAR(radiance, area, 1e-3);  // radiance 1 where covered: the box filter integrates it
  // An 8-segment mesh is smaller by far more than the bound (its outline is an inscribed
  // octagon, 10 % less area).
  const Scene coarse = emissive_scene(make_uv_sphere(8, 4), transform, float(distance), fov);
  const ReferenceFrame tess = render_reference(coarse, truth_settings(size, n, false));
  EXPECT_LT(covered_area(tess), expected - 2.0 * bound);
}

TEST(GroundTruth, TessellationSilhouetteErrorFollowsTheChordError) {
  // Seen across its axis from afar, make_uv_sphere(s, s/2)'s outline is the regular s-gon
  // inscribed in the sphere's (the meridian facing the camera). Each of its sides leaves a
  // circular segment of angle beta = 2 pi / s outside, whose chord error (sagitta) is
  // r (1 - cos(pi / s)) and whose mean width, area / arc, is r (beta - sin beta) / (2 beta),
  // two thirds of the chord error as s grows. That mean width is what silhouette_error
  // measures between the tessellated and the analytic sphere.
  const uint32_t size = 64, n = 8;
  const float distance = 200.0f, fov = glm::radians(0.8f);
  const double scale = (size / 2.0) / std::tan(double(fov) / 2.0);
  const double r_circle = scale / std::sqrt(double(distance) * distance - 1.0);
  const double r_polygon = scale / double(distance);  // the meridian lies in the plane z = 0
  const Scene analytic_scene =
      emissive_scene(make_uv_sphere(16, 8), glm::mat4(1.0f), distance, fov);
  const ReferenceFrame truth = render_reference(analytic_scene, truth_settings(size, n, true));
  double previous = 1e9;
  for (uint32_t segments : {8u, 16u, 32u, 64u}) {
    const double beta = 2.0 * kPi / segments;
    const double chord_error = r_circle * (1.0 - std::cos(kPi / segments));
    const double polygon_area = segments / 2.0 * r_polygon * r_polygon * std::sin(beta);
    const double predicted = (kPi * r_circle * r_circle - polygon_area) / (2.0 * kPi * r_circle);
    const Scene tess_scene =
        emissive_scene(make_uv_sphere(segments, segments / 2), glm::mat4(1.0f), distance, fov);
    const ReferenceFrame tess = render_reference(tess_scene, truth_settings(size, n, false));
    const SilhouetteError e = silhouette_error(tess.ownership, truth.ownership);
    // The outline's length, measured on the supersampled truth, is the circle's within 3 %.
    EXPECT_NEAR(e.length_px, 2.0 * kPi * r_circle, 0.03 * 2.0 * kPi * r_circle);
    // Within 10 %, plus what N x N samples can resolve of a sliver (1/N^2 px^2 per sub-cell
    // on the outline, ~2 per sub-cell of length, errors of random sign: well under 0.01 px).
    EXPECT_NEAR(e.mean_px, predicted, 0.1 * predicted + 0.005)
        << segments << " segments, chord error " << chord_error << " px";
    EXPECT_LT(e.mean_px, chord_error);
    std::printf(
        "GROUND_TRUTH uv sphere %u segments, r %.2f px: chord error %.4f px, mean "
        "silhouette error %.4f px (predicted %.4f), outline %.2f px (circle %.2f)\n",
        segments, r_circle, chord_error, e.mean_px, predicted, e.length_px, 2.0 * kPi * r_circle);
    EXPECT_EQ(e.worst_object, 0u);
    EXPECT_NEAR(e.worst_object_px, e.mean_px, 1e-9);  // one object against the background
    EXPECT_LT(e.mean_px, previous / 3.0);             // halving the angle quarters the error
    previous = e.mean_px;
  }
}

// A triangle filling the half-plane right of the line through the origin along `direction`
// (in z = 0), far beyond the view.
Mesh half_plane(glm::vec2 direction) {
  const glm::vec2 d = glm::normalize(direction), right(d.y, -d.x);
  Mesh m;
  const glm::vec2 corners[3] = {-50.0f * d, 50.0f * right, 50.0f * d};
  for (glm::vec2 p : corners) {
    m.positions.push_back(glm::vec3(p, 0.0f));
    m.normals.push_back({0.0f, 0.0f, 1.0f});
    m.uvs.push_back({0.0f, 0.0f});
  }
  m.indices = {0, 1, 2};  // counter-clockwise seen from +z
  return m;
}

TEST(GroundTruth, HalfPlaneEdgeThroughPixelCentresCoversHalf) {
  // In an odd-sized image the view axis passes through the centre of the middle pixel. The
  // N x N sample grid is symmetric about the pixel centre, so an edge through that centre
  // has as many samples on either side, except those exactly on it, which the top-left rule
  // gives wholly to one side: at most N of N^2, so |coverage - 1/2| <= 1/(2N), and 0 when no
  // sample lies on the edge (a vertical edge and even N; an irrational slope).
  const uint32_t size = 33, mid = size / 2;
  for (uint32_t n : {1u, 2u, 3u, 4u, 5u}) {
    const Scene vertical =
        emissive_scene(half_plane({0.0f, 1.0f}), glm::mat4(1.0f), 3.0f, glm::radians(60.0f));
    const ReferenceFrame f = render_reference(vertical, truth_settings(size, n, false));
    for (uint32_t y = 0; y < size; ++y) {
      const double c = f.hdr.at(mid, y).r;
      if (n % 2 == 0) {
        EXPECT_EQ(c, 0.5) << "N " << n << " row " << y;
      } else {
        EXPECT_LE(std::abs(c - 0.5), 0.5 / n + 1e-7) << "N " << n << " row " << y;
      }
      EXPECT_EQ(f.hdr.at(mid - 1, y).r, 0.0f);
      EXPECT_EQ(f.hdr.at(mid + 1, y).r, 1.0f);
    }
    const Scene slanted = emissive_scene(half_plane({1.0f, 0.6180339887f}), glm::mat4(1.0f), 3.0f,
                                         glm::radians(60.0f));
    const double c = render_reference(slanted, truth_settings(size, n, false)).hdr.at(mid, mid).r;
    if (n % 2 == 0) {
      EXPECT_EQ(c, 0.5) << "N " << n;
    } else {
      EXPECT_LE(std::abs(c - 0.5), 0.5 / n + 1e-7) << "N " << n;
    }
  }
}

// Area of the disk of centre (cx, cy) and radius r inside pixel [x, x+1] x [y, y+1]: the
// covered height integrated over x by the midpoint rule (fine enough for 1e-6).
double disk_area_in_pixel(double cx, double cy, double r, int x, int y) {
  const int steps = 20000;
  double area = 0.0;
  for (int k = 0; k < steps; ++k) {
    const double px = x + (k + 0.5) / steps;
    const double h2 = r * r - (px - cx) * (px - cx);
    if (h2 <= 0.0) continue;
    const double h = std::sqrt(h2);
    area += std::max(0.0, std::min(cy + h, y + 1.0) - std::max(cy - h, double(y)));
  }
  return area / steps;
}

TEST(GroundTruth, SupersampledDiskIntegratesItsAreaPerPixel) {
  // A sphere of radiance 1 seen from afar, slightly off the axis: a disk (its outline's
  // departure from a circle is below 1e-7 px here). Each pixel's value is then the fraction of
  // the pixel inside the disk. Per column of samples (width 1/N) the count errs by at most
  // half a sample, 1/(2N) of the column's height, where the edge is within 45 degrees of
  // horizontal (rows instead otherwise): at most 1/(2N) per pixel, plus 1/N^2 for the arc's
  // curvature and the two orientations meeting in one pixel.
  const uint32_t size = 20, n = 16;
  const float distance = 1000.0f, fov = glm::radians(0.2f);
  const glm::vec3 offset(0.0523f, -0.0291f, 0.0f);
  const Scene scene =
      emissive_scene(make_uv_sphere(16, 8), glm::translate(glm::mat4(1.0f), offset), distance, fov);
  const ReferenceFrame f = render_reference(scene, truth_settings(size, n, true));
  const double scale = (size / 2.0) / std::tan(double(fov) / 2.0);
  const double r = scale / std::sqrt(double(distance) * distance - 1.0);
  const double cx = size / 2.0 + offset.x / double(distance) * scale;
  const double cy = size / 2.0 - offset.y / double(distance) * scale;  // image y points down
  const double bound = 0.5 / n + 1.0 / (double(n) * n);
  double worst = 0.0, total = 0.0;
  int partial = 0;
  for (uint32_t y = 0; y < size; ++y) {
    for (uint32_t x = 0; x < size; ++x) {
      const double expected = disk_area_in_pixel(cx, cy, r, int(x), int(y));
      const double actual = f.hdr.at(x, y).r;
      EXPECT_NEAR(actual, expected, bound) << "pixel " << x << ", " << y;
      worst = std::max(worst, std::abs(actual - expected));
      total += actual;
      partial += expected > 0.0 && expected < 1.0;
    }
  }
  std::printf("GROUND_TRUTH disk r %.3f px: worst pixel error %.5f (bound %.5f)\n", r, worst,
              bound);
  EXPECT_GT(partial, 20);  // the disk's edge crosses many pixels
  EXPECT_NEAR(total, kPi * r * r, stratified_area_bound(2.0 * r, n));
}

// A lit ellipsoid, mirrored or not, optionally with bevelled tiles (base colour and normal
// maps), shaded from a finely tessellated mesh (interpolated normals, the compute path's
// raster) and from the analytic surface. Returns the relative radiance error between them away
// from the outline, where both see the ellipsoid in every neighbouring pixel.
RadianceError analytic_against_tessellated(glm::vec3 scale, bool textured) {
  const uint32_t size = 96;
  Scene s;
  s.camera.position = {0.0f, 0.0f, 5.0f};
  s.camera.vertical_fov = glm::radians(40.0f);
  s.meshes.push_back(make_uv_sphere(512, 256));
  Material m{glm::vec3(0.7f, 0.5f, 0.3f), 0.0f, 0.6f};
  if (textured) {
    TileMaps maps = make_tile_maps(256, 4, glm::vec3(0.8f, 0.6f, 0.4f), 1.0f);
    s.textures = {std::move(maps.base_color), std::move(maps.normal)};
    m.base_color = glm::vec3(1.0f);
    m.base_color_map = 0;
    m.normal_map = 1;
  }
  s.materials.push_back(m);
  glm::mat4 t = glm::rotate(glm::mat4(1.0f), 0.5f, glm::normalize(glm::vec3(1, 2, 0.5f)));
  s.objects.push_back({0, 0, glm::scale(t, scale)});
  s.lights.push_back({LightKind::directional, glm::vec3(0.0f),
                      glm::normalize(glm::vec3(-0.4f, -0.5f, -1.0f)), glm::vec3(1.0f), 3.0f});
  s.ambient = glm::vec3(0.02f);
  ReferenceSettings rs = truth_settings(size, 1, false);
  const ReferenceFrame tess = render_reference(s, rs);
  rs.ground_truth.analytic_spheres = true;
  const ReferenceFrame exact = render_reference(s, rs);
  std::vector<uint8_t> mask(tess.owner.size(), 0);
  size_t compared = 0;
  for (uint32_t y = 1; y + 1 < size; ++y) {
    for (uint32_t x = 1; x + 1 < size; ++x) {
      bool inside = true;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const size_t j = size_t(y + dy) * size + (x + dx);
          inside = inside && tess.owner[j] != kNoTriangle && exact.owner[j] != kNoTriangle;
        }
      mask[size_t(y) * size + x] = inside;
      compared += inside;
    }
  }
  EXPECT_GT(compared, 1500u);
  const RadianceError e = radiance_error(tess.hdr, exact.hdr, &mask);
  std::printf("GROUND_TRUTH ellipsoid scale.x %.1f%s: relative error mean %.2e, p99 %.2e\n",
              scale.x, textured ? ", textured" : "", e.mean_relative, e.p99_relative);
  return e;
}

TEST(GroundTruth, AnalyticEllipsoidShadesLikeAFineTessellation) {
  for (glm::vec3 scale : {glm::vec3(1.3f, 0.8f, 1.1f), glm::vec3(-1.3f, 0.8f, 1.1f)}) {
    // 512 segments: normals 0.7 degrees apart, so the interpolated normal is off by ~1e-4
    // rad, a relative radiance error of ~1e-4 / tan(angle to the light's horizon).
    const RadianceError e = analytic_against_tessellated(scale, false);
    EXPECT_LT(e.mean_relative, 1e-3) << "scale " << scale.x;
    EXPECT_LT(e.p99_relative, 5e-3) << "scale " << scale.x;
  }
  // With texture maps the two differ also in the texture footprint (the triangle's plane
  // against the tangent plane) and at the tiles' sharp bevels; a wrong uv (a seam moved) or a
  // wrong tangent frame (the bevels lit from the other side) would be tens of per cent.
  const RadianceError e = analytic_against_tessellated(glm::vec3(1.3f, 0.8f, 1.1f), true);
  EXPECT_LT(e.mean_relative, 1e-2);
  EXPECT_LT(e.p99_relative, 1e-1);
}

TEST(GroundTruth, DefaultsAndLimits) {
  const Scene scene = emissive_scene(make_uv_sphere(16, 8), glm::mat4(1.0f), 5.0f, 0.7f);
  ReferenceSettings rs = truth_settings(8, 1, false);
  EXPECT_TRUE(render_reference(scene, rs).ownership.first.empty());  // the compute path's model
  for (uint32_t n : {0u, 33u}) {
    rs.ground_truth.supersampling = n;
    EXPECT_THROW(render_reference(scene, rs), Error) << n;
  }
  EXPECT_TRUE(make_uv_sphere(8, 4).analytic_sphere.has_value());
  EXPECT_EQ(make_icosphere(1).analytic_sphere->u_at_plus_x, 0.5f);
  EXPECT_FALSE(make_cube().analytic_sphere.has_value());
}

}  // namespace
}  // namespace tessera
