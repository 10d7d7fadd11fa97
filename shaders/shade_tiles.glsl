// Shading by tiles (RendererOptions::shade_tiles): which 8x8 pixels a workgroup of the shading
// pass (shade.comp) or of the background's dispatch (shade_background.comp) takes. Needs
// bindings.glsl and raster_common.glsl (TILE_SIZE, SHADE_TILES).

// The first pixel of this workgroup's 8x8 block; false if its dispatch listed no tile for it.
// TS_SHADE_TILES_OFF: a workgroup per 8x8 pixels of the image. Otherwise a row of the dispatch
// is frame.tiles.x listed tiles (list_tiles.comp), each (TILE_SIZE / 8)^2 workgroups: the drawn
// tiles, listed from the front of shade_tiles, or (TS_SHADE_TILES_BACKGROUND) the others,
// listed from the back.
bool block_origin(out ivec2 origin) {
  origin = ivec2(gl_WorkGroupID.xy) * 8;
  if (SHADE_TILES == TS_SHADE_TILES_OFF) return true;
  uint side = uint(TILE_SIZE / 8);
  uint listed = gl_WorkGroupID.y * frame.tiles.x + gl_WorkGroupID.x / (side * side);
  bool drawn = SHADE_TILES == TS_SHADE_TILES_DRAWN;
  if (listed >= (drawn ? counters[0].drawn_tiles : counters[0].background_tiles)) return false;
  uint tile = shade_tiles[drawn ? listed : frame.tiles.x * frame.tiles.y - 1u - listed];
  uint block = gl_WorkGroupID.x % (side * side);
  origin = ivec2(tile % frame.tiles.x, tile / frame.tiles.x) * TILE_SIZE +
           ivec2(block % side, block / side) * 8;
  return true;
}

// Resets the depth bound of the tile whose first 8x8 block starts at `origin` for the next
// frame, which then needs no fill of tile_far: the rasterizers, which read and lower it, ran
// before this pass. Every tile's first block is shaded once, by one of the dispatches. One thread
// of the block stores; the test is two masks (TILE_SIZE is a power of two), where a division by a
// tile size read from the frame had made the shading pass 4 us slower on the H200.
void reset_tile_bound(ivec2 origin) {
  if (gl_LocalInvocationIndex == 0u && all(equal(origin & (TILE_SIZE - 1), ivec2(0))))
    tile_far[uint(origin.y / TILE_SIZE) * frame.tiles.x + uint(origin.x / TILE_SIZE)] = 0xFFFFFFFFu;
}
