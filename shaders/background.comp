#version 460
#extension GL_GOOGLE_include_directive : require
// The background's stored and display colours (GpuBackground), one thread, recorded by the
// renderer whenever what they depend on changed (the background colour, the exposure, the view,
// the tone map, the HDR format's limit and rounding). The shading pass stores them for every
// pixel no triangle covers while the background is one colour, instead of tone-mapping and
// encoding each of them (on the H200 at 1920x1080 that was 8 us of one sphere's 0.08 ms frame).
// The same functions of the same frame constants as the shading pass's own, so the same bits.
#include "bindings.glsl"
#include "display.glsl"
#include "pixel_colour.glsl"

layout(local_size_x = 1) in;

void main() {
  vec3 value = stored(frame.background);
  background_colours.stored = vec4(value, 1.0);
  background_colours.display = vec4(display_colour(as_stored(value)), 1.0);
}
