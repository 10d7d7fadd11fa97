// The shading model of a surface point: constant ambient, the environment's light (split-sum
// image-based lighting) and Cook-Torrance (brdf.glsl) for every light. Shared by the compute
// shading pass and the graphics baseline's fragment shader, so both do the same work. Needs
// bindings.glsl (frame, lights, environment) and material.glsl (MaterialSample, and through
// it brdf.glsl).

// Multiple-scattering energy compensation (ENERGY_COMPENSATION, brdf.glsl; Kulla & Conty 2017,
// "Revisiting Physically Based Shading at Imageworks"): the specular lobe is scaled by
// 1 + F0 (1 / E - 1) (Filament's form), E its directional albedo with F = 1 from the DFG table,
// and the diffuse layer by (1 - Es(mu_o)) (1 - Es(mu_i)) / (1 - Es_avg), Es the specular layer's
// albedo with Fresnel and that scale: reciprocal, and a white material reflects exactly 1.

#include "ibl_mode.glsl"

// Bilinear lookup in the DFG table of this variant at (N.V, roughness): x the Schlick-weighted
// part of the specular albedo, y the whole albedo with F = 1, z the mean Schlick factor seen
// by a Lambert lobe (dfg.comp).
vec3 dfg_lookup(float NoV, float roughness) {
  uint table = BRDF_VARIANT == TS_BRDF_FILAMENT ? 1u : 0u;
  vec2 p = clamp(vec2(NoV, roughness), 0.0, 1.0) * float(TS_DFG_SIZE - 1);
  uvec2 i0 = uvec2(p);
  uvec2 i1 = min(i0 + 1u, uvec2(TS_DFG_SIZE - 1));
  vec2 t = p - vec2(i0);
  uint base = table * TS_DFG_SIZE * TS_DFG_SIZE;
  vec3 e00 = dfg[base + i0.y * TS_DFG_SIZE + i0.x].xyz, e10 = dfg[base + i0.y * TS_DFG_SIZE + i1.x].xyz;
  vec3 e01 = dfg[base + i1.y * TS_DFG_SIZE + i0.x].xyz, e11 = dfg[base + i1.y * TS_DFG_SIZE + i1.x].xyz;
  return mix(mix(e00, e10, t.x), mix(e01, e11, t.x), t.y);
}

// Cosine-weighted means 2 int g(mu) mu dmu of the table's terms at this roughness (the rows
// after the two tables, dfg.comp): x of E, y of E_Fc, z of E_Fc / E.
vec3 dfg_average(float roughness) {
  uint base = 2u * TS_DFG_SIZE * TS_DFG_SIZE + (BRDF_VARIANT == TS_BRDF_FILAMENT ? TS_DFG_SIZE : 0u);
  float p = clamp(roughness, 0.0, 1.0) * float(TS_DFG_SIZE - 1);
  uint i0 = uint(p);
  uint i1 = min(i0 + 1u, TS_DFG_SIZE - 1u);
  return mix(dfg[base + i0].xyz, dfg[base + i1].xyz, p - float(i0));
}

// Directional albedo Es of the compensated specular layer at one cosine, per channel: the
// Schlick-weighted albedo f0 (E - E_Fc) + E_Fc times the compensation 1 + f0 (1 / E - 1).
// At most 1 in exact arithmetic; the table's noise is clamped away.
vec3 specular_layer_albedo(vec3 dfg_terms, vec3 f0) {
  vec3 single = f0 * (dfg_terms.y - dfg_terms.x) + dfg_terms.x;
  return min(single * (1.0 + f0 * (1.0 / dfg_terms.y - 1.0)), vec3(1.0));
}

// Its cosine-weighted mean Es_avg, expanded in f0 so that one table of means per roughness
// serves every f0: (f0 E + (1 - f0) E_Fc)(1 - f0 + f0 / E) averaged term by term.
vec3 specular_layer_average(vec3 means, vec3 f0) {
  vec3 g = 1.0 - f0;
  return f0 * g * means.x + f0 * f0 + g * g * means.y + f0 * g * means.z;
}

// The view's half of the diffuse layer's weight, (1 - Es(mu_o)) / (1 - Es_avg). Es_avg reaches 1
// only for f0 = 1, a metal without diffuse colour: the floor keeps 0 / 0 away.
vec3 diffuse_layer_view(vec3 dfg_terms, vec3 f0, float roughness) {
  vec3 average = specular_layer_average(dfg_average(roughness), f0);
  return (1.0 - specular_layer_albedo(dfg_terms, f0)) / max(1.0 - average, vec3(1e-4));
}

