#version 460
#extension GL_GOOGLE_include_directive : require
// Silhouette coverage's second half (FrameSettings::aa_coverage silhouette, several samples per
// pixel): one thread per outline pixel the shading pass listed (TS_BINDING_OUTLINE), one whose
// samples see triangles of one surface and the background. It measures the area of the pixel
// the surface's front faces cover (silhouette_coverage, coverage.glsl) and, where it finds
// one, writes the pixel again: the surface's colour weighted by that area, the background by
// the rest. Where it finds none (-1: two surfaces, or a walk too long), the shading pass's
// counts stay. Each pixel is written by its own thread alone, so the list's order, which
// differs from run to run, changes no bit.
#include "bindings.glsl"
#include "material.glsl"
#include "lighting.glsl"
#include "raster_common.glsl"
#include "coverage.glsl"
#include "display.glsl"
#include "pixel_colour.glsl"

layout(local_size_x = TS_GROUP_SIZE) in;

void main() {
  uint index = gl_GlobalInvocationID.x;
  if (index >= counters[0].outline_pixels) return;
  GpuOutlinePixel listed = outline[index];
  ivec2 pixel = ivec2(listed.pixel & 0xFFFFu, listed.pixel >> 16);
  uint base = sample_index(pixel_index(pixel), 0u);
  uint seen[SAMPLES];
  uint empty = 0u;
  ivec2 offsets = ivec2(0);
  for (uint s = 0u; s < SAMPLES; ++s) {
    seen[s] = uint(visibility[base + s] & 0xFFFFFFFFul);
    if (seen[s] == 0xFFFFFFFFu) {
      empty++;
      offsets += sample_offset(s);
    }
  }
  float covered = silhouette_coverage(pixel, seen);
  if (covered <= 0.0) return;
  // The background as the shading pass shaded it: seen through the mean of the empty samples.
  vec2 point = vec2(pixel) + vec2(offsets) / float(TS_SUBPIXEL_ONE * empty);
  write_pixel(pixel, listed.surface * covered + stored(background(point)) * (1.0 - covered));
}
