// How much of a pixel a surface covers, for anti-aliasing's weights (FrameSettings::
// aa_coverage): analytic (outline_coverage, where the samples see one triangle and the
// background) and silhouette (front_face_area, the measure of the outline pass's walk, over
// one surface and the background). The reference renderer's versions are in
// core/pixel_coverage.cpp. Needs bindings.glsl and raster_common.glsl.

#include "view_clip.glsl"

// The pixel square cut by the lines of at most 8 edges (a triangle after the view's five
// planes): each cut adds at most one corner to the 4.
const int COVERAGE_CORNERS = 12;

// Triangle instance `id` of object slot `slot` as the rasterizer saw it, relative to pixel
// `pixel`: clipped to the near plane and guard band as the clip pass does, its corners snapped
// as setup snaps them, in 1/TS_SUBPIXEL_ONE px. Returns the number of corners (0..9);
// `twice_area` is twice its signed area in those units (its sign the winding setup sees).
int pixel_corners(uint slot, uint id, ivec2 pixel, out ivec2 corner[9], out int64_t twice_area) {
  vec4 c[3];
  triangle_clip_coords(slot, id, c);
  vec4 clipped[9];
  int n = clip_to_view(c, clipped);
  twice_area = 0l;
  if (!POLYGONS_IN_REGISTERS) {
    for (int k = 0; k < n; ++k) corner[k] = snap_to_subpixels(clipped[k]) - pixel * TS_SUBPIXEL_ONE;
    for (int k = 0; k < n; ++k) twice_area += edge_function(ivec2(0), corner[k], corner[(k + 1) % n]);
    return n;
  }
  // Constant indices only: the loops unroll; the unused corners are zero.
  for (int k = 0; k < 9; ++k) {
    corner[k] = ivec2(0);
    if (k < n) corner[k] = snap_to_subpixels(clipped[k]) - pixel * TS_SUBPIXEL_ONE;
  }
  for (int k = 0; k < 9; ++k) {
    if (k < n) twice_area += edge_function(ivec2(0), corner[k], k + 1 < n ? corner[min(k + 1, 8)] : corner[0]);
  }
  return n;
}

// The edge from the first of the corners `corner` to the next, or to `first` (the polygon's
// first corner) if `remaining` is 1, for POLYGONS_IN_REGISTERS: a polygon's corners taken as a
// queue, the first returned and the others moved up, so that only constants index `corner`.
void pop_edge(inout ivec2 corner[9], int remaining, ivec2 first, out ivec2 a, out ivec2 b) {
  a = corner[0];
  b = remaining > 1 ? corner[1] : first;
  for (int j = 0; j < 8; ++j) corner[j] = corner[j + 1];
}

// Appends `v` to the queue `q`, whose corners are kept at its end, the newest last.
void push_back(inout vec2 q[COVERAGE_CORNERS], vec2 v) {
  for (int j = 0; j + 1 < COVERAGE_CORNERS; ++j) q[j] = q[j + 1];
  q[COVERAGE_CORNERS - 1] = v;
}

// Rotates `q` left by `places`, a constant where it is called (so is every index).
void rotate_left(inout vec2 q[COVERAGE_CORNERS], int places) {
  vec2 t[COVERAGE_CORNERS] = q;
  for (int j = 0; j < COVERAGE_CORNERS; ++j) q[j] = t[(j + places) % COVERAGE_CORNERS];
}

// Moves the last `count` corners of `q` to its front, in order: a rotation by
// COVERAGE_CORNERS - count places, made of rotations by 8, 4, 2 and 1.
void rotate_to_front(inout vec2 q[COVERAGE_CORNERS], int count) {
  int shift = COVERAGE_CORNERS - count;
  if ((shift & 8) != 0) rotate_left(q, 8);
  if ((shift & 4) != 0) rotate_left(q, 4);
  if ((shift & 2) != 0) rotate_left(q, 2);
  if ((shift & 1) != 0) rotate_left(q, 1);
}

