#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// Rasterizer for large triangles: one workgroup per screen tile, one thread per pixel, over the
// tile's list (tile_raster.glsl). Each thread writes the minimum key of each of its samples with
// a single atomicMin per sample. With hierarchical depth rejection the bound starts from
// tile_far (the farthest depth of triangles covering the whole tile, written by fill, and
// earlier batches' bounds) and the samples from the visibility buffer (earlier batches).
#include "bindings.glsl"
#include "raster_common.glsl"

// One thread per pixel of a TILE_SIZE x TILE_SIZE tile (the same specialization constant).
layout(local_size_x_id = TS_SPEC_TILE_SIZE, local_size_y_id = TS_SPEC_TILE_SIZE) in;

#include "tile_raster.glsl"

void main() {
  ivec2 tile = ivec2(gl_WorkGroupID.xy);  // a workgroup per tile of the image
  uint tile_index = uint(tile.y) * frame.tiles.x + uint(tile.x);
  if (SHADE_TILES != TS_SHADE_TILES_OFF && frame.tile_list_stride == 0u) {
    // Counted lists with shading by tiles: rows of frame.tiles.x workgroups over the tiles the
    // scan pass listed (scan.comp's LIST_TILES says why).
    if (tile_index >= counters[batch.index].tiles_dispatch.w) return;  // the last row's rest
    tile_index = shade_tiles[tile_index];
    tile = ivec2(tile_index % frame.tiles.x, tile_index / frame.tiles.x);
  }
  uint count = tile_counts[tile_index];
  // The next batch's (or frame's) count pass adds to zeroed counts: every tile with a count is
  // read here (every tile is dispatched, or every tile that holds entries) and nowhere after,
  // so zeroing it here replaces a fill of the buffer and two barriers before each batch.
  barrier();
  if (gl_LocalInvocationIndex == 0u && count != 0u) {
    tile_counts[tile_index] = 0u;
    if (SHADE_TILES != TS_SHADE_TILES_OFF) tile_drawn[tile_index] = 1u;
  }
  if (count == 0u) return;
  // Past a list's room the frame is redone anyway (direct lists: fill.comp).
  uint stride = frame.tile_list_stride;
  uint first = stride != 0u ? tile_index * stride : tile_offsets[tile_index];
  uint end = stride != 0u ? first + min(count, stride) : min(first + count, frame.tile_entry_capacity);

  ivec2 pixel = tile * TILE_SIZE + ivec2(gl_LocalInvocationID.xy);
  ivec2 p = pixel_centre(pixel);
  bool in_image = all(lessThan(uvec2(pixel), frame.image_size));
  uint index = pixel_index(pixel);
  for (uint s = 0u; s < SAMPLES; ++s) {
    best[s] = REJECTION && in_image ? visibility[sample_index(index, s)] : TS_VIS_EMPTY;
  }
  uint bound = REJECTION ? tile_far[tile_index] : 0u;
  uint rejected = rasterize_tile(first, end, pixel, p, in_image, bound);
  // The tile's bound for raster_small and later batches (the last round's reduction).
  if (REJECTION && gl_LocalInvocationIndex == 0u) {
    atomicMin(tile_far[tile_index], bound);
    if (rejected > 0u) atomicAdd(counters[batch.index].rejected_entries, rejected);
  }
  for (uint s = 0u; s < SAMPLES; ++s) {
    if ((changed & (1u << s)) != 0u) atomicMin(visibility[sample_index(index, s)], best[s]);
  }
}
