#version 460
#extension GL_GOOGLE_include_directive : require
// Tile-list allocation: one thread per screen tile takes a contiguous range of the tile-entry
// array for its tile's count. The ranges come from one atomicAdd per workgroup on the batch's
// entry total, so their order varies from run to run, as the order inside a list already does
// (fill.comp): the rasterizer's atomicMin makes the image independent of both, and the total,
// the only value read back, is a sum and so the same in every order. Unlike a prefix sum in one
// workgroup, this spreads over the whole GPU in one pass. Also writes the indirect dispatch
// sizes of the passes that follow, and with shading by tiles lists the tiles that hold entries
// for the per-tile rasterizer (in shade_tiles, which list_tiles fills anew after the last batch).
#include "bindings.glsl"
#include "raster_common.glsl"

layout(local_size_x = TS_SCAN_GROUP_SIZE) in;

shared uint group_total;
shared uint group_base;

shared uint group_listed;
shared uint group_list_base;

// With shading by tiles (the CPU devices' setting), the per-tile rasterizer runs only over the
// tiles that hold entries, which this pass lists: lavapipe ran a workgroup of the whole pass for
// every tile of the image, 1,024 at 512x512, whether it held an entry or not. Otherwise over
// every tile: on the H200 the list made scatter's counted frames slower (at 10^5 objects, where
// every tile holds entries, raster_tiles 0.922 -> 0.992 ms and scan 0.078 -> 0.084 ms).
const bool LIST_TILES = SHADE_TILES != TS_SHADE_TILES_OFF;

// The per-tile rasterizer's dispatch. Listed tiles: rows of frame.tiles.x workgroups, y (the
// rows) and w (the tiles listed) raised as the list grows, from the zero the counters start
// the frame with.
void write_dispatch_sizes(uint b, bool tiles_used) {
  uint small_count = min(counters[b].small_counts.x, frame.raster_capacity);
  counters[b].small_dispatch = uvec4((small_count + TS_GROUP_SIZE - 1) / TS_GROUP_SIZE, 1, 1, 0);
  if (LIST_TILES) {
    counters[b].tiles_dispatch.x = tiles_used ? frame.tiles.x : 0u;
    counters[b].tiles_dispatch.z = 1u;
  } else {
    counters[b].tiles_dispatch = tiles_used ? uvec4(frame.tiles.x, frame.tiles.y, 1, 0) : uvec4(0, 1, 1, 0);
  }
}

void main() {
  uint tile = gl_GlobalInvocationID.x;
  bool binned = counters[batch.index].big_tris != 0u;
  if (gl_GlobalInvocationID.x == 0u) write_dispatch_sizes(batch.index, binned);
  // Nothing binned (the common case for small triangles): every count is 0, the offsets are
  // never read and the tile passes are skipped.
  if (!binned) return;
  if (gl_LocalInvocationIndex == 0u) {
    group_total = 0u;
    group_listed = 0u;
  }
  barrier();
  uint count = tile < frame.tiles.x * frame.tiles.y ? tile_counts[tile] : 0u;
  uint local = count != 0u ? atomicAdd(group_total, count) : 0u;
  uint listed = LIST_TILES && count != 0u ? atomicAdd(group_listed, 1u) : 0u;
  barrier();
  if (gl_LocalInvocationIndex == 0u) {
    group_base = group_total != 0u ? atomicAdd(counters[batch.index].tile_entries, group_total) : 0u;
    uint n = LIST_TILES ? group_listed : 0u;
    uint base = n != 0u ? atomicAdd(counters[batch.index].tiles_dispatch.w, n) : 0u;
    group_list_base = base;
    // The rows this workgroup's tiles reach into that no earlier one did.
    uint row = frame.tiles.x;
    uint rows = (base + n + row - 1u) / row - (base + row - 1u) / row;
    if (rows != 0u) atomicAdd(counters[batch.index].tiles_dispatch.y, rows);
  }
  barrier();
  if (count == 0u) return;  // the rasterizer and fill read no range of an empty tile
  tile_offsets[tile] = group_base + local;
  tile_cursors[tile] = group_base + local;
  // The order varies from run to run; each tile's workgroup is its own, so the image does not.
  if (LIST_TILES) shade_tiles[group_list_base + listed] = tile;
}
