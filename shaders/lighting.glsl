// The shading model of a surface point: constant ambient plus Cook-Torrance (brdf.glsl) for
// every light. Shared by the compute shading pass and the graphics baseline's fragment shader,
// so both do the same work. Needs bindings.glsl (frame, lights, materials).
#include "brdf.glsl"

// Multiple-scattering energy compensation (Kulla & Conty 2017, in Filament's form): scales the
// specular lobe by 1 + F0 (1 / E - 1), E the lobe's directional albedo with F = 1 from the DFG
// table, so a white furnace keeps its energy at every roughness. Not for Blinn-Phong.
layout(constant_id = TS_SPEC_ENERGY_COMPENSATION) const bool ENERGY_COMPENSATION = false;

// Bilinear lookup of the specular albedo E(N.V, roughness) in the DFG table of this variant.
float specular_albedo(float NoV, float roughness) {
  uint table = BRDF_VARIANT == TS_BRDF_FILAMENT ? 1u : 0u;
  vec2 p = clamp(vec2(NoV, roughness), 0.0, 1.0) * float(TS_DFG_SIZE - 1);
  uvec2 i0 = uvec2(p);
  uvec2 i1 = min(i0 + 1u, uvec2(TS_DFG_SIZE - 1));
  vec2 t = p - vec2(i0);
  uint base = table * TS_DFG_SIZE * TS_DFG_SIZE;
  float e00 = dfg[base + i0.y * TS_DFG_SIZE + i0.x].y, e10 = dfg[base + i0.y * TS_DFG_SIZE + i1.x].y;
  float e01 = dfg[base + i1.y * TS_DFG_SIZE + i0.x].y, e11 = dfg[base + i1.y * TS_DFG_SIZE + i1.x].y;
  return mix(mix(e00, e10, t.x), mix(e01, e11, t.x), t.y);
}

// Specialization to the scene's lights: with LIGHTS_SPECIALIZED, the lights are sorted by kind
// (point, spot, directional) and each kind has its own loop of known length, whose branches
// the compiler resolves; otherwise one loop over frame.scene_counts.y lights decides per light.
layout(constant_id = TS_SPEC_LIGHTS_SPECIALIZED) const bool LIGHTS_SPECIALIZED = false;
layout(constant_id = TS_SPEC_POINT_LIGHTS) const uint POINT_LIGHTS = 0u;
layout(constant_id = TS_SPEC_SPOT_LIGHTS) const uint SPOT_LIGHTS = 0u;
layout(constant_id = TS_SPEC_DIRECTIONAL_LIGHTS) const uint DIRECTIONAL_LIGHTS = 0u;

struct SurfacePoint {
  vec3 P, N, V;
  float NoV;
  vec3 base_color;
  float metallic, roughness;
  vec3 specular_scale;
};

// Light i's contribution; `kind` is a compile-time constant in the specialized loops.
vec3 light_contribution(SurfacePoint s, uint i, uint kind) {
  GpuLight light = lights[i];
  vec3 L;
  vec3 radiance;
  if (kind == TS_LIGHT_DIRECTIONAL) {
    L = -light.direction.xyz;
    radiance = light.radiance.rgb;
  } else {
    vec3 to_light = light.position.xyz - s.P;
    float d2 = dot(to_light, to_light);
    // A light exactly on the surface has no direction: treat it as arriving along N.
    L = d2 > 0.0 ? to_light * inversesqrt(d2) : s.N;
    float attenuation;
    if (light.kind.y == TS_FALLOFF_CLASSIC) {
      // A classic light with Kc = 0 would divide by zero at distance 0.
      float d = sqrt(d2);
      attenuation = 1.0 / max(light.falloff.y + light.falloff.z * d + light.falloff.w * d2, MIN_ATTENUATION_DENOMINATOR);
    } else {
      attenuation = 1.0 / max(d2, MIN_LIGHT_DISTANCE_SQUARED);
      // Smooth fade to zero at the light's range (Karis 2013): saturate(1 - (d/r)^4)^2.
      float fade = clamp(1.0 - d2 * d2 * light.falloff.x, 0.0, 1.0);
      attenuation *= fade * fade;
    }
    if (kind == TS_LIGHT_SPOT) {
      // Smooth step between the outer and inner cones, squared as in Filament.
      float spot = clamp(dot(light.direction.xyz, -L) * light.cone.x + light.cone.y, 0.0, 1.0);
      attenuation *= spot * spot;
    }
    radiance = light.radiance.rgb * attenuation;
  }
  return surface_response(s.N, s.V, L, s.NoV, s.base_color, s.metallic, s.roughness, radiance, s.specular_scale);
}

// Radiance leaving surface point P (world) with unit normal N towards the unit direction V
// (towards the viewer), for material `material`.
vec3 shade_surface(vec3 P, vec3 N, vec3 V, uint material) {
  GpuMaterial m = materials[material];
  SurfacePoint s;
  s.P = P;
  s.N = N;
  s.V = V;
  s.base_color = m.base_color.rgb;
  s.metallic = clamp(m.metallic, 0.0, 1.0);
  s.roughness = clamp(m.roughness, MIN_PERCEPTUAL_ROUGHNESS, 1.0);
  s.NoV = max(dot(N, V), MIN_N_DOT_V);
  s.specular_scale = vec3(1.0);
  if (ENERGY_COMPENSATION && BRDF_VARIANT != TS_BRDF_BLINN_PHONG) {
    // E is at least ~0.07 (classic, grazing, alpha = 1), so the division is safe.
    vec3 f0 = mix(vec3(0.04), s.base_color, s.metallic);
    s.specular_scale = 1.0 + f0 * (1.0 / specular_albedo(s.NoV, s.roughness) - 1.0);
  }

  // Constant ambient, dimmed by the material's occlusion, plus what the surface emits.
  vec3 color = frame.ambient.rgb * s.base_color * m.emissive_occlusion.a + m.emissive_occlusion.rgb;
  if (LIGHTS_SPECIALIZED) {
    for (uint i = 0u; i < POINT_LIGHTS; ++i) color += light_contribution(s, i, TS_LIGHT_POINT);
    for (uint i = POINT_LIGHTS; i < POINT_LIGHTS + SPOT_LIGHTS; ++i) color += light_contribution(s, i, TS_LIGHT_SPOT);
    for (uint i = POINT_LIGHTS + SPOT_LIGHTS; i < POINT_LIGHTS + SPOT_LIGHTS + DIRECTIONAL_LIGHTS; ++i) {
      color += light_contribution(s, i, TS_LIGHT_DIRECTIONAL);
    }
  } else {
    for (uint i = 0u; i < frame.scene_counts.y; ++i) color += light_contribution(s, i, lights[i].kind.x);
  }
  return color;
}
