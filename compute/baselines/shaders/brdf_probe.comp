#version 460
#extension GL_GOOGLE_include_directive : require
// Tests only: evaluates the shading model's BRDF (brdf.glsl, the code the shading pass runs)
// for given directions, so it can be checked against formulas, for reciprocity and for energy.
#include "shared/gpu_types.h"
#include "brdf.glsl"

layout(local_size_x = 64) in;

layout(set = 0, binding = 0, std430) readonly buffer Samples { GpuBrdfSample samples[]; };
layout(set = 0, binding = 1, std430) writeonly buffer Results { vec4 results[]; };
layout(push_constant) uniform Count { uint count; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= count) return;
  GpuBrdfSample b = samples[i];
  ShadingPoint s;
  s.P = vec3(0.0);
  s.N = b.n;
  s.V = b.v;
  s.NoV = max(dot(b.n, b.v), TS_MIN_N_DOT_V);
  PixelParams p = metallic_roughness_params(b.base_color, b.metallic, b.roughness);
  // f(l, v) * N.L for unit incident radiance, as the shading pass computes it.
  LightSample light;
  light.L = b.l;
  light.radiance = vec3(1.0);
  results[i] = vec4(surface_response(s, p, light), 0.0);
}
