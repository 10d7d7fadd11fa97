#version 460
#extension GL_GOOGLE_include_directive : require
// Triangle setup: one thread per triangle instance of the batch. Transforms to clip space,
// culls (non-finite, frustum, back face, empty), snaps to fixed point and appends raster
// triangles; small ones go to the per-triangle list, larger ones are counted into the screen
// tiles they may touch. Triangles that cross the near plane or the guard band are listed for
// the clip pass instead: clipping code here, even never taken, slows every thread on lavapipe.
#include "bindings.glsl"
#include "raster_common.glsl"

layout(local_size_x = TS_GROUP_SIZE) in;

#include "setup_common.glsl"

bool is_finite(vec4 c) {
  return !any(isnan(c)) && !any(isinf(c));
}

void main() {
  uint local = gl_GlobalInvocationID.x;
  if (local >= batch.triangle_count) return;
  uint id = batch.first_triangle + local;
  vec4 c[3];
  triangle_clip_coords(id, c);

  if (!is_finite(c[0]) || !is_finite(c[1]) || !is_finite(c[2])) {
    atomicAdd(counters[batch.index].culled_nonfinite, 1u);
    return;
  }
  // Trivial reject: all three vertices outside one viewport plane or behind the near plane.
  bool outside = false;
  bool needs_clip = false;
  for (int axis = 0; axis < 2; ++axis) {
    outside = outside || (c[0][axis] > c[0].w && c[1][axis] > c[1].w && c[2][axis] > c[2].w);
    outside = outside || (c[0][axis] < -c[0].w && c[1][axis] < -c[1].w && c[2][axis] < -c[2].w);
  }
  for (int plane = 0; plane < 5; ++plane) {
    float d0 = plane_distance(c[0], plane), d1 = plane_distance(c[1], plane), d2 = plane_distance(c[2], plane);
    if (plane == 0) outside = outside || (d0 < 0.0 && d1 < 0.0 && d2 < 0.0);
    needs_clip = needs_clip || d0 < 0.0 || d1 < 0.0 || d2 < 0.0;
  }
  if (outside) {
    atomicAdd(counters[batch.index].culled_frustum, 1u);
    return;
  }
  if (needs_clip) {
    uint slot = atomicAdd(counters[batch.index].clip_list, 1u);
    if (slot < frame.limits.x) clip_list[slot] = id;  // overflow: the host grows and redoes
    return;
  }
  emit(c[0], c[1], c[2], id);
}
