#version 460
#extension GL_GOOGLE_include_directive : require
// Tile counting: for every bin entry (a block of at most 8x8 tiles of one binned triangle), adds
// one to the count of each tile of the block the triangle may cover, the block's tiles dealt out
// among TS_BIN_CHUNK threads (bin_block_tile), dispatched indirectly (big_dispatch, which setup
// and clip raise as they append).
#include "bindings.glsl"
#include "raster_common.glsl"

layout(local_size_x = TS_GROUP_SIZE) in;

void main() {
  uint e = gl_GlobalInvocationID.x / TS_BIN_CHUNK;
  if (e >= min(counters[batch.index].big_tris, frame.raster_capacity)) return;
  uvec2 entry = big_list[e];
  ivec2 first, size;
  bin_entry_block(entry.y, first, size);
  uint tiles = uint(size.x * size.y);
  uint k = gl_GlobalInvocationID.x % TS_BIN_CHUNK;
  if (k >= tiles) return;
  RasterTri t = load_raster_tri(entry.x);
  for (; k < tiles; k += TS_BIN_CHUNK) {
    ivec2 tile = bin_block_tile(first, size, k);
    if (tile_may_overlap(t, tile)) atomicAdd(tile_counts[uint(tile.y) * frame.tiles.x + uint(tile.x)], 1u);
  }
}
