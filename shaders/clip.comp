#version 460
#extension GL_GOOGLE_include_directive : require
// Clipping: triangles that cross the near plane or the guard band, listed by setup. Each is
// clipped (Sutherland-Hodgman) against the near plane and the four guard-band planes into a
// convex polygon of at most 3 + 5 vertices, then emitted as a fan of raster triangles. The
// list is short in practice, so a fixed grid of threads loops over it, with plain atomics.
#include "bindings.glsl"
#include "raster_common.glsl"

layout(local_size_x = TS_GROUP_SIZE) in;

#include "setup_common.glsl"

void emit(vec4 c0, vec4 c1, vec4 c2, uint id, bool mirrored) {
  RasterTri t;
  uint outcome = prepare_triangle(c0, c1, c2, id, mirrored, t);
  if (outcome == OUTCOME_FACING) {
    atomicAdd(counters[batch.index].culled_backface, 1u);
    return;
  }
  if (outcome == OUTCOME_EMPTY) {
    atomicAdd(counters[batch.index].culled_empty, 1u);
    return;
  }
  uint index = atomicAdd(counters[batch.index].raster_tris, 1u);
  if (index >= frame.raster_capacity) return;  // overflow: the host sees the count, grows, redoes
  store_raster_tri(index, t);
  if (outcome == OUTCOME_SMALL) {
    small_list[atomicAdd(counters[batch.index].small_tris, 1u)] = index;
  } else {
    uint entries = bin_entry_count(t);
    store_bin_entries(index, t, atomicAdd(counters[batch.index].big_tris, entries), entries);
  }
}

void main() {
  uint count = min(counters[batch.index].clip_list, frame.raster_capacity);
  for (uint i = gl_GlobalInvocationID.x; i < count; i += TS_CLIP_GROUPS * TS_GROUP_SIZE) {
    uint id = clip_list[i];
    vec4 c[3];
    uint slot = find_object(id);
    triangle_clip_coords(slot, id, c);
    atomicAdd(counters[batch.index].clipped, 1u);
    vec4 poly[9];
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
        if ((da >= 0.0) != (db >= 0.0)) {
          // An edge shared by two triangles is walked a->b by one and b->a by the other. The
          // crossing is computed from its inside end towards its outside end, whichever way
          // the edge is walked, so that both triangles get the same bits and no sample on the
          // edge is covered twice or missed (docs/architecture.md, "Coverage rules").
          bool a_in = da >= 0.0;
          vec4 p_in = a_in ? a : b;
          vec4 p_out = a_in ? b : a;
          float d_in = a_in ? da : db;
          float d_out = a_in ? db : da;
          next_poly[m++] = mix(p_in, p_out, d_in / (d_in - d_out));
        }
      }
      n = m;
      for (int k = 0; k < n; ++k) poly[k] = next_poly[k];
    }
    bool mirrored = objects[slot].mirrored != 0u;
    for (int k = 1; k + 1 < n; ++k) emit(poly[0], poly[k], poly[k + 1], id, mirrored);
  }
}
