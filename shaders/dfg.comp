#version 460
#extension GL_GOOGLE_include_directive : require
// The DFG table, computed once at start-up: for N.V and perceptual roughness on a
// TS_DFG_SIZE^2 grid, the directional albedo of the specular lobe with F = 1 (y) and its
// Schlick-weighted part (x), by importance-sampling GGX (Karis 2013, "Real Shading in Unreal
// Engine 4"). One table per visibility term: classic (Schlick-GGX) and filament (height-
// correlated Smith), selected by the specialization constant TS_SPEC_BRDF. z: the mean of the
// Schlick factor (1 - V.H)^5 over cosine-distributed light directions, which weights the
// classic model's (1 - F) Lambert lobe under a uniform environment. After both tables, one row
// per variant: per roughness, the cosine-weighted means 2 int g(mu) mu dmu of E, E_Fc and
// E_Fc / E over N.V (trapezoid rule on the table's own points), for energy compensation's
// diffuse layer (lighting.glsl). One workgroup per roughness, so the row can be summed.
#include "bindings.glsl"
#include "brdf.glsl"

layout(local_size_x = TS_DFG_SIZE, local_size_y = 1) in;

shared vec3 row_terms[TS_DFG_SIZE];

const uint SAMPLES = 4096u;

// Hammersley point i of n (radical inverse in base 2).
vec2 hammersley(uint i, uint n) {
  return vec2(float(i) / float(n), float(bitfieldReverse(i)) * 2.3283064365386963e-10);
}

void main() {
  uvec2 cell = gl_GlobalInvocationID.xy;  // the dispatch is exactly TS_DFG_SIZE^2
  // Grid points from 0 to 1 inclusive, with the shading pass's own clamps.
  float NoV = max(float(cell.x) / float(TS_DFG_SIZE - 1), TS_MIN_N_DOT_V);
  float roughness = max(float(cell.y) / float(TS_DFG_SIZE - 1), TS_MIN_PERCEPTUAL_ROUGHNESS);
  float alpha = roughness * roughness;
  vec3 V = vec3(sqrt(1.0 - NoV * NoV), 0.0, NoV);
  vec2 sum = vec2(0.0);
  for (uint i = 0u; i < SAMPLES; ++i) {
    vec2 u = hammersley(i, SAMPLES);
    // GGX-distributed half vector: cos^2 theta = (1 - u) / (1 + (alpha^2 - 1) u).
    float cos2 = (1.0 - u.y) / (1.0 + (alpha * alpha - 1.0) * u.y);
    float cos_h = sqrt(cos2);
    float sin_h = sqrt(1.0 - cos2);
    float phi = 2.0 * PI * u.x;
    vec3 H = vec3(sin_h * cos(phi), sin_h * sin(phi), cos_h);
    vec3 L = 2.0 * dot(V, H) * H - V;
    float NoL = L.z;
    if (NoL <= 0.0) continue;
    float VoH = clamp(dot(V, H), 0.0, 1.0);
    float vis = BRDF_VARIANT == TS_BRDF_FILAMENT ? V_SmithGGXCorrelated(NoV, NoL, alpha)
                                                  : V_SmithSchlickGGX(NoV, NoL, roughness);
    // f cos / pdf for pdf = D N.H / (4 V.H): the D cancels.
    float weight = vis * 4.0 * NoL * VoH / cos_h;
    float fc = pow(1.0 - VoH, 5.0);
    sum += vec2(weight * fc, weight);
  }
  float diffuse_fc = 0.0;
  for (uint i = 0u; i < SAMPLES; ++i) {
    vec2 u = hammersley(i, SAMPLES);
    float r = sqrt(u.x);
    float phi = 2.0 * PI * u.y;
    vec3 L = vec3(r * cos(phi), r * sin(phi), sqrt(1.0 - u.x));
    vec3 H = normalize(V + L);
    diffuse_fc += pow(1.0 - clamp(dot(V, H), 0.0, 1.0), 5.0);
  }
  uint table = BRDF_VARIANT == TS_BRDF_FILAMENT ? 1u : 0u;
  vec2 terms = sum / float(SAMPLES);
  dfg[(table * TS_DFG_SIZE + cell.y) * TS_DFG_SIZE + cell.x] = vec4(terms, diffuse_fc / float(SAMPLES), 0.0);

  // E >= ~0.07 everywhere (classic, grazing, alpha = 1), so E_Fc / E is safe.
  row_terms[cell.x] = NoV * vec3(terms.y, terms.x, terms.x / terms.y);
  barrier();
  if (cell.x != 0u) return;
  vec3 integral = 0.5 * (row_terms[0] + row_terms[TS_DFG_SIZE - 1]);
  for (uint i = 1u; i + 1u < TS_DFG_SIZE; ++i) integral += row_terms[i];
  dfg[2u * TS_DFG_SIZE * TS_DFG_SIZE + table * TS_DFG_SIZE + cell.y] =
      vec4(2.0 * integral / float(TS_DFG_SIZE - 1), 0.0);
}
