// BRDF terms, one function per physical term, and the variants built from them.
// Conventions: roughness is perceptual, alpha = roughness^2 (Burley 2012); all cosines are
// clamped by the caller as documented in shade.comp.

const float PI = 3.14159265358979323846;

// Smallest perceptual roughness used: below it alpha^2 underflows the GGX denominator in fp32
// and a point light's highlight collapses to a single sample (Filament uses 0.045 for fp32).
const float MIN_PERCEPTUAL_ROUGHNESS = 0.045;
// Smallest N.V used: at a silhouette N.V reaches 0 and the specular term divides by it.
const float MIN_N_DOT_V = 1e-4;
// Smallest squared light distance, in m^2 (1 cm): a light on the surface would divide by zero.
const float MIN_LIGHT_DISTANCE_SQUARED = 1e-4;
// Smallest classic attenuation denominator Kc + Kl d + Kq d^2: it is 0 at d = 0 when Kc = 0.
const float MIN_ATTENUATION_DENOMINATOR = 1e-4;

// GGX / Trowbridge-Reitz normal distribution (Walter et al. 2007, "Microfacet Models for
// Refraction through Rough Surfaces"). With alpha >= 0.045^2 the denominator stays >= alpha^4 > 0.
float D_GGX(float NoH, float alpha) {
  float a2 = alpha * alpha;
  float f = (NoH * a2 - NoH) * NoH + 1.0;
  return a2 / (PI * f * f);
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
// N.V >= MIN_N_DOT_V, N.L > 0 and alpha > 0 the denominator is positive.
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
// leaves (lighting.glsl computes both factors from the DFG table). Not for Blinn-Phong.
layout(constant_id = TS_SPEC_ENERGY_COMPENSATION) const bool ENERGY_COMPENSATION = false;

// Outgoing radiance towards V from one light of incident radiance `radiance` arriving along L:
// f(L, V) * radiance * N.L. N, V, L unit; NoV already clamped to >= MIN_N_DOT_V.
// `specular_scale` multiplies the specular lobe: the energy compensation factor, or 1.
// `diffuse_layer` replaces the diffuse lobe's Fresnel weight when ENERGY_COMPENSATION is on
// (Kulla & Conty's (1 - E(mu_o))(1 - E(mu_i)) / (1 - E_avg), for both variants); else unused.
vec3 surface_response(vec3 N, vec3 V, vec3 L, float NoV, vec3 base_color, float metallic,
                      float roughness, vec3 radiance, vec3 specular_scale, vec3 diffuse_layer) {
  float NoL = dot(N, L);
  if (NoL <= 0.0) return vec3(0.0);  // light below the horizon contributes nothing
  // V + L vanishes only for a light exactly opposite the viewer, already excluded for
  // front-facing samples; fall back to N rather than normalise a zero vector.
  vec3 h = V + L;
  float h2 = dot(h, h);
  vec3 H = h2 > 0.0 ? h * inversesqrt(h2) : N;
  float NoH = clamp(dot(N, H), 0.0, 1.0);
  float VoH = clamp(dot(V, H), 0.0, 1.0);

  float alpha = roughness * roughness;
  vec3 f0 = mix(vec3(0.04), base_color, metallic);
  vec3 diffuse_color = (1.0 - metallic) * base_color;
  vec3 f;
  if (BRDF_VARIANT == TS_BRDF_BLINN_PHONG) {
    // The non-physical baseline: no Fresnel, no geometry term.
    f = diffuse_color * Fd_Lambert() + f0 * D_BlinnPhong(NoH, alpha);
  } else {
    vec3 F = F_Schlick(VoH, f0);
    float D = D_GGX(NoH, alpha);
    if (ENERGY_COMPENSATION) {
      float vis = BRDF_VARIANT == TS_BRDF_FILAMENT ? V_SmithGGXCorrelated(NoV, NoL, alpha)
                                                   : V_SmithSchlickGGX(NoV, NoL, roughness);
      f = diffuse_layer * diffuse_color * Fd_Lambert() + D * vis * F * specular_scale;
    } else if (BRDF_VARIANT == TS_BRDF_FILAMENT) {
      f = diffuse_color * Fd_Lambert() + D * V_SmithGGXCorrelated(NoV, NoL, alpha) * F * specular_scale;
    } else {
      f = (vec3(1.0) - F) * diffuse_color * Fd_Lambert() +
          D * V_SmithSchlickGGX(NoV, NoL, roughness) * F * specular_scale;
    }
  }
  return f * radiance * NoL;
}
