// The minimal graphics program's fragment stage (bench/minimal_graphics.cpp), shared by the
// rungs of its ladder that keep its shading: Cook-Torrance (GGX distribution, Schlick-GGX Smith
// geometry with k = (r + 1)^2 / 8, Schlick Fresnel; Karis 2013, "Real Shading in Unreal
// Engine 4") and a Lambert diffuse lobe weighted by 1 - F, for four point lights, plus a
// constant ambient term. The includer declares the inputs and `color`, and defines where the
// data comes from (a uniform block, or storage buffers): EYE, AMBIENT, BASE_COLOR, METALLIC,
// ROUGHNESS (perceptual), LIGHT_POSITION(i) and LIGHT_RADIANCE(i) (intensity times colour,
// W/sr: irradiance is this over d^2), and the varyings world_position and normal.

const float PI = 3.14159265358979;

float distribution_ggx(float NoH, float alpha) {
  float a2 = alpha * alpha;
  float d = NoH * NoH * (a2 - 1.0) + 1.0;
  return a2 / (PI * d * d);
}

float geometry_schlick_ggx(float NoX, float k) {
  return NoX / (NoX * (1.0 - k) + k);
}

vec3 fresnel_schlick(float VoH, vec3 f0) {
  return f0 + (1.0 - f0) * pow(1.0 - VoH, 5.0);
}

void main() {
  vec3 N = normalize(normal);
  vec3 V = normalize(EYE - world_position);
  // Grazing views and mirror-smooth surfaces would divide by zero.
  float NoV = max(dot(N, V), 1e-4);
  float roughness = max(ROUGHNESS, 0.045);
  float alpha = roughness * roughness;
  float k = (roughness + 1.0) * (roughness + 1.0) / 8.0;
  vec3 base = BASE_COLOR;
  float metallic = METALLIC;
  vec3 f0 = mix(vec3(0.04), base, metallic);
  vec3 diffuse = base * (1.0 - metallic) / PI;
  vec3 c = AMBIENT * base;
  for (int i = 0; i < 4; ++i) {
    vec3 to_light = LIGHT_POSITION(i) - world_position;
    float d2 = max(dot(to_light, to_light), 1e-4);
    vec3 L = to_light * inversesqrt(d2);
    float NoL = max(dot(N, L), 0.0);
    vec3 H = normalize(V + L);
    float NoH = max(dot(N, H), 0.0);
    float VoH = max(dot(V, H), 0.0);
    vec3 F = fresnel_schlick(VoH, f0);
    vec3 specular = F * (distribution_ggx(NoH, alpha) * geometry_schlick_ggx(NoV, k) *
                         geometry_schlick_ggx(NoL, k) / (4.0 * NoV * max(NoL, 1e-4)));
    c += ((1.0 - F) * diffuse + specular) * LIGHT_RADIANCE(i) / d2 * NoL;
  }
  color = vec4(min(c, vec3(65504.0)), 1.0);
}
