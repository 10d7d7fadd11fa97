#version 460
#extension GL_GOOGLE_include_directive : require
// Ladder rung tessera_brdf (bench/minimal_graphics.cpp): as ladder_varyings.frag, with
// Tessera's BRDF (shaders/brdf.glsl: metallic_roughness_params and surface_response, the
// classic variant the yardstick uses, with their guards) in place of the minimal program's,
// and the minimal program's lights (inverse-square falloff, no range) and ambient term. The
// next rung, the baseline's fragment stage, adds the rest of Tessera's material and lighting
// code (material.glsl, lighting.glsl).
#include "bindings.glsl"
#include "brdf.glsl"

// Nothing here discards or writes depth: hidden fragments are rejected before shading.
layout(early_fragment_tests) in;

layout(location = 0) in vec3 world_position;
layout(location = 1) in vec3 world_normal;
layout(location = 2) flat in uint material;
layout(location = 3) in vec4 world_tangent;
layout(location = 4) in vec2 uv;
layout(location = 5) in vec2 uv1;
layout(location = 0) out vec4 color;

void main() {
  ShadingPoint s;
  s.P = world_position;
  s.N = normalize(world_normal);
  s.V = normalize(frame.camera_position - world_position);
  s.NoV = max(dot(s.N, s.V), TS_MIN_N_DOT_V);
  GpuMaterial m = materials[material];
  PixelParams p = metallic_roughness_params(m.base_color, m.metallic, m.roughness);
  vec3 c = frame.ambient * m.base_color;
  for (uint i = 0u; i < 4u; ++i) {
    vec3 to_light = lights[i].position - world_position;
    float d2 = max(dot(to_light, to_light), TS_MIN_LIGHT_DISTANCE_SQUARED);
    LightSample light;
    light.L = to_light * inversesqrt(d2);
    light.radiance = lights[i].radiance / d2;
    c += surface_response(s, p, light);
  }
  color = vec4(min(c, vec3(TS_MAX_HALF)), 1.0);
}
