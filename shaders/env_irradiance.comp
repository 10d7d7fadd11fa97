#version 460
#extension GL_GOOGLE_include_directive : require
// Diffuse irradiance of the environment as 9 spherical-harmonic coefficients (Ramamoorthi &
// Hanrahan 2001): the radiance of every texel of one mip level of the equirectangular map,
// weighted by the texel's solid angle, projected on the 9 basis functions, then convolved with
// the clamped cosine (A0 = pi, A1 = 2 pi / 3, A2 = pi / 4) and divided by pi, so the shading
// pass gets irradiance / pi. One workgroup; each thread sums a fixed subset of texels and the
// partial sums are added in a fixed order, so the result is the same on every run.
#define TS_ENV_PASS
#include "bindings.glsl"

layout(local_size_x = 256) in;

const float PI = 3.14159265358979323846;

shared vec3 partial[256];

void main() {
  uint tid = gl_LocalInvocationID.x;
  uint level = env_pass.level;
  ivec2 size = textureSize(env_map, int(level));
  uint count = uint(size.x * size.y);
  vec3 c[9];
  for (int k = 0; k < 9; ++k) c[k] = vec3(0.0);
  for (uint i = tid; i < count; i += 256u) {
    uint x = i % uint(size.x), y = i / uint(size.x);
    float phi = 2.0 * PI * ((float(x) + 0.5) / float(size.x) - 0.5);
    float theta = PI * (float(y) + 0.5) / float(size.y);
    vec3 d = vec3(sin(theta) * sin(phi), cos(theta), -sin(theta) * cos(phi));
    float solid_angle = (2.0 * PI / float(size.x)) * (PI / float(size.y)) * sin(theta);
    vec3 L = texelFetch(env_map, ivec2(x, y), int(level)).rgb * solid_angle;
    c[0] += L * 0.282095;
    c[1] += L * (0.488603 * d.y);
    c[2] += L * (0.488603 * d.z);
    c[3] += L * (0.488603 * d.x);
    c[4] += L * (1.092548 * d.x * d.y);
    c[5] += L * (1.092548 * d.y * d.z);
    c[6] += L * (0.315392 * (3.0 * d.z * d.z - 1.0));
    c[7] += L * (1.092548 * d.x * d.z);
    c[8] += L * (0.546274 * (d.x * d.x - d.y * d.y));
  }
  const float band[3] = float[3](1.0, 2.0 / 3.0, 0.25);  // A_l / pi
  for (int k = 0; k < 9; ++k) {
    partial[tid] = c[k];
    barrier();
    for (uint stride = 128u; stride > 0u; stride >>= 1) {
      if (tid < stride) partial[tid] += partial[tid + stride];
      barrier();
    }
    if (tid == 0u) env_irradiance[k] = vec4(partial[0] * band[k == 0 ? 0 : (k < 4 ? 1 : 2)], 0.0);
    barrier();
  }
}
