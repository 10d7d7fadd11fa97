#version 460
#extension GL_GOOGLE_include_directive : require
// Tests only: evaluates the shading model's BRDF (brdf.glsl, the code the shading pass runs)
// for given directions, so it can be checked against formulas, for reciprocity and for energy.
#include "shared/gpu_types.h"
#include "brdf.glsl"

layout(local_size_x = 64) in;

// Per sample: n, v, l (xyz, unit) and (base colour rgb, metallic), then roughness in x.
layout(set = 0, binding = 0, std430) readonly buffer Samples { vec4 samples[]; };
layout(set = 0, binding = 1, std430) writeonly buffer Results { vec4 results[]; };
layout(push_constant) uniform Count { uint count; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= count) return;
  vec3 n = samples[i * 5].xyz;
  vec3 v = samples[i * 5 + 1].xyz;
  vec3 l = samples[i * 5 + 2].xyz;
  vec4 material = samples[i * 5 + 3];
  float roughness = clamp(samples[i * 5 + 4].x, MIN_PERCEPTUAL_ROUGHNESS, 1.0);
  float NoV = max(dot(n, v), MIN_N_DOT_V);
  // f(l, v) * N.L for unit incident radiance, as the shading pass computes it.
  results[i] = vec4(surface_response(n, v, l, NoV, material.rgb, clamp(material.a, 0.0, 1.0), roughness, vec3(1.0), vec3(1.0), vec3(1.0)), 0.0);
}
