// A triangle instance in clip space and its clipping to the near plane and the guard band,
// shared by the clip pass (which rasterizes what is left) and analytic coverage (coverage.glsl,
// which measures it). Needs bindings.glsl.

// Setup's frames that record no object_clip pass (Renderer's forms_object_clip_in_setup) form
// view_proj * model below. A specialization constant, not a uniform: lavapipe inlines uniforms
// that decide branches into its shaders, and compiled setup anew every frame (16 ms and 0.6 MB
// more a frame for one sphere).
layout(constant_id = TS_SPEC_OBJECT_CLIP_INLINE) const bool OBJECT_CLIP_INLINE = false;

// How the clipped polygons here and in coverage.glsl are kept (Context::polygons_in_registers):
// indexed by corner (false), as GPUs run them best, or walked as queues whose arrays are
// indexed by constants only (true). lavapipe keeps an array in registers only if every index is
// a constant; otherwise every access goes lane by lane through memory, and its compiler took
// about three times as long over the code that measures coverage (docs/development.md,
// "Measured CI time"). The H200 ran the queues up to 18 % slower (probably as registers that
// leave fewer threads resident). Both forms take the same steps in the same order.
layout(constant_id = TS_SPEC_POLYGONS_IN_REGISTERS) const bool POLYGONS_IN_REGISTERS = false;

// Clip-space position of the corners of triangle instance `id` of object slot `slot`. The
// object's view_proj * model comes from the object_clip pass: computed there once per object
// rather than here once per triangle, with the same expression, so the same floats (or here,
// under OBJECT_CLIP_INLINE). Setup calls it per triangle: written through a helper taking the vertex indices, the same computation made
// the H200's setup pass 24 % slower at 10^6 grid objects (21.6 -> 26.8 ms).
void triangle_clip_coords(uint slot, uint id, out vec4 c[3]) {
  uvec3 vi = triangle_vertices(objects[slot], id);
  // The same expression as object_clip.comp's, so the same floats either way.
  mat4 to_clip = OBJECT_CLIP_INLINE ? frame.view_proj * objects[slot].model : object_clip[slot];
  for (int k = 0; k < 3; ++k) c[k] = to_clip * vec4(vertices[vi[k]].position_u.xyz, 1.0);
}

// Signed distance to clip plane `plane` (inside >= 0): the near plane, then the guard band.
float plane_distance(vec4 c, int plane) {
  float gx = frame.guard_band.x;
  float gy = frame.guard_band.y;
  switch (plane) {
    case 0: return c.w - frame.near_plane;
    case 1: return gx * c.w - c.x;
    case 2: return gx * c.w + c.x;
    case 3: return gy * c.w - c.y;
    default: return gy * c.w + c.y;
  }
}

// Fixed-point (1/TS_SUBPIXEL_ONE px) position of clip-space point `c` in the image: how setup
// snaps a vertex. `c` is in front of the near plane and inside the guard band.
ivec2 snap_to_subpixels(vec4 c) {
  vec2 screen = (c.xy / c.w * 0.5 + 0.5) * vec2(frame.image_size);
  return ivec2(floor(screen * float(TS_SUBPIXEL_ONE) + 0.5));
}

// Where the edge a -> b, whose ends lie at plane distances da and db of opposite signs, crosses
// the plane. An edge shared by two triangles is walked a->b by one and b->a by the other: the
// crossing is computed from its inside end towards its outside end, whichever way the edge is
// walked, so that both triangles get the same bits and no sample on the edge is covered twice
// or missed (docs/architecture.md, "Coverage rules").
vec4 plane_crossing(vec4 a, vec4 b, float da, float db) {
  bool a_in = da >= 0.0;
  vec4 p_in = a_in ? a : b;
  vec4 p_out = a_in ? b : a;
  float d_in = a_in ? da : db;
  float d_out = a_in ? db : da;
  return mix(p_in, p_out, d_in / (d_in - d_out));
}

// clip_to_view with its polygons indexed by the corner: GPUs keep such arrays in memory.
int clip_to_view_indexed(vec4 c[3], out vec4 poly[9]) {
  vec4 next_poly[9];
  int n = 3;
  poly[0] = c[0];
  poly[1] = c[1];
  poly[2] = c[2];
  for (int plane = 0; plane < 5 && n > 0; ++plane) {
    int m = 0;
    for (int k = 0; k < n; ++k) {
      vec4 a = poly[k];
      vec4 b = poly[(k + 1) % n];
      float da = plane_distance(a, plane);
      float db = plane_distance(b, plane);
      if (da >= 0.0) next_poly[m++] = a;
      if ((da >= 0.0) != (db >= 0.0)) next_poly[m++] = plane_crossing(a, b, da, db);
    }
    n = m;
    for (int k = 0; k < n; ++k) poly[k] = next_poly[k];
  }
  return n;
}

// Appends `v` to the queue `q` (its corners kept at its end, the newest last).
void push_back(inout vec4 q[9], vec4 v) {
  for (int j = 0; j < 8; ++j) q[j] = q[j + 1];
  q[8] = v;
}

// Rotates `q` left by `places`, a constant where it is called (so is every index).
void rotate_left(inout vec4 q[9], int places) {
  vec4 t[9] = q;
  for (int j = 0; j < 9; ++j) q[j] = t[(j + places) % 9];
}

// clip_to_view with its polygons walked as queues, each array indexed by constants only: the
// same steps in the same order, so the same floats.
int clip_to_view_queued(vec4 c[3], out vec4 poly[9]) {
  int n = 3;
  poly[0] = c[0];
  poly[1] = c[1];
  poly[2] = c[2];
  for (int k = 3; k < 9; ++k) poly[k] = vec4(0.0);
  for (int plane = 0; plane < 5 && n > 0; ++plane) {
    vec4 first = poly[0];
    vec4 next_poly[9];
    for (int j = 0; j < 9; ++j) next_poly[j] = vec4(0.0);
    int m = 0;
    for (int k = 0; k < n; ++k) {
      vec4 a = poly[0];
      vec4 b = k + 1 < n ? poly[1] : first;
      for (int j = 0; j < 8; ++j) poly[j] = poly[j + 1];
      float da = plane_distance(a, plane);
      float db = plane_distance(b, plane);
      if (da >= 0.0) {
        push_back(next_poly, a);
        m++;
      }
      if ((da >= 0.0) != (db >= 0.0)) {
        push_back(next_poly, plane_crossing(a, b, da, db));
        m++;
      }
    }
    n = m;
    // The m corners are next_poly[9 - m ..]: to the front.
    int shift = 9 - m;
    if ((shift & 8) != 0) rotate_left(next_poly, 8);
    if ((shift & 4) != 0) rotate_left(next_poly, 4);
    if ((shift & 2) != 0) rotate_left(next_poly, 2);
    if ((shift & 1) != 0) rotate_left(next_poly, 1);
    poly = next_poly;
  }
  return n;
}

// Clips triangle `c` to the near plane and the four guard-band planes (Sutherland & Hodgman
// 1974, "Reentrant polygon clipping"): the convex polygon left, at most 3 + 5 corners, in
// `poly`; returns their number (0 if nothing is left). In one of two forms that give the same
// bits (POLYGONS_IN_REGISTERS).
int clip_to_view(vec4 c[3], out vec4 poly[9]) {
  if (POLYGONS_IN_REGISTERS) return clip_to_view_queued(c, poly);
  return clip_to_view_indexed(c, poly);
}