// Irradiance / pi at normal n from the environment's 9 spherical-harmonic coefficients, the
// cosine convolution already folded in (Ramamoorthi & Hanrahan 2001, "An Efficient
// Representation for Irradiance Environment Maps"). Nine terms ring slightly below zero
// opposite a bright source: clamped, as radiance cannot be negative.
vec3 irradiance_sh(vec3 n) {
  vec3 e = env_irradiance[0].rgb * 0.282095
         + env_irradiance[1].rgb * (0.488603 * n.y)
         + env_irradiance[2].rgb * (0.488603 * n.z)
         + env_irradiance[3].rgb * (0.488603 * n.x)
         + env_irradiance[4].rgb * (1.092548 * n.x * n.y)
         + env_irradiance[5].rgb * (1.092548 * n.y * n.z)
         + env_irradiance[6].rgb * (0.315392 * (3.0 * n.z * n.z - 1.0))
         + env_irradiance[7].rgb * (1.092548 * n.x * n.z)
         + env_irradiance[8].rgb * (0.546274 * (n.x * n.x - n.y * n.y));
  return max(e, vec3(0.0));
}

// Specialization to the scene's lights: with LIGHTS_SPECIALIZED, the lights are sorted by kind
// (in TS_LIGHT_* order) and each kind has its own loop of known length, whose branches the
// compiler resolves; otherwise one loop over frame.light_count lights decides per light.
// The count of kind k is specialization constant TS_SPEC_LIGHT_COUNT_BASE + k.
layout(constant_id = TS_SPEC_LIGHTS_SPECIALIZED) const bool LIGHTS_SPECIALIZED = false;
layout(constant_id = TS_SPEC_LIGHT_COUNT_BASE + TS_LIGHT_POINT) const uint POINT_LIGHTS = 0u;
layout(constant_id = TS_SPEC_LIGHT_COUNT_BASE + TS_LIGHT_SPOT) const uint SPOT_LIGHTS = 0u;
layout(constant_id = TS_SPEC_LIGHT_COUNT_BASE + TS_LIGHT_DIRECTIONAL) const uint DIRECTIONAL_LIGHTS = 0u;

// Smooth fade of an inverse-square light to zero at its range r (Karis 2013):
// saturate(1 - (d/r)^4)^2, with `inv_range4` = 1 / r^4 (0: no range, no fade). d^4 overflows
// fp32 beyond d = 1.4e9 m, and 0 * Inf is NaN: so no range means no arithmetic at all, and
// beyond the range (d^2 >= r^2 = inversesqrt(1 / r^4), at most 1e18 m^2 as r <= 1e9 m) the
// fade is 0 without forming d^4.
float range_fade(float d2, float inv_range4) {
  if (inv_range4 == 0.0) return 1.0;
  if (d2 >= inversesqrt(inv_range4)) return 0.0;
  float fade = clamp(1.0 - d2 * d2 * inv_range4, 0.0, 1.0);
  return fade * fade;
}

// Distance falloff of a light with a position at squared distance d2 (TS_FALLOFF_*). Kc, Kl,
// Kq <= 1e6 and d^2 <= 1.2e31 m^2 (positions within 1e15 m, docs/shading.md) keep every term
// finite.
float distance_attenuation(GpuLight light, float d2) {
  if (light.falloff == TS_FALLOFF_CLASSIC) {
    // A classic light with Kc = 0 would divide by zero at distance 0.
    float d = sqrt(d2);
    return 1.0 / max(light.attenuation.x + light.attenuation.y * d + light.attenuation.z * d2, TS_MIN_ATTENUATION_DENOMINATOR);
  }
  return 1.0 / max(d2, TS_MIN_LIGHT_DISTANCE_SQUARED) * range_fade(d2, light.inv_range4);
}

// What `light` of kind `kind` (a compile-time constant in the specialized loops) sends to the
// surface point P with normal N: one branch per TS_LIGHT_* kind.
LightSample light_sample(GpuLight light, uint kind, vec3 P, vec3 N) {
  LightSample ls;
  if (kind == TS_LIGHT_DIRECTIONAL) {
    ls.L = -light.direction;
    ls.radiance = light.radiance;
    return ls;
  }
  vec3 to_light = light.position - P;
  float d2 = dot(to_light, to_light);  // <= 1.2e31 m^2 for the accepted positions
  // A light exactly on the surface has no direction: treat it as arriving along N.
  ls.L = d2 > 0.0 ? to_light * inversesqrt(d2) : N;
  float attenuation = distance_attenuation(light, d2);
  if (kind == TS_LIGHT_SPOT) {
    // Smooth step between the outer and inner cones, squared as in Filament.
    float spot = clamp(dot(light.direction, -ls.L) * light.cone_scale + light.cone_offset, 0.0, 1.0);
    attenuation *= spot * spot;
  }
  ls.radiance = light.radiance * attenuation;
  return ls;
}

