#version 460
#extension GL_GOOGLE_include_directive : require
// Tile fill: one thread per bin entry (a block of at most 8x8 tiles of one binned triangle)
// writes the raster-triangle index into the list of every tile of the block it may cover, at a
// slot taken from that tile's cursor. The order inside a list varies from run to run; the
// rasterizer's atomicMin makes the result independent of it.
// With depth rejection, a triangle that covers every sample of a tile also lowers the tile's
// bound (tile_far) to its farthest depth: no sample of the tile ends up farther.
#include "bindings.glsl"
#include "raster_common.glsl"

layout(local_size_x = TS_GROUP_SIZE) in;

void main() {
  uint e = gl_GlobalInvocationID.x;
  if (e >= min(counters[batch.index].big_tris, frame.raster_capacity)) return;
  uvec2 entry = big_list[e];
  RasterTri t = load_raster_tri(entry.x);
  ivec2 origin = ivec2(entry.y & 0x3FFu, (entry.y >> 10) & 0x3FFu);
  ivec2 size = ivec2((entry.y >> 20) & 0xFu, (entry.y >> 24) & 0xFu) + 1;
  for (int ty = origin.y; ty < origin.y + size.y; ++ty) {
    for (int tx = origin.x; tx < origin.x + size.x; ++tx) {
      if (!tile_may_overlap(t, ivec2(tx, ty))) continue;
      uint tile = uint(ty) * frame.tiles.x + uint(tx);
      uint slot = atomicAdd(tile_cursors[tile], 1u);
      if (slot < frame.tile_entry_capacity) tile_entries[slot] = entry.x;
      // The box test first: most triangles cover no tile whole, and it is cheaper than the
      // three edge functions. The box holds every pixel of the image with a covered sample
      // (raster_tiles relies on it), so it holds the tile's pixels in the image if the
      // triangle covers the tile.
      ivec2 tile_min = ivec2(tx, ty) * TILE_SIZE;
      ivec2 tile_max = min(tile_min + (TILE_SIZE - 1), ivec2(frame.image_size) - 1);
      bool box_holds_tile =
          all(lessThanEqual(t.box_min, tile_min)) && all(greaterThanEqual(t.box_max, tile_max));
      if (REJECTION && box_holds_tile && tile_inside(t, ivec2(tx, ty))) {
        uint far_high = farthest_key_high(t.depth);
        // A plain read first skips most atomics: a stale value is never below the true one.
        if (tile_far[tile] > far_high) atomicMin(tile_far[tile], far_high);
      }
    }
  }
}