// cut_by_edge with the polygons indexed by the corner.
int cut_by_edge_indexed(inout vec2 region[COVERAGE_CORNERS], int m, ivec2 a, ivec2 b, int64_t sign) {
  vec2 fa = vec2(a) / float(TS_SUBPIXEL_ONE);
  vec2 ab = vec2(b - a) / float(TS_SUBPIXEL_ONE) * float(sign);
  vec2 next[COVERAGE_CORNERS];
  int count = 0;
  for (int j = 0; j < m; ++j) {
    vec2 p = region[j];
    vec2 q = region[(j + 1) % m];
    float dp = ab.x * (p.y - fa.y) - ab.y * (p.x - fa.x);
    float dq = ab.x * (q.y - fa.y) - ab.y * (q.x - fa.x);
    if (dp >= 0.0) next[count++] = p;
    if ((dp >= 0.0) != (dq >= 0.0)) next[count++] = mix(p, q, dp / (dp - dq));
  }
  for (int j = 0; j < count; ++j) region[j] = next[j];
  return count;
}

// cut_by_edge with the polygons walked as queues (constant indices only): the same steps.
int cut_by_edge_queued(inout vec2 region[COVERAGE_CORNERS], int m, ivec2 a, ivec2 b, int64_t sign) {
  vec2 fa = vec2(a) / float(TS_SUBPIXEL_ONE);
  vec2 ab = vec2(b - a) / float(TS_SUBPIXEL_ONE) * float(sign);
  vec2 first = region[0];
  vec2 next[COVERAGE_CORNERS];
  for (int j = 0; j < COVERAGE_CORNERS; ++j) next[j] = vec2(0.0);
  int count = 0;
  for (int j = 0; j < m; ++j) {
    vec2 p = region[0];
    vec2 q = j + 1 < m ? region[1] : first;
    for (int i = 0; i + 1 < COVERAGE_CORNERS; ++i) region[i] = region[i + 1];
    float dp = ab.x * (p.y - fa.y) - ab.y * (p.x - fa.x);
    float dq = ab.x * (q.y - fa.y) - ab.y * (q.x - fa.x);
    if (dp >= 0.0) {
      push_back(next, p);
      count++;
    }
    if ((dp >= 0.0) != (dq >= 0.0)) {
      push_back(next, mix(p, q, dp / (dp - dq)));
      count++;
    }
  }
  rotate_to_front(next, count);
  region = next;
  return count;
}

// Cuts the convex polygon `region` (m corners, in pixels) by the line of the edge a -> b (in
// 1/TS_SUBPIXEL_ONE px), keeping the side sign * cross(b - a, p - a) >= 0: one step of
// Sutherland & Hodgman (1974, "Reentrant polygon clipping"). Returns the corners left. In one
// of two forms that give the same bits (POLYGONS_IN_REGISTERS, view_clip.glsl).
int cut_by_edge(inout vec2 region[COVERAGE_CORNERS], int m, ivec2 a, ivec2 b, int64_t sign) {
  if (POLYGONS_IN_REGISTERS) return cut_by_edge_queued(region, m, a, b, sign);
  return cut_by_edge_indexed(region, m, a, b, sign);
}

// The pixel square [0, 1]^2 as a polygon.
int unit_square(out vec2 region[COVERAGE_CORNERS]) {
  if (POLYGONS_IN_REGISTERS) {
    for (int j = 4; j < COVERAGE_CORNERS; ++j) region[j] = vec2(0.0);
  }
  region[0] = vec2(0.0, 0.0);
  region[1] = vec2(1.0, 0.0);
  region[2] = vec2(1.0, 1.0);
  region[3] = vec2(0.0, 1.0);
  return 4;
}

// Area of polygon `region` (m corners) by the shoelace formula, in px^2.
float polygon_area(vec2 region[COVERAGE_CORNERS], int m) {
  float twice = 0.0;
  if (!POLYGONS_IN_REGISTERS) {
    for (int j = 0; j < m; ++j) {
      vec2 p = region[j];
      vec2 q = region[(j + 1) % m];
      twice += p.x * q.y - p.y * q.x;
    }
    return 0.5 * abs(twice);
  }
  // Constant indices only: the same terms in the same order.
  for (int j = 0; j < COVERAGE_CORNERS; ++j) {
    vec2 p = region[j];
    vec2 q = j + 1 < m ? region[min(j + 1, COVERAGE_CORNERS - 1)] : region[0];
    if (j < m) twice += p.x * q.y - p.y * q.x;
  }
  return 0.5 * abs(twice);
}

