#version 460
#extension GL_GOOGLE_include_directive : require
// Clipping: triangles that cross the near plane or the guard band, listed by setup. Each is
// clipped (Sutherland-Hodgman) against the near plane and the four guard-band planes into a
// convex polygon of at most 3 + 5 vertices, then emitted as a fan of raster triangles. The
// list is short in practice: a thread per entry, dispatched indirectly (setup sizes it, so an
// empty list launches nothing), with plain atomics.
#include "bindings.glsl"
#include "raster_common.glsl"

layout(local_size_x = TS_GROUP_SIZE) in;

#include "setup_common.glsl"

void emit(vec4 c0, vec4 c1, vec4 c2, uint id, bool mirrored, bool double_sided) {
  RasterTri t;
  uint outcome = prepare_triangle(c0, c1, c2, id, mirrored, double_sided, t);
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
    uint walks = small_walks(t);
    uint slot = append_small(1u, walks);
    if (frame.tile_list_stride != 0u) {  // no scan pass sizes raster_small's dispatch
      RAISE_DISPATCH(counters[batch.index].small_dispatch.x, slot, walks, TS_GROUP_SIZE);
    }
    store_small_entries(index, slot, walks);
  } else {
    uint entries = bin_entry_count(t);
    uint first = atomicAdd(counters[batch.index].big_tris, entries);
    RAISE_DISPATCH(counters[batch.index].big_dispatch.x, first, entries, TS_BIN_ENTRIES_PER_GROUP);
    if (frame.tile_list_stride != 0u && first == 0u) WRITE_TILES_DISPATCH(batch.index);
    store_bin_entries(index, t, first, entries);
  }
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i < min(counters[batch.index].clip_list, frame.raster_capacity)) {
    uint id = clip_list[i];
    vec4 c[3];
    uint slot = find_object(id);
    triangle_clip_coords(slot, id, c);
    atomicAdd(counters[batch.index].clipped, 1u);
    vec4 poly[9];
    int n = clip_to_view(c, poly);
    bool mirrored = objects[slot].mirrored != 0u;
    bool double_sided = objects[slot].double_sided != 0u;
    for (int k = 1; k + 1 < n; ++k) emit(poly[0], poly[k], poly[k + 1], id, mirrored, double_sided);
  }
}
