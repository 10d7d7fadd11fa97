#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require
// Shading by tiles (RendererOptions::shade_tiles): one thread per screen tile lists the tiles
// the rasterizers marked in tile_drawn for the shading pass (shade_tiles from the front) and
// every other tile for its background dispatch (from the back), and builds both indirect
// dispatches (GpuCounters.shade_dispatch, .background_dispatch of batch 0).
// Why: a CPU device such as lavapipe runs every instruction of a shader for every group of 8
// lanes, whatever branch they take, so a pixel that shows only the background costs the whole
// shading code; only not dispatching it saves that (docs/performance.md, "lavapipe against its
// own graphics pipeline"). The lists' order changes from run to run and nothing depends on it:
// each workgroup of either dispatch writes its own pixels alone.
#include "bindings.glsl"
#include "raster_common.glsl"

layout(local_size_x = TS_GROUP_SIZE) in;

// Appends the tiles of the threads whose `take` is true to the drawn list (or the background
// list) and returns this thread's place in it; raises the dispatch's y by the rows of
// frame.tiles.x tiles the appended tiles reach into, so that y ends as ceil(length / row).
// One atomic pair per subgroup, not per thread: one address each, which would serialize.
uint append(bool take, bool background) {
  uvec4 takers = subgroupBallot(take);
  uint count = subgroupBallotBitCount(takers);
  uint base = 0u;
  if (count != 0u && subgroupElect()) {
    base = background ? atomicAdd(counters[0].background_tiles, count)
                      : atomicAdd(counters[0].drawn_tiles, count);
    uint row = frame.tiles.x;
    uint rows = (base + count + row - 1u) / row - (base + row - 1u) / row;
    if (rows != 0u) {
      if (background) {
        atomicAdd(counters[0].background_dispatch.y, rows);
      } else {
        atomicAdd(counters[0].shade_dispatch.y, rows);
      }
    }
  }
  return subgroupBroadcastFirst(base) + subgroupBallotExclusiveBitCount(takers);
}

void main() {
  uint tile = gl_GlobalInvocationID.x;
  uint tiles = frame.tiles.x * frame.tiles.y;
  if (tile == 0u) {
    // A row of the dispatch covers frame.tiles.x listed tiles, each in 8x8-pixel workgroups:
    // at most 4 * 1024 workgroups (TS_MAX_TILES_PER_SIDE), and 1024 rows, within the
    // 65,535 every device allows per dimension, which one row of all listed tiles would exceed.
    uint groups_per_tile = uint(TILE_SIZE / 8) * uint(TILE_SIZE / 8);
    counters[0].shade_dispatch.x = groups_per_tile * frame.tiles.x;
    counters[0].shade_dispatch.z = 1u;
    counters[0].background_dispatch.x = groups_per_tile * frame.tiles.x;
    counters[0].background_dispatch.z = 1u;
    // Silhouette coverage's outline dispatch, which the shading pass sets otherwise at pixel
    // (0, 0), a pixel the background's dispatch may shade (shade.comp).
    counters[0].outline_dispatch.y = 1u;
    counters[0].outline_dispatch.z = 1u;
  }
  bool in_grid = tile < tiles;
  bool drawn = in_grid && tile_drawn[tile] != 0u;
  // Read here and nowhere after: zeroed for the next frame, which then needs no fill.
  if (drawn) tile_drawn[tile] = 0u;
  uint slot = append(drawn, false);
  if (drawn) shade_tiles[slot] = tile;
  slot = append(in_grid && !drawn, true);
  if (in_grid && !drawn) shade_tiles[tiles - 1u - slot] = tile;
}