// Outline coverage of pixel `pixel` by triangle instance `id`, the one triangle its samples
// see, `empty` (one bit per sample) the others: the area (px^2, 0..1) of the pixel square
// inside the lines of the triangle's outline edges, those with an empty sample on or beyond
// them and no covered sample beyond (the edge separates what the pixel's samples see of the
// surface from the background: taken as where the surface ends). Its other edges do not cut:
// the surface continues across them. Returns -1 if no edge is an outline edge, 0 for a
// triangle with no area. The triangle is rebuilt as the rasterizer saw it (pixel_corners), so
// each sample is tested against each edge with the rasterizer's exact integer edge function.
float outline_coverage(uint id, ivec2 pixel, uint empty) {
  ivec2 corner[9];
  int64_t twice_area;
  int n = pixel_corners(find_object(id), id, pixel, corner, twice_area);
  if (twice_area == 0l) return 0.0;
  int64_t sign = twice_area > 0l ? 1l : -1l;

  vec2 region[COVERAGE_CORNERS];
  int m = unit_square(region);
  int cuts = 0;
  ivec2 first = corner[0];
  for (int k = 0; k < n && m > 0; ++k) {
    ivec2 a, b;
    if (POLYGONS_IN_REGISTERS) {
      pop_edge(corner, n - k, first, a, b);
    } else {
      a = corner[k];
      b = corner[(k + 1) % n];
    }
    bool beyond_empty = false;
    bool beyond_covered = false;
    for (uint s = 0u; s < SAMPLES; ++s) {
      int64_t e = sign * edge_function(a, b, sample_offset(s));
      if ((empty & (1u << s)) != 0u) beyond_empty = beyond_empty || e <= 0l;
      else beyond_covered = beyond_covered || e < 0l;
    }
    if (!beyond_empty || beyond_covered) continue;
    cuts++;
    m = cut_by_edge(region, m, a, b, sign);
  }
  if (cuts == 0) return -1.0;
  // Rounding can leave a sliver's area a hair outside [0, 1].
  return clamp(polygon_area(region, m), 0.0, 1.0);
}

// Mean over [lo, hi] of g(x) = 1 - clamp(x, 0, 1), the share of a pixel's row right of x: g is
// 1 left of the pixel, falls linearly across it and is 0 right of it, so the integral over each
// piece is its length times g at the piece's middle (exact for a linear piece), with no
// difference of antiderivatives to cancel on a nearly vertical edge.
float mean_right_share(float lo, float hi) {
  float left = max(min(hi, 0.0) - lo, 0.0);
  float a = max(lo, 0.0), b = min(hi, 1.0);
  float across = max(b - a, 0.0) * (1.0 - 0.5 * (a + b));
  return hi > lo ? (left + across) / (hi - lo) : 1.0 - clamp(lo, 0.0, 1.0);
}

// Signed share of the directed edge a -> b (in pixels, relative to the pixel's top-left corner)
// in the area of a closed polygon inside the pixel square [0, 1]^2. By Green's theorem the
// polygon's winding number, integrated over the square, is the sum over its edges of the
// square's area right of each edge within the edge's rows, signed by the edge's direction in y
// (the exact-area coverage that accumulating font rasterizers compute): a closed-form integral
// per edge, no clipped polygon to keep. Registers only: the Sutherland-Hodgman cut it replaces in the silhouette walk kept its
// polygons in arrays that a GPU spills to memory.
float edge_share_in_pixel(vec2 a, vec2 b) {
  float y0 = clamp(a.y, 0.0, 1.0);
  float y1 = clamp(b.y, 0.0, 1.0);
  if (y0 == y1) return 0.0;  // no row of the square (or horizontal)
  float slope = (b.x - a.x) / (b.y - a.y);  // b.y != a.y, as the clamped ends differ
  float x0 = a.x + (y0 - a.y) * slope;
  float x1 = a.x + (y1 - a.y) * slope;
  return (y1 - y0) * mean_right_share(min(x0, x1), max(x0, x1));
}

