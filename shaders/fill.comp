#version 460
#extension GL_GOOGLE_include_directive : require
// Tile fill: TS_BIN_CHUNK threads per bin entry (a block of at most 8x8 tiles of one binned
// triangle), among which the block's tiles are dealt out (bin_block_tile), write the
// raster-triangle index into the list of every tile of the block it may cover, at a slot taken
// from that tile's cursor. The order inside a list varies from run to
// run; the rasterizer's atomicMin makes the result independent of it.
// With depth rejection, a triangle that covers every sample of a tile also lowers the tile's
// bound (tile_far) to its farthest depth: no sample of the tile ends up farther.
//
// Direct tile lists (frame.tile_list_stride != 0; RendererOptions::tile_lists): no count or
// scan pass ran. Tile t's list is the fixed range [t * stride, (t + 1) * stride) of the entry
// array, and the slot comes from the tile's count itself, which raster_tiles reads (and zeroes)
// as the counted lists' count. A list longer than the stride keeps its first `stride` entries and
// the host, seeing the longest (tile_list_max), redoes the frame with longer lists. This pass
// also adds the batch's entry total, which the scan pass adds for counted lists.
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#include "bindings.glsl"
#include "raster_common.glsl"

layout(local_size_x = TS_GROUP_SIZE) in;

// Fills the lists with thread `k` (0 to TS_BIN_CHUNK - 1) of bin entry `e`'s tiles.
void fill_entry(uint e, uint k, inout uint appended, inout uint longest) {
  uvec2 entry = big_list[e];
  ivec2 first, size;
  bin_entry_block(entry.y, first, size);
  uint tiles = uint(size.x * size.y);
  if (k >= tiles) return;
  RasterTri t = load_raster_tri(entry.x);
  uint stride = frame.tile_list_stride;
  for (; k < tiles; k += TS_BIN_CHUNK) {
    ivec2 tile_xy = bin_block_tile(first, size, k);
    if (!tile_may_overlap(t, tile_xy)) continue;
    uint tile = uint(tile_xy.y) * frame.tiles.x + uint(tile_xy.x);
    if (stride != 0u) {
      uint depth = atomicAdd(tile_counts[tile], 1u);
      if (depth < stride) tile_entries[tile * stride + depth] = entry.x;
      appended++;
      longest = max(longest, depth + 1u);
    } else {
      uint slot = atomicAdd(tile_cursors[tile], 1u);
      if (slot < frame.tile_entry_capacity) tile_entries[slot] = entry.x;
    }
    // The box test first: most triangles cover no tile whole, and it is cheaper than the
    // three edge functions. The box holds every pixel of the image with a covered sample
    // (raster_tiles relies on it), so it holds the tile's pixels in the image if the
    // triangle covers the tile.
    ivec2 tile_min = tile_xy * TILE_SIZE;
    ivec2 tile_max = min(tile_min + (TILE_SIZE - 1), ivec2(frame.image_size) - 1);
    bool box_holds_tile =
        all(lessThanEqual(t.box_min, tile_min)) && all(greaterThanEqual(t.box_max, tile_max));
    if (REJECTION && box_holds_tile && tile_inside(t, tile_xy)) {
      uint far_high = farthest_key_high(t.depth);
      // A plain read first skips most atomics: a stale value is never below the true one.
      if (tile_far[tile] > far_high) atomicMin(tile_far[tile], far_high);
    }
  }
}

// TS_BIN_CHUNK threads per entry, in a loop over the entries: dispatched indirectly (big_dispatch)
// the workgroups cover them all once; dispatched directly, sized by the last frame's entries
// (renderer.cpp's direct_groups), the loop takes as many turns as this frame needs.
void main() {
  uint entries = min(counters[batch.index].big_tris, frame.raster_capacity);
  uint step = gl_NumWorkGroups.x * (TS_GROUP_SIZE / TS_BIN_CHUNK);
  uint k = gl_GlobalInvocationID.x % TS_BIN_CHUNK;
  uint appended = 0u;  // direct lists: entries this thread appended, and the longest list's length
  uint longest = 0u;
  for (uint e = gl_GlobalInvocationID.x / TS_BIN_CHUNK; e < entries; e += step) {
    fill_entry(e, k, appended, longest);
  }
  if (frame.tile_list_stride != 0u) {
    // One atomic per subgroup: per-thread atomics on one address would serialize.
    uint total = subgroupAdd(appended);
    uint deepest = subgroupMax(longest);
    if (subgroupElect() && total > 0u) {
      atomicAdd(counters[batch.index].tile_entries, total);
      atomicMax(counters[batch.index].tile_list_max, deepest);
    }
  }
}
