#version 460
#extension GL_GOOGLE_include_directive : require
// Tile fill: one thread per row of a bin entry's block (at most 8x8 tiles of one binned
// triangle) writes the raster-triangle index into the list of every tile of the row it may
// cover, at a slot taken from that tile's cursor. The order inside a list varies from run to
// run; the rasterizer's atomicMin makes the result independent of it.
#include "bindings.glsl"
#include "raster_common.glsl"

layout(local_size_x = TS_GROUP_SIZE) in;

void main() {
  uint e = gl_GlobalInvocationID.x / TS_BIN_CHUNK;
  if (e >= min(counters[batch.index].big_tris, frame.raster_capacity)) return;
  uvec2 entry = big_list[e];
  ivec2 first;
  int width;
  if (!bin_entry_row(entry.y, gl_GlobalInvocationID.x % TS_BIN_CHUNK, first, width)) return;
  RasterTri t = load_raster_tri(entry.x);
  for (int tx = first.x; tx < first.x + width; ++tx) {
    if (!tile_may_overlap(t, ivec2(tx, first.y))) continue;
    uint slot = atomicAdd(tile_cursors[uint(first.y) * frame.tiles.x + uint(tx)], 1u);
    if (slot < frame.tile_entry_capacity) tile_entries[slot] = entry.x;
  }
}
