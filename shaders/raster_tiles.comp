#version 460
#extension GL_GOOGLE_include_directive : require
// Rasterizer for large triangles: one workgroup per screen tile, one thread per pixel. Each
// thread keeps the minimum key of each of its samples over the tile's list and writes it with
// a single atomicMin per sample.
#include "bindings.glsl"
#include "raster_common.glsl"

// One thread per pixel of a TILE_SIZE x TILE_SIZE tile (the same specialization constant).
layout(local_size_x_id = TS_SPEC_TILE_SIZE, local_size_y_id = TS_SPEC_TILE_SIZE) in;

void main() {
  ivec2 tile = ivec2(gl_WorkGroupID.xy);
  uint tile_index = uint(tile.y) * frame.tiles.x + uint(tile.x);
  uint count = tile_counts[tile_index];
  if (count == 0u) return;
  uint first = tile_offsets[tile_index];
  uint end = min(first + count, frame.tile_entry_capacity);  // past capacity the frame is redone anyway

  ivec2 pixel = tile * TILE_SIZE + ivec2(gl_LocalInvocationID.xy);
  ivec2 p = pixel_centre(pixel);
  uint64_t best[SAMPLES];
  for (uint s = 0u; s < SAMPLES; ++s) best[s] = TS_VIS_EMPTY;
  for (uint k = first; k < end; ++k) {
    RasterTri t = load_raster_tri(tile_entries[k]);
    // The box is clamped to the image, so this also keeps pixels past the image's edge out.
    if (any(lessThan(pixel, t.box_min)) || any(greaterThan(pixel, t.box_max))) continue;
    Edges centre = edges_at(t, p);
    Thresholds h = thresholds_of(t);
    for (uint s = 0u; s < SAMPLES; ++s) {
      Edges e = edges_moved(t, centre, sample_offset(s) - TS_SUBPIXEL_ONE / 2);
      if (!is_covered(e, h)) continue;
      if (DEBUG_COVERAGE) atomicAdd(coverage[pixel_index(pixel)], 1u);
      best[s] = min(best[s], visibility_key(depth_at(t, e), t.id));
    }
  }
  uint index = pixel_index(pixel);
  for (uint s = 0u; s < SAMPLES; ++s) {
    if (best[s] != TS_VIS_EMPTY) atomicMin(visibility[sample_index(index, s)], best[s]);
  }
}
