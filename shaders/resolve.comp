#version 460
#extension GL_GOOGLE_include_directive : require
// Resolve: tone mapping and sRGB encoding of the HDR image into the RGBA8 image. The window
// binds a swapchain image there instead (compute/present.cpp), viewed as R8G8B8A8_UNORM: its
// bytes are the sRGB-encoded ones whether the swapchain is UNORM or sRGB.
#include "bindings.glsl"
#include "display.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

// A B8G8R8A8 swapchain image holds blue in its first byte; through its R8G8B8A8 view the store
// swaps red and blue so that each byte holds the channel the presentation engine reads there.
layout(constant_id = TS_SPEC_OUTPUT_BGRA) const bool OUTPUT_BGRA = false;

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, ivec2(frame.image_size)))) return;
  vec3 encoded = display_colour(texelFetch(hdr_texture, pixel, 0).rgb);
  imageStore(ldr_image, pixel, vec4(OUTPUT_BGRA ? encoded.bgr : encoded, 1.0));
}
