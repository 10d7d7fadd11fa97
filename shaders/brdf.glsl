// Cook-Torrance microfacet BRDF terms, one function per physical term.
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

// Lambertian diffuse lobe (Lambert 1760).
float Fd_Lambert() {
  return 1.0 / PI;
}

// Outgoing radiance towards V from one light of incident radiance `radiance` arriving along L.
// N, V, L unit; NoV already clamped to >= MIN_N_DOT_V.
vec3 cook_torrance(vec3 N, vec3 V, vec3 L, float NoV, vec3 base_color, float metallic,
                   float roughness, vec3 radiance) {
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
  vec3 F = F_Schlick(VoH, f0);
  vec3 specular = D_GGX(NoH, alpha) * V_SmithSchlickGGX(NoV, NoL, roughness) * F;
  vec3 diffuse = (vec3(1.0) - F) * (1.0 - metallic) * base_color * Fd_Lambert();
  return (diffuse + specular) * radiance * NoL;
}
