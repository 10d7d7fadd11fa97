#version 460
#extension GL_GOOGLE_include_directive : require
// One level of the prefiltered specular cube (Karis 2013, "Real Shading in Unreal Engine 4"):
// for each texel's direction R, with N = V = R, the GGX lobe of roughness
// level / (levels - 1) integrated over the environment by importance sampling, weighted by N.L.
// Samples read the equirectangular map's mip level whose texels match the sample's solid angle
// (filtered importance sampling, Krivanek & Colbert 2008), so few samples give a smooth result.
// Level 0 (the mirror) reads the map once along R.
#define TS_ENV_PASS
#include "bindings.glsl"
#include "brdf.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

// Hammersley point i of n (radical inverse in base 2).
vec2 hammersley(uint i, uint n) {
  return vec2((float(i) + 0.5) / float(n), float(bitfieldReverse(i)) * 2.3283064365386963e-10);
}

// Direction through texel centre (x, y) of cube face `face`, inverting Vulkan's cube face
// selection (sc, tc, ma per face as in the specification's cube map table).
vec3 cube_direction(uint face, uvec2 xy, uint size) {
  vec2 st = (vec2(xy) + 0.5) / float(size) * 2.0 - 1.0;
  float a = st.x, b = st.y;
  vec3 d;
  if (face == 0u) d = vec3(1.0, -b, -a);
  else if (face == 1u) d = vec3(-1.0, -b, a);
  else if (face == 2u) d = vec3(a, 1.0, b);
  else if (face == 3u) d = vec3(a, -1.0, -b);
  else if (face == 4u) d = vec3(a, -b, 1.0);
  else d = vec3(-a, -b, -1.0);
  return normalize(d);
}

vec3 environment_at(vec3 d, float lod) {
  return textureLod(env_map, equirect_uv(d), lod).rgb;
}

void main() {
  uvec3 id = gl_GlobalInvocationID;
  uint size = env_pass.size;
  if (id.x >= size || id.y >= size) return;
  vec3 R = cube_direction(id.z, id.xy, size);
  ivec2 map_size = textureSize(env_map, 0);
  // Mean solid angle of a level-0 texel of the map.
  float texel_solid_angle = 4.0 * PI / float(map_size.x * map_size.y);
  vec3 result;
  if (env_pass.level == 0u) {
    // Roughness 0 is a mirror: the map filtered to this cube's texel size.
    float cube_texel = 4.0 * PI / (6.0 * float(size * size));
    result = environment_at(R, max(0.5 * log2(cube_texel / texel_solid_angle), 0.0));
  } else {
    float roughness = max(float(env_pass.level) / float(env_pass.levels - 1u), TS_MIN_PERCEPTUAL_ROUGHNESS);
    float alpha = roughness * roughness;
    // Frame around R.
    vec3 up = abs(R.y) < 0.999 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
    vec3 tx = normalize(cross(up, R));
    vec3 ty = cross(R, tx);
    uint n = env_pass.samples;
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    for (uint i = 0u; i < n; ++i) {
      vec2 u = hammersley(i, n);
      float cos2 = (1.0 - u.x) / (1.0 + (alpha * alpha - 1.0) * u.x);
      float cos_h = sqrt(cos2);
      float sin_h = sqrt(max(1.0 - cos2, 0.0));
      float phi = 2.0 * PI * u.y;
      vec3 H = tx * (sin_h * cos(phi)) + ty * (sin_h * sin(phi)) + R * cos_h;
      vec3 L = 2.0 * dot(R, H) * H - R;
      float NoL = dot(R, L);
      if (NoL <= 0.0) continue;
      // pdf of L with N = V: D(h) / 4; the sample stands for 1 / (n pdf) steradians.
      // 1 - cos2 without its cancellation: alpha^2 u / (1 + (alpha^2 - 1) u).
      float sin2 = alpha * alpha * u.x / (1.0 + (alpha * alpha - 1.0) * u.x);
      float pdf = D_GGX(cos_h, sin2, alpha) * 0.25;
      float sample_solid_angle = 1.0 / (float(n) * pdf);
      float lod = max(0.5 * log2(sample_solid_angle / texel_solid_angle) + 1.0, 0.0);
      sum += environment_at(L, lod) * NoL;
      weight += NoL;
    }
    result = sum / max(weight, 1e-6);
  }
  // Texels of the levels before this one: 6 faces of (base >> l)^2 each.
  uint base = size << env_pass.level;
  uint offset = 0u;
  for (uint l = 0u; l < env_pass.level; ++l) offset += 6u * (base >> l) * (base >> l);
  offset += (id.z * size + id.y) * size + id.x;
  env_texels[offset] = uvec2(packHalf2x16(result.rg), packHalf2x16(vec2(result.b, 1.0)));
}
