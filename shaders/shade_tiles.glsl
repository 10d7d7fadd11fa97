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
