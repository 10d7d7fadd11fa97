#version 460
#extension GL_GOOGLE_include_directive : require
// Tile counting: for every bin entry (a block of at most 8x8 tiles of one binned triangle), adds
// one to the count of each tile of the block the triangle may cover, a thread per row of the
// block, dispatched indirectly (big_dispatch, which setup and clip raise as they append).
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
    if (tile_may_overlap(t, ivec2(tx, first.y))) atomicAdd(tile_counts[uint(first.y) * frame.tiles.x + uint(tx)], 1u);
  }
}
