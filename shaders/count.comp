#version 460
#extension GL_GOOGLE_include_directive : require
// Tile counting: for every bin entry (a block of at most 8x8 tiles of one binned triangle), adds
// one to the count of each tile of the block the triangle may cover. A fixed grid of threads
// loops over the entries, whose number is known only on the GPU.
#include "bindings.glsl"
#include "raster_common.glsl"

layout(local_size_x = TS_GROUP_SIZE) in;

void main() {
  uint n = min(counters[batch.index].big_tris, frame.raster_capacity);
  for (uint e = gl_GlobalInvocationID.x; e < n; e += TS_COUNT_GROUPS * TS_GROUP_SIZE) {
    uvec2 entry = big_list[e];
    RasterTri t = load_raster_tri(entry.x);
    ivec2 origin = ivec2(entry.y & 0x3FFu, (entry.y >> 10) & 0x3FFu);
    ivec2 size = ivec2((entry.y >> 20) & 0xFu, (entry.y >> 24) & 0xFu) + 1;
    for (int ty = origin.y; ty < origin.y + size.y; ++ty) {
      for (int tx = origin.x; tx < origin.x + size.x; ++tx) {
        if (tile_may_overlap(t, ivec2(tx, ty))) atomicAdd(tile_counts[uint(ty) * frame.tiles.x + uint(tx)], 1u);
      }
    }
  }
}
