#version 460
#extension GL_GOOGLE_include_directive : require
// Exclusive prefix sum of the per-tile triangle counts, in one workgroup: each thread sums a
// contiguous chunk, the chunk sums are scanned in shared memory, then each chunk is written.
// Also writes the indirect dispatch sizes of the two passes that follow.
#include "bindings.glsl"

layout(local_size_x = TS_SCAN_GROUP_SIZE) in;

shared uint partial[TS_SCAN_GROUP_SIZE];

void write_dispatch_sizes(uint b, bool tiles_used) {
  uint small_count = min(counters[b].small_tris, frame.raster_capacity);
  uint big_count = min(counters[b].big_tris, frame.raster_capacity);
  counters[b].small_dispatch = uvec4((small_count + TS_GROUP_SIZE - 1) / TS_GROUP_SIZE, 1, 1, 0);
  counters[b].big_dispatch = uvec4((big_count + TS_GROUP_SIZE - 1) / TS_GROUP_SIZE, 1, 1, 0);
  counters[b].tiles_dispatch = tiles_used ? uvec4(frame.tiles.x, frame.tiles.y, 1, 0) : uvec4(0, 1, 1, 0);
}

void main() {
  uint n = frame.tiles.x * frame.tiles.y;
  uint t = gl_LocalInvocationID.x;
  // Nothing binned (the common case for small triangles): every count is 0, so the offsets
  // are never read; skip the scan and the tile passes.
  if (counters[batch.index].big_tris == 0u) {
    if (t == 0u) {
      counters[batch.index].tile_entries = 0u;
      write_dispatch_sizes(batch.index, false);
    }
    return;
  }
  uint chunk = (n + TS_SCAN_GROUP_SIZE - 1) / TS_SCAN_GROUP_SIZE;
  uint begin = min(t * chunk, n);
  uint end = min(begin + chunk, n);
  uint sum = 0u;
  for (uint i = begin; i < end; ++i) sum += tile_counts[i];
  partial[t] = sum;
  barrier();
  for (uint offset = 1u; offset < TS_SCAN_GROUP_SIZE; offset <<= 1) {
    uint v = t >= offset ? partial[t - offset] : 0u;
    barrier();
    partial[t] += v;
    barrier();
  }
  uint running = partial[t] - sum;
  for (uint i = begin; i < end; ++i) {
    tile_offsets[i] = running;
    tile_cursors[i] = running;
    running += tile_counts[i];
  }
  if (t == TS_SCAN_GROUP_SIZE - 1) {
    counters[batch.index].tile_entries = partial[t];
    write_dispatch_sizes(batch.index, true);
  }
}
