#version 460
#extension GL_GOOGLE_include_directive : require
// Resolve: tone mapping and sRGB encoding of the HDR image into the RGBA8 image. The window
// binds a swapchain image there instead (compute/present.cpp), viewed as R8G8B8A8_UNORM: its
// bytes are the sRGB-encoded ones whether the swapchain is UNORM or sRGB.
#include "bindings.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

// A B8G8R8A8 swapchain image holds blue in its first byte; through its R8G8B8A8 view the store
// swaps red and blue so that each byte holds the channel the presentation engine reads there.
layout(constant_id = TS_SPEC_OUTPUT_BGRA) const bool OUTPUT_BGRA = false;

// Narkowicz 2015, "ACES Filmic Tone Mapping Curve": a fit of the ACES reference rendering
// transform's luminance response.
vec3 tonemap_aces(vec3 x) {
  return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

// Reinhard et al. 2002, "Photographic Tone Reproduction for Digital Images", per channel.
vec3 tonemap_reinhard(vec3 x) {
  return x / (1.0 + x);
}

// IEC 61966-2-1 sRGB transfer function.
vec3 srgb_encode(vec3 c) {
  vec3 lo = 12.92 * c;
  vec3 hi = 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055;
  return mix(hi, lo, lessThanEqual(c, vec3(0.0031308)));
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, ivec2(frame.image_size)))) return;
  // The shading pass already applied the exposure (pre-exposure, bindings.glsl).
  vec3 hdr = max(texelFetch(hdr_texture, pixel, 0).rgb, vec3(0.0));
  // Debug views hold values in [0, 1] meant to be seen as they are: no curve.
  bool shaded = frame.view == TS_VIEW_SHADED;
  uint op = shaded ? frame.tonemap : TS_TONEMAP_CLAMP;
  vec3 mapped = op == TS_TONEMAP_ACES       ? tonemap_aces(hdr)
                : op == TS_TONEMAP_REINHARD ? tonemap_reinhard(hdr)
                                            : clamp(hdr, 0.0, 1.0);
  vec3 encoded = srgb_encode(mapped);
  imageStore(ldr_image, pixel, vec4(OUTPUT_BGRA ? encoded.bgr : encoded, 1.0));
}
