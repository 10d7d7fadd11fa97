#version 460
#extension GL_GOOGLE_include_directive : require
// Shading at one sample per pixel: one thread per pixel. Reads the visibility buffer, rebuilds
// the visible triangle in world space, intersects the pixel's camera ray with it for
// perspective-correct barycentrics and texture footprints, applies the material's texture maps,
// and evaluates the shading model (lighting.glsl) into linear HDR. Empty pixels get the
// background: the environment along the pixel's ray, or the scene's background colour.
// Several samples per pixel are shaded by shade_samples.comp, a module of its own because a
// driver translates a module whole before specialization folds the unused path away: on
// lavapipe the multi-sample code cost every one-sample shading pipeline about 0.35 of its 1.3
// CPU seconds (docs/development.md, "Measured CI time").
#include "bindings.glsl"
#include "material.glsl"
#include "lighting.glsl"
#include "raster_common.glsl"
#include "display.glsl"
#include "pixel_colour.glsl"
#include "shade_tiles.glsl"
#include "shade_pixel.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

// SHADE_TILES (raster_common.glsl): TS_SHADE_TILES_OFF dispatches a workgroup per 8x8 pixels of
// the image; TS_SHADE_TILES_DRAWN one per 8x8 pixels of each tile list_tiles found drawn into
// (shade_background.comp takes the others).

void main() {
  ivec2 origin;
  if (!block_origin(origin)) return;
  reset_tile_bound(origin);
  ivec2 pixel = origin + ivec2(gl_LocalInvocationID.xy);
  if (!all(lessThan(pixel, ivec2(frame.image_size)))) return;
  uint64_t key = visibility[pixel_index(pixel)];
  // Emptied for the next frame, which then need not fill the buffer (GpuFrame.reset_visibility):
  // only covered pixels are written, on a line this thread has just read.
  if (frame.reset_visibility != 0u && key != TS_VIS_EMPTY) visibility[pixel_index(pixel)] = TS_VIS_EMPTY;
  shade_one_sample_pixel(pixel, key);
}
