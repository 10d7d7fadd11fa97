#version 460
#extension GL_GOOGLE_include_directive : require
// Stores four values into texel (0, 0) of the HDR image that tell how its RGBA16F stores round
// (Vulkan allows to nearest even or toward zero), so that the shading pass can resolve from the
// value the image holds (display.glsl's as_stored). Read back by Renderer's probe_hdr_rounding,
// which expects, to nearest even / toward zero (fp16 bits):
//   1 + 3 * 2^-12 (3/4 of the way to 1 + 2^-10)       0x3C01 / 0x3C00
//   its negative                                          0xBC01 / 0xBC00
//   1 + 3 * 2^-11 (a tie between 1 + 2^-10 and 1 + 2^-9)  0x3C02 / 0x3C01
//   2^-20 + 3 * 2^-26 (3/4 of a subnormal step above 2^-20) 0x0011 / 0x0010 (0x0000 if flushed)
#include "bindings.glsl"

layout(local_size_x = 1) in;

void main() {
  float above_one = 1.0 + 3.0 / 4096.0;
  imageStore(hdr_image, ivec2(0), vec4(above_one, -above_one, 1.0 + 3.0 / 2048.0, ldexp(1.0, -20) + 3.0 * ldexp(1.0, -26)));
}
