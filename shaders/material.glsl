// A material at a surface point: its factors times its texture maps, and the shading normal
// with the normal map applied. Shared by the compute shading pass and the graphics baseline.
// Needs bindings.glsl; the mirror in the reference is resolve_material (reference_renderer.cpp).
#include "texture.glsl"

// Maps this pipeline can sample (TS_MAP_* bits). The generic pipeline keeps them all and tests
// each material's map index at run time; a pipeline specialized to a scene drops the code of
// maps no material of the scene uses.
layout(constant_id = TS_SPEC_TEXTURE_MAPS) const uint TEXTURE_MAPS = TS_MAP_ALL;

// Smallest N.V a normal map may leave. A mapped normal can face away from the viewer (a steep
// bump near a silhouette); shading it would light the surface from below its horizon and make
// the clamped N.V of the specular term blow up. Such a normal is bent back towards V until
// N.V = 0.01 (about 0.6 degrees above the horizon), which keeps the image continuous.
const float MIN_MAPPED_N_DOT_V = 0.01;

// Where and how a pixel sees a surface, before the material is applied.
struct SurfaceGeometry {
  vec3 P;        // world position
  vec3 N;        // unit interpolated normal (world)
  vec4 T;        // interpolated tangent (world, not unit) and handedness
  vec2 uv;
  vec2 duv_dx;   // uv change for one pixel step right
  vec2 duv_dy;   // and down
};

struct MaterialSample {
  vec3 base_color;
  float metallic;
  float roughness;
  float occlusion;
  vec3 emissive;
  vec3 N;  // shading normal
};

bool has_map(uint bit, uint index) {
  return (TEXTURE_MAPS & bit) != 0u && index != TS_NO_TEXTURE;
}

// Tangent-space normal `local` (unit-ish) to world, around the geometric frame of g.
vec3 apply_normal_map(SurfaceGeometry g, vec3 local, float scale, vec3 V) {
  vec3 tangent = g.T.xyz - g.N * dot(g.N, g.T.xyz);  // Gram-Schmidt against the normal
  float t2 = dot(tangent, tangent);
  // No usable tangent (a mesh without a uv gradient here): keep the interpolated normal.
  if (t2 <= 1e-20) return g.N;
  tangent *= inversesqrt(t2);
  vec3 bitangent = g.T.w * cross(g.N, tangent);
  vec3 mapped = tangent * (local.x * scale) + bitangent * (local.y * scale) + g.N * local.z;
  float m2 = dot(mapped, mapped);
  // A texel of (0.5, 0.5, 0.5) encodes the zero vector: nothing to normalize.
  if (m2 <= 1e-20) return g.N;
  vec3 n = mapped * inversesqrt(m2);
  float nv = dot(n, V);
  if (nv < MIN_MAPPED_N_DOT_V) n = normalize(n + V * (MIN_MAPPED_N_DOT_V - nv));
  return n;
}

MaterialSample evaluate_material(uint index, SurfaceGeometry g, vec3 V) {
  GpuMaterial m = materials[index];
  MaterialSample s;
  s.base_color = m.base_color.rgb;
  s.metallic = m.metallic;
  s.roughness = m.roughness;
  s.occlusion = m.emissive_occlusion.a;
  s.emissive = m.emissive_occlusion.rgb;
  s.N = g.N;
  if (has_map(TS_MAP_BASE_COLOR, m.maps.x)) {
    s.base_color *= sample_texture(m.maps.x, g.uv, g.duv_dx, g.duv_dy).rgb;
  }
  if (has_map(TS_MAP_METALLIC_ROUGHNESS, m.maps.y)) {
    vec4 t = sample_texture(m.maps.y, g.uv, g.duv_dx, g.duv_dy);
    s.roughness *= t.g;
    s.metallic *= t.b;
  }
  if (has_map(TS_MAP_OCCLUSION, m.maps.w)) {
    s.occlusion *= sample_texture(m.maps.w, g.uv, g.duv_dx, g.duv_dy).r;
  }
  if (has_map(TS_MAP_NORMAL, m.maps.z)) {
    vec3 local = sample_texture(m.maps.z, g.uv, g.duv_dx, g.duv_dy).rgb * 2.0 - 1.0;
    s.N = apply_normal_map(g, local, m.normal_scale, V);
  }
  return s;
}
