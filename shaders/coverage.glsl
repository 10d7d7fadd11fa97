// Analytic coverage (FrameSettings::aa_coverage analytic) of a pixel whose samples see one
// triangle and the background: how much of it the surface covers. The reference
// renderer's version is core/pixel_coverage.cpp. Needs bindings.glsl and raster_common.glsl.

#include "view_clip.glsl"

// The pixel square cut by the lines of at most 8 edges (a triangle after the view's five
// planes): each cut adds at most one corner to the 4.
const int COVERAGE_CORNERS = 12;

// Outline coverage of pixel `pixel` by triangle instance `id`, the one triangle its samples
// see, `empty` (one bit per sample) the others: the area (px^2, 0..1) of the pixel square
// inside the lines of the triangle's outline edges, those with an empty sample on or beyond
// them and no covered sample beyond (the edge separates what the pixel's samples see of the
// surface from the background: taken as where the surface ends). Its other edges do not cut:
// the surface continues across them. Returns -1 if no edge is an outline edge, 0 for a
// triangle with no area. The triangle is rebuilt as the rasterizer saw it: clipped to the
// near plane and guard band as the clip pass does, its corners snapped as setup snaps them,
// taken relative to the pixel in integers, so each sample is tested against each edge with
// the rasterizer's exact integer edge function. The square is cut by Sutherland & Hodgman
// (1974, "Reentrant polygon clipping") and measured by the shoelace formula.
float outline_coverage(uint id, ivec2 pixel, uint empty) {
  vec4 c[3];
  triangle_clip_coords(find_object(id), id, c);
  vec4 clipped[9];
  int n = clip_to_view(c, clipped);
  ivec2 corner[9];
  int64_t twice_area = 0l;
  for (int k = 0; k < n; ++k) corner[k] = snap_to_subpixels(clipped[k]) - pixel * TS_SUBPIXEL_ONE;
  for (int k = 0; k < n; ++k) twice_area += edge_function(ivec2(0), corner[k], corner[(k + 1) % n]);
  if (twice_area == 0l) return 0.0;
  int64_t sign = twice_area > 0l ? 1l : -1l;

  vec2 region[COVERAGE_CORNERS];
  region[0] = vec2(0.0, 0.0);
  region[1] = vec2(1.0, 0.0);
  region[2] = vec2(1.0, 1.0);
  region[3] = vec2(0.0, 1.0);
  int m = 4;
  int cuts = 0;
  vec2 next[COVERAGE_CORNERS];
  for (int k = 0; k < n && m > 0; ++k) {
    ivec2 a = corner[k];
    ivec2 b = corner[(k + 1) % n];
    bool beyond_empty = false;
    bool beyond_covered = false;
    for (uint s = 0u; s < SAMPLES; ++s) {
      int64_t e = sign * edge_function(a, b, sample_offset(s));
      if ((empty & (1u << s)) != 0u) beyond_empty = beyond_empty || e <= 0l;
      else beyond_covered = beyond_covered || e < 0l;
    }
    if (!beyond_empty || beyond_covered) continue;
    cuts++;
    // Inside the edge's line: s * cross(b - a, p - a) >= 0, in pixels.
    vec2 fa = vec2(a) / float(TS_SUBPIXEL_ONE);
    vec2 ab = vec2(b - a) / float(TS_SUBPIXEL_ONE) * float(sign);
    int count = 0;
    for (int j = 0; j < m; ++j) {
      vec2 p = region[j];
      vec2 q = region[(j + 1) % m];
      float dp = ab.x * (p.y - fa.y) - ab.y * (p.x - fa.x);
      float dq = ab.x * (q.y - fa.y) - ab.y * (q.x - fa.x);
      if (dp >= 0.0) next[count++] = p;
      if ((dp >= 0.0) != (dq >= 0.0)) next[count++] = mix(p, q, dp / (dp - dq));
    }
    m = count;
    for (int j = 0; j < m; ++j) region[j] = next[j];
  }
  if (cuts == 0) return -1.0;
  float twice = 0.0;
  for (int j = 0; j < m; ++j) {
    vec2 p = region[j];
    vec2 q = region[(j + 1) % m];
    twice += p.x * q.y - p.y * q.x;
  }
  // Rounding can leave a sliver's area a hair outside [0, 1].
  return clamp(0.5 * abs(twice), 0.0, 1.0);
}
