// BRDF terms, one function per physical term, and the variants built from them.
// Conventions: roughness is perceptual, alpha = roughness^2 (Burley 2012). The guards
// (TS_MIN_*) are in shaders/shared/constants.h, shared with the reference renderer.
// The structure follows Filament's surfaceShading(PixelParams, Light, ...): a surface point,
// the shading parameters of its material and one light's sample, each a struct, so a new
// material parameter or light changes a struct and the code that uses it, not every signature.

#ifndef TESSERA_BRDF_GLSL
#define TESSERA_BRDF_GLSL

const float PI = 3.14159265358979323846;

// Where and from where a surface point is seen.
struct ShadingPoint {
  vec3 P;     // world position
  vec3 N;     // unit shading normal
  vec3 V;     // unit direction towards the viewer
  float NoV;  // N.V clamped to >= TS_MIN_N_DOT_V
};

// The shading parameters of a material at a point (Filament's PixelParams), derived once per
// pixel from the material's factors and maps.
struct PixelParams {
  vec3 diffuse_color;   // Lambert albedo: (1 - metallic) base colour
  vec3 f0;              // specular reflectance at normal incidence
  float roughness;      // perceptual, clamped to [TS_MIN_PERCEPTUAL_ROUGHNESS, 1]
  float alpha;          // roughness^2
  vec3 specular_scale;  // multiplies the specular lobe: the energy compensation factor, or 1
  // With ENERGY_COMPENSATION: the diffuse layer's weight, which replaces the classic 1 - F
  // (Kulla & Conty's (1 - Es(mu_o))(1 - Es(mu_i)) / (1 - Es_avg), lighting.glsl); else unused.
  vec3 diffuse_layer;
};

// The light arriving at a point from one light.
struct LightSample {
  vec3 L;         // unit direction towards the light
  vec3 radiance;  // incident radiance along L (after falloff and cone)
};

// The shading parameters of the glTF 2.0 metallic-roughness model (Burley 2012): dielectrics
// reflect TS_DIELECTRIC_F0 specularly and their base colour diffusely, metals reflect their
// base colour specularly. Factors outside [0, 1] are clamped.
PixelParams metallic_roughness_params(vec3 base_color, float metallic, float roughness) {
  PixelParams p;
  float m = clamp(metallic, 0.0, 1.0);
  p.roughness = clamp(roughness, TS_MIN_PERCEPTUAL_ROUGHNESS, 1.0);
  p.alpha = p.roughness * p.roughness;
  p.f0 = mix(vec3(TS_DIELECTRIC_F0), base_color, m);
  p.diffuse_color = (1.0 - m) * base_color;
  p.specular_scale = vec3(1.0);
  p.diffuse_layer = vec3(1.0);
  return p;
}

// GGX / Trowbridge-Reitz normal distribution (Walter et al. 2007, "Microfacet Models for
// Refraction through Rough Surfaces"), D = alpha^2 / (pi ((N.H)^2 (alpha^2 - 1) + 1)^2), with
// the bracket written as sin2_NH + (N.H alpha)^2, sin2_NH = 1 - (N.H)^2 = |N x H|^2 given by
// the caller (Lagrange's identity, as Filament computes it). The textbook form loses 1 - (N.H)^2
// to cancellation where N.H is near 1, which is where a smooth surface's lobe lies: at the
// smallest roughness, 0.045 (alpha^2 = 4.1e-6), a float N.H's rounding (about 1.2e-7 in
// 1 - (N.H)^2) moved the bracket by about 3 % and a point light's highlight peak by up to 4 of
// 255 levels. For unit N and H the bracket is >= alpha^2 > 0.
float D_GGX(float NoH, float sin2_NH, float alpha) {
  float a = NoH * alpha;
  float k = alpha / (sin2_NH + a * a);
  return k * k * (1.0 / PI);
}

// Smith geometry term with the Schlick-GGX approximation for analytic lights,
// k = (roughness + 1)^2 / 8 (Schlick 1994; Karis 2013, "Real Shading in Unreal Engine 4"),
// folded with the 1 / (4 N.L N.V) of the Cook-Torrance denominator. Folding cancels N.L and
// N.V analytically, so no division by a vanishing cosine remains.
float V_SmithSchlickGGX(float NoV, float NoL, float roughness) {
  float k = (roughness + 1.0) * (roughness + 1.0) / 8.0;
  return 0.25 / ((NoV * (1.0 - k) + k) * (NoL * (1.0 - k) + k));
}

// Schlick's Fresnel approximation (Schlick 1994, "An Inexpensive BRDF Model for Physically-based
// Rendering"), evaluated on V.H.
vec3 F_Schlick(float VoH, vec3 f0) {
  float f = pow(1.0 - VoH, 5.0);
  return f0 + (vec3(1.0) - f0) * f;
}