// Light i's contribution; `kind` is a compile-time constant in the specialized loops.
vec3 light_contribution(ShadingPoint s, PixelParams p, uint i, uint kind) {
  LightSample light = light_sample(lights[i], kind, s.P, s.N);
  if (ENERGY_COMPENSATION && BRDF_VARIANT != TS_BRDF_BLINN_PHONG) {
    // The light's half of the reciprocal diffuse weight: 1 - Es(mu_i).
    p.diffuse_layer *= 1.0 - specular_layer_albedo(dfg_lookup(dot(s.N, light.L), p.roughness), p.f0);
  }
  return surface_response(s, p, light);
}

// The environment's light reflected towards V with the split-sum approximation (Karis 2013):
// the prefiltered radiance along the reflection at this roughness times the specular albedo
// from the DFG table, plus the diffuse albedo times the irradiance.
vec3 environment_light(ShadingPoint s, PixelParams p) {
  vec3 R = reflect(-s.V, s.N);
  // A rough lobe leans from R towards N, more so at grazing angles (off-specular peak): look
  // the prefiltered map up along the lobe's dominant direction (Lagarde & de Rousiers 2014,
  // "Moving Frostbite to Physically Based Rendering", listing 22).
  float alpha = p.alpha;
  float smooth_factor = 1.0 - alpha;
  vec3 dominant = normalize(mix(s.N, R, smooth_factor * (sqrt(smooth_factor) + alpha)));
  // Level k of the cube was prefiltered for roughness k / (levels - 1).
  float lod = p.roughness * float(frame.env_levels - 1u);
  vec3 prefiltered = textureLod(env_specular, dominant, lod).rgb;
  vec3 irradiance = irradiance_sh(s.N);
  if (BRDF_VARIANT == TS_BRDF_BLINN_PHONG) return p.diffuse_color * irradiance + p.f0 * prefiltered;
  vec3 dfg_terms = dfg_lookup(s.NoV, p.roughness);
  // Integral of F_Schlick times the lobe: f0 (E - E_Fc) + E_Fc, with E_Fc the Schlick part.
  vec3 specular = (p.f0 * (dfg_terms.y - dfg_terms.x) + dfg_terms.x) * prefiltered * p.specular_scale;
  // The classic model weights diffuse by 1 - F(V.H), F averaged over the cosine lobe:
  // 1 - (f0 + (1 - f0) mean(Fc)) = (1 - f0) (1 - mean(Fc)).
  vec3 kd = BRDF_VARIANT == TS_BRDF_CLASSIC ? (vec3(1.0) - p.f0) * (1.0 - dfg_terms.z) : vec3(1.0);
  // Compensated: the diffuse layer's weight integrated over a uniform sky of cosine-weighted
  // light directions, (1 - Es(mu_o)) (1 - Es_avg) / (1 - Es_avg) = 1 - Es(mu_o).
  if (ENERGY_COMPENSATION) kd = 1.0 - specular_layer_albedo(dfg_terms, p.f0);
  return kd * p.diffuse_color * irradiance + specular;
}

// Radiance leaving surface point P (world) towards the unit direction V (towards the viewer),
// for the material sample `ms` (with its shading normal).
vec3 shade_surface(vec3 P, vec3 V, MaterialSample ms) {
  ShadingPoint s;
  s.P = P;
  s.N = ms.N;
  s.V = V;
  s.NoV = max(dot(s.N, V), TS_MIN_N_DOT_V);
  PixelParams p = ms.pixel;
  if (ENERGY_COMPENSATION && BRDF_VARIANT != TS_BRDF_BLINN_PHONG) {
    // E is at least ~0.07 (classic, grazing, alpha = 1), so the division is safe.
    vec3 dfg_terms = dfg_lookup(s.NoV, p.roughness);
    p.specular_scale = 1.0 + p.f0 * (1.0 / dfg_terms.y - 1.0);
    p.diffuse_layer = diffuse_layer_view(dfg_terms, p.f0, p.roughness);
  }

  // Constant ambient and the environment, dimmed by the material's occlusion, plus what the
  // surface emits.
  vec3 color = frame.ambient * ms.base_color * ms.occlusion + ms.emissive;
  if (ibl_enabled()) color += environment_light(s, p) * ms.occlusion;
  if (LIGHTS_SPECIALIZED) {
    // One loop per kind, in TS_LIGHT_* order (the order of the sorted lights).
    uint first = 0u;
    for (uint i = first; i < first + POINT_LIGHTS; ++i) color += light_contribution(s, p, i, TS_LIGHT_POINT);
    first += POINT_LIGHTS;
    for (uint i = first; i < first + SPOT_LIGHTS; ++i) color += light_contribution(s, p, i, TS_LIGHT_SPOT);
    first += SPOT_LIGHTS;
    for (uint i = first; i < first + DIRECTIONAL_LIGHTS; ++i) color += light_contribution(s, p, i, TS_LIGHT_DIRECTIONAL);
  } else {
    for (uint i = 0u; i < frame.light_count; ++i) color += light_contribution(s, p, i, lights[i].kind);
  }
  return color;
}
