#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// Rasterization and shading of a small frame in one pass (RendererOptions::raster_shade): one
// workgroup per screen tile, one thread per pixel, one sample. Each workgroup takes every raster
// triangle setup appended whose box meets its tile (tile_raster.glsl's scan_tile), keeps each
// pixel's minimum key, and shades the pixel from it as the shading pass would
// (shade_pixel.glsl). In place of the bin, fill, both rasterizers and shading passes, and of the
// barriers between them: each pass of a frame of few triangles costs a dependent pass's latency
// (about 8 us on the H200) for a few microseconds of work. The keys are those the rasterizers
// would have left in the visibility buffer (every triangle whose box meets a pixel's tile is
// tested against it, and a key is the same whichever rasterizer forms it), so the image is the
// same bits.
#include "bindings.glsl"
#include "material.glsl"
#include "lighting.glsl"
#include "raster_common.glsl"
#include "display.glsl"
#include "pixel_colour.glsl"
#include "shade_pixel.glsl"

layout(local_size_x_id = TS_SPEC_TILE_SIZE, local_size_y_id = TS_SPEC_TILE_SIZE) in;

#include "tile_raster.glsl"

void main() {
  ivec2 tile = ivec2(gl_WorkGroupID.xy);
  ivec2 pixel = tile * TILE_SIZE + ivec2(gl_LocalInvocationID.xy);
  ivec2 p = pixel_centre(pixel);
  bool in_image = all(lessThan(uvec2(pixel), frame.image_size));
  // The frame's visibility buffer starts empty (the last frame's shading emptied it, or the
  // clear filled it), and no other pass of this frame writes it.
  best[0] = TS_VIS_EMPTY;
  scan_tile(tile, 0u, min(counters[0].raster_tris, frame.raster_capacity), pixel, p);
  if (!in_image) return;
  uint64_t key = best[0];
  // Kept for a read-back of the visibility buffer after the frame (GpuFrame.reset_visibility
  // off); otherwise left empty for the next frame.
  if (frame.reset_visibility == 0u && key != TS_VIS_EMPTY) visibility[pixel_index(pixel)] = key;
  shade_one_sample_pixel(pixel, key);
}
