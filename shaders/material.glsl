// A material at a surface point: its factors times its texture maps, and the shading normal
// with the normal map applied. Shared by the compute shading pass and the graphics baseline.
// Needs bindings.glsl; the mirror in the reference is resolve_material (reference_renderer.cpp).
// A material parameter is read here (from GpuMaterial) and applied to the shading parameters
// (PixelParams) at the end of evaluate_material; the lighting code uses only PixelParams.
// Maps this pipeline can sample (TS_MAP_* bits, with TS_MAP_WRAP_MODES for wrap modes other
// than repeat). The generic pipeline keeps them all and tests each material's map index at run
// time; a pipeline specialized to a scene drops the code of maps no material of the scene uses.
layout(constant_id = TS_SPEC_TEXTURE_MAPS) const uint TEXTURE_MAPS = TS_MAP_ALL;
// Maps that may read uv set 1 (TS_MAP_* bits). Generic: all, tested per material at run time;
// specialized to a scene: the maps its materials read with set 1, usually none, which leaves
// out set 1's fetch and interpolation.
layout(constant_id = TS_SPEC_UV1_MAPS) const uint UV1_MAPS = TS_MAP_ALL;
// 0 in the modules built for pipelines whose TEXTURE_MAPS holds no map (shade_untextured and
// the others of shaders/CMakeLists.txt's VARIANTS): they hold no texture code at all, because a
// driver may translate and inline all of it before specialization would remove it.
#ifndef TS_TEXTURE_MAP_CODE
#define TS_TEXTURE_MAP_CODE 1
#endif

#include "texture.glsl"
#include "brdf.glsl"


// Where and how a pixel sees a surface, before the material is applied.
struct SurfaceGeometry {
  vec3 P;        // world position
  vec3 N;        // unit interpolated normal (world)
  vec4 T;        // interpolated tangent (world, not unit) and handedness
  vec2 uv;
  vec2 duv_dx;   // uv change for one pixel step right
  vec2 duv_dy;   // and down
  vec2 uv1;      // uv set 1 and its footprint, read by the maps of GpuMaterial.uv1_maps
  vec2 duv1_dx;
  vec2 duv1_dy;
};

struct MaterialSample {
  vec3 base_color;  // with its map applied (the ambient term's albedo)
  float occlusion;  // scales ambient and environment light
  vec3 emissive;
  vec3 N;             // shading normal
  PixelParams pixel;  // what the BRDF needs (brdf.glsl)
};

bool has_map(uint bit, uint index) {
  return (TEXTURE_MAPS & bit) != 0u && index != TS_NO_TEXTURE;
}

// True if the material's map `bit` reads uv set 1 (glTF texCoord 1).
bool reads_uv1(GpuMaterial m, uint bit) {
  return (UV1_MAPS & bit) != 0u && (m.uv1_maps & bit) != 0u;
}

// Map `bit` (texture `index`) of material m at g, through the uv set it reads. One call of
// sample_texture, not one per set: drivers inline every call site before specialization
// removes the maps a pipeline leaves out (sample_texture says why that matters).
vec4 sample_map(GpuMaterial m, uint bit, uint index, SurfaceGeometry g) {
  bool set1 = reads_uv1(m, bit);
  return sample_texture(index, set1 ? g.uv1 : g.uv, set1 ? g.duv1_dx : g.duv_dx,
                        set1 ? g.duv1_dy : g.duv_dy);
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
  if (nv < TS_MIN_MAPPED_N_DOT_V) n = normalize(n + V * (TS_MIN_MAPPED_N_DOT_V - nv));
  return n;
}

// A double-sided material's back face is shaded as the front face of a surface turned toward
// the viewer (glTF 2.0 3.9.5): normal and tangent frame flipped (negating the handedness too
// flips the bitangent, w * cross(N, T)). `back`: the pixel sees the triangle's back face.
SurfaceGeometry face_viewer(uint index, SurfaceGeometry g, bool back) {
  if (back && materials[index].double_sided != 0u) {
    g.N = -g.N;
    g.T = -g.T;
  }
  return g;
}

MaterialSample evaluate_material(uint index, SurfaceGeometry g, vec3 V) {
  GpuMaterial m = materials[index];
  MaterialSample s;
  s.base_color = m.base_color;
  float metallic = m.metallic;
  float roughness = m.roughness;
  s.occlusion = m.occlusion;
  s.emissive = m.emissive;
  s.N = g.N;
  // One call of sample_map per map, not a loop around one call, although each call site is
  // inlined whole before specialization removes the maps a pipeline leaves out: lavapipe (Mesa
  // 22.3) keeps such a loop and runs every branch of a varying condition under a mask, so a loop
  // sampled every map and applied each map's result five times a pixel: the textured scene's
  // graphics frame ran 814 M instructions with the loop against 650 M with these calls, which
  // cost about 50 ms more to build (docs/development.md, "Measured CI time").
#if TS_TEXTURE_MAP_CODE
  if (has_map(TS_MAP_BASE_COLOR, m.base_color_map)) {
    s.base_color *= sample_map(m, TS_MAP_BASE_COLOR, m.base_color_map, g).rgb;
  }
  if (has_map(TS_MAP_METALLIC_ROUGHNESS, m.metallic_roughness_map)) {
    vec4 t = sample_map(m, TS_MAP_METALLIC_ROUGHNESS, m.metallic_roughness_map, g);
    roughness *= t.g;
    metallic *= t.b;
  }
  if (has_map(TS_MAP_OCCLUSION, m.occlusion_map)) {
    s.occlusion *= sample_map(m, TS_MAP_OCCLUSION, m.occlusion_map, g).r;
  }
  if (has_map(TS_MAP_EMISSIVE, m.emissive_map)) {
    s.emissive *= sample_map(m, TS_MAP_EMISSIVE, m.emissive_map, g).rgb;
  }
  if (has_map(TS_MAP_NORMAL, m.normal_map)) {
    vec3 local = sample_map(m, TS_MAP_NORMAL, m.normal_map, g).rgb * 2.0 - 1.0;
    s.N = apply_normal_map(g, local, m.normal_scale, V);
  }
#endif
  s.pixel = metallic_roughness_params(s.base_color, metallic, roughness);
  return s;
}