// Fixed-point corner (1/TS_SUBPIXEL_ONE px, relative to the pixel) in pixels.
vec2 in_pixels(ivec2 corner) {
  return vec2(corner) / float(TS_SUBPIXEL_ONE);
}

// True if the fixed-point box [lo, hi] (relative to the pixel) overlaps the open pixel square:
// a triangle that only touches the pixel along a line has no area in it, and is left out
// exactly rather than by rounding.
bool box_reaches_pixel(ivec2 lo, ivec2 hi) {
  return all(greaterThan(hi, ivec2(0))) && all(lessThan(lo, ivec2(TS_SUBPIXEL_ONE)));
}

// Area (px^2) of pixel `pixel` inside triangle instance `t` of object slot `slot` (clipped and
// snapped as the rasterizer saw it) if it winds as `facing` says (the sign of its doubled
// area; 0: take the triangle's own, and set it), else 0: facing away, edge-on after snapping,
// or outside the pixel. A triangle wholly in front of the near plane and inside the guard band
// (nearly every one) is taken in registers, corner by corner; only one the view clips is
// rebuilt as a polygon (pixel_corners).
float front_face_area(uint slot, uint t, ivec2 pixel, inout int64_t facing) {
  vec4 c[3];
  triangle_clip_coords(slot, t, c);
  bool unclipped = true;
  for (int plane = 0; plane < 5; ++plane) {
    unclipped = unclipped && plane_distance(c[0], plane) >= 0.0 && plane_distance(c[1], plane) >= 0.0 &&
                plane_distance(c[2], plane) >= 0.0;
  }
  if (unclipped) {
    // What clip_to_view returns for such a triangle: its corners, in order.
    ivec2 origin = pixel * TS_SUBPIXEL_ONE;
    ivec2 p0 = snap_to_subpixels(c[0]) - origin;
    ivec2 p1 = snap_to_subpixels(c[1]) - origin;
    ivec2 p2 = snap_to_subpixels(c[2]) - origin;
    int64_t twice_area = edge_function(ivec2(0), p0, p1) + edge_function(ivec2(0), p1, p2) +
                         edge_function(ivec2(0), p2, p0);
    if (facing == 0l) facing = twice_area > 0l ? 1l : -1l;
    if (twice_area * facing <= 0l) return 0.0;
    if (!box_reaches_pixel(min(p0, min(p1, p2)), max(p0, max(p1, p2)))) return 0.0;
    vec2 a = in_pixels(p0), b = in_pixels(p1), d = in_pixels(p2);
    return abs(edge_share_in_pixel(a, b) + edge_share_in_pixel(b, d) + edge_share_in_pixel(d, a));
  }
  ivec2 corner[9];
  int64_t twice_area;
  int n = pixel_corners(slot, t, pixel, corner, twice_area);
  if (facing == 0l) facing = twice_area > 0l ? 1l : -1l;
  if (twice_area * facing <= 0l) return 0.0;
  ivec2 lo = corner[0], hi = corner[0];
  for (int k = 1; k < (POLYGONS_IN_REGISTERS ? 9 : n); ++k) {
    if (k >= n) continue;
    lo = min(lo, corner[k]);
    hi = max(hi, corner[k]);
  }
  if (!box_reaches_pixel(lo, hi)) return 0.0;
  float share = 0.0;
  ivec2 first = corner[0];
  for (int k = 0; k < n; ++k) {
    ivec2 a, b;
    if (POLYGONS_IN_REGISTERS) {
      pop_edge(corner, n - k, first, a, b);
    } else {
      a = corner[k];
      b = corner[(k + 1) % n];
    }
    share += edge_share_in_pixel(in_pixels(a), in_pixels(b));
  }
  return abs(share);
}
