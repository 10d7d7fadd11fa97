#version 460
#extension GL_GOOGLE_include_directive : require
// Tile fill: one thread per large triangle writes its raster-triangle index into the list of
// every tile it may touch, at a slot taken from that tile's cursor. The order inside a list
// varies from run to run; the rasterizer's atomicMin makes the result independent of it.
#include "bindings.glsl"
#include "raster_common.glsl"

layout(local_size_x = TS_GROUP_SIZE) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= min(counters[batch.index].big_tris, frame.limits.x)) return;
  uint index = big_list[i];
  RasterTri t = load_raster_tri(index);
  ivec2 first, last;
  tile_range(t, first, last);
  for (int ty = first.y; ty <= last.y; ++ty) {
    for (int tx = first.x; tx <= last.x; ++tx) {
      if (!tile_may_overlap(t, ivec2(tx, ty))) continue;
      uint slot = atomicAdd(tile_cursors[uint(ty) * frame.image_size.z + uint(tx)], 1u);
      if (slot < frame.limits.y) tile_entries[slot] = index;
    }
  }
}
