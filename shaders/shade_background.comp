#version 460
#extension GL_GOOGLE_include_directive : require
// Shading by tiles (RendererOptions::shade_tiles), the background's dispatch: one thread per
// pixel of the tiles no rasterizer drew into, where every sample is empty, writes the colour
// the shading pass (shade.comp) would write there, without reading the visibility buffer.
// A shader of its own rather than a variant of shade.comp: it holds none of the shading code,
// so lavapipe builds it in a fraction of the time, and one pipeline serves every light
// configuration (the renderer specializes it only to the environment, the sample count and the
// tile size).
#include "bindings.glsl"
#include "raster_common.glsl"
#include "display.glsl"
#include "pixel_colour.glsl"
#include "shade_tiles.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

void main() {
  ivec2 origin;
  if (!block_origin(origin)) return;
  reset_tile_bound(origin);
  ivec2 pixel = origin + ivec2(gl_LocalInvocationID.xy);
  if (any(greaterThanEqual(pixel, ivec2(frame.image_size)))) return;
  if (SAMPLES == 1u && background_is_uniform()) {
    write_background_pixel(pixel);
    return;
  }
  vec3 color = stored(background(vec2(pixel) + 0.5));
  // What shade.comp stores for a pixel of empty samples, in the same arithmetic: with several
  // samples it sums its groups' colours times their weights from zero, the sole group's weight
  // exactly 1 (resolve_samples).
  write_pixel(pixel, SAMPLES > 1u ? vec3(0.0) + color * 1.0 : color);
}
