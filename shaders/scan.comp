#version 460
#extension GL_GOOGLE_include_directive : require
// Tile-list allocation: one thread per screen tile takes a contiguous range of the tile-entry
// array for its tile's count. The ranges come from one atomicAdd per workgroup on the batch's
// entry total, so their order varies from run to run, as the order inside a list already does
// (fill.comp): the rasterizer's atomicMin makes the image independent of both, and the total,
// the only value read back, is a sum and so the same in every order. Unlike a prefix sum in one
// workgroup, this spreads over the whole GPU in one pass. Also writes the indirect dispatch
// sizes of the passes that follow.
#include "bindings.glsl"

layout(local_size_x = TS_SCAN_GROUP_SIZE) in;

shared uint group_total;
shared uint group_base;

void write_dispatch_sizes(uint b, bool tiles_used) {
  uint small_count = min(counters[b].small_counts.x, frame.raster_capacity);
  counters[b].small_dispatch = uvec4((small_count + TS_GROUP_SIZE - 1) / TS_GROUP_SIZE, 1, 1, 0);
  counters[b].tiles_dispatch = tiles_used ? uvec4(frame.tiles.x, frame.tiles.y, 1, 0) : uvec4(0, 1, 1, 0);
}

void main() {
  uint tile = gl_GlobalInvocationID.x;
  bool binned = counters[batch.index].big_tris != 0u;
  if (gl_GlobalInvocationID.x == 0u) write_dispatch_sizes(batch.index, binned);
  // Nothing binned (the common case for small triangles): every count is 0, the offsets are
  // never read and the tile passes are skipped.
  if (!binned) return;
  if (gl_LocalInvocationIndex == 0u) group_total = 0u;
  barrier();
  uint count = tile < frame.tiles.x * frame.tiles.y ? tile_counts[tile] : 0u;
  uint local = count != 0u ? atomicAdd(group_total, count) : 0u;
  barrier();
  if (gl_LocalInvocationIndex == 0u) {
    group_base = group_total != 0u ? atomicAdd(counters[batch.index].tile_entries, group_total) : 0u;
  }
  barrier();
  if (count == 0u) return;  // the rasterizer and fill read no range of an empty tile
  tile_offsets[tile] = group_base + local;
  tile_cursors[tile] = group_base + local;
}