// Height-correlated Smith visibility V = G / (4 N.L N.V) for GGX (Heitz 2014, "Understanding
// the Masking-Shadowing Function in Microfacet-Based BRDFs"; the form Filament uses). With
// N.V >= TS_MIN_N_DOT_V, N.L > 0 and alpha > 0 the denominator is positive.
float V_SmithGGXCorrelated(float NoV, float NoL, float alpha) {
  float a2 = alpha * alpha;
  float lambda_v = NoL * sqrt(NoV * NoV * (1.0 - a2) + a2);
  float lambda_l = NoV * sqrt(NoL * NoL * (1.0 - a2) + a2);
  return 0.5 / (lambda_v + lambda_l);
}

// Normalized Blinn-Phong lobe (n + 8) / (8 pi) (N.H)^n (Akenine-Moeller et al., "Real-Time
// Rendering", 3rd ed., 7.6), with the exponent matched to GGX by n = 2 / alpha^2 - 2 (Walter et
// al. 2007). alpha >= 0.045^2 keeps n below 5e5, finite in fp32.
float D_BlinnPhong(float NoH, float alpha) {
  float n = 2.0 / (alpha * alpha) - 2.0;
  return (n + 8.0) / (8.0 * PI) * pow(NoH, n);
}

// Lambertian diffuse lobe (Lambert 1760).
float Fd_Lambert() {
  return 1.0 / PI;
}

// The BRDF variant, chosen when the pipeline is built (TS_BRDF_*).
layout(constant_id = TS_SPEC_BRDF) const uint BRDF_VARIANT = TS_BRDF_CLASSIC;

// Energy-conserving layering (--energy-compensation): the specular lobe is scaled up for its
// lost multiple scattering and the diffuse layer takes only the energy the specular layer
// leaves (PixelParams' specular_scale and diffuse_layer, from the DFG table in lighting.glsl).
// Not for Blinn-Phong.
layout(constant_id = TS_SPEC_ENERGY_COMPENSATION) const bool ENERGY_COMPENSATION = false;

// Outgoing radiance towards s.V from one light: f(L, V) * radiance * N.L.
vec3 surface_response(ShadingPoint s, PixelParams p, LightSample light) {
  vec3 N = s.N, V = s.V, L = light.L;
  float NoL = dot(N, L);
  if (NoL <= 0.0) return vec3(0.0);  // light below the horizon contributes nothing
  // V + L vanishes only for a light exactly opposite the viewer, already excluded for
  // front-facing samples; fall back to N rather than normalise a zero vector.
  vec3 h = V + L;
  float h2 = dot(h, h);
  vec3 H = h2 > 0.0 ? h * inversesqrt(h2) : N;
  float NoH = clamp(dot(N, H), 0.0, 1.0);
  float VoH = clamp(dot(V, H), 0.0, 1.0);

  vec3 f;
  if (BRDF_VARIANT == TS_BRDF_BLINN_PHONG) {
    // The non-physical baseline: no Fresnel, no geometry term.
    f = p.diffuse_color * Fd_Lambert() + p.f0 * D_BlinnPhong(NoH, p.alpha);
  } else {
    vec3 F = F_Schlick(VoH, p.f0);
    // Where N.H was clamped up to 0 (H below the surface, at silhouettes) the lobe takes its
    // value at N.H = 0, as the textbook form of the clamped N.H did: sin^2 = 1.
    vec3 NxH = cross(N, H);
    float D = D_GGX(NoH, NoH > 0.0 ? dot(NxH, NxH) : 1.0, p.alpha);
    if (ENERGY_COMPENSATION) {
      float vis = BRDF_VARIANT == TS_BRDF_FILAMENT ? V_SmithGGXCorrelated(s.NoV, NoL, p.alpha)
                                                   : V_SmithSchlickGGX(s.NoV, NoL, p.roughness);
      f = p.diffuse_layer * p.diffuse_color * Fd_Lambert() + D * vis * F * p.specular_scale;
    } else if (BRDF_VARIANT == TS_BRDF_FILAMENT) {
      f = p.diffuse_color * Fd_Lambert() + D * V_SmithGGXCorrelated(s.NoV, NoL, p.alpha) * F * p.specular_scale;
    } else {
      f = (vec3(1.0) - F) * p.diffuse_color * Fd_Lambert() +
          D * V_SmithSchlickGGX(s.NoV, NoL, p.roughness) * F * p.specular_scale;
    }
  }
  return f * light.radiance * NoL;
}

#endif  // TESSERA_BRDF_GLSL
