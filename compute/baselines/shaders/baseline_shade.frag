#version 460
#extension GL_GOOGLE_include_directive : require
// Graphics baseline (benchmarks and tests only): the compute path's shading model per fragment.
// Texture footprints come from the fragment shader's own derivatives of uv, where the compute
// path intersects the neighbouring pixels' rays.
#include "bindings.glsl"
#include "material.glsl"
#include "lighting.glsl"

// Nothing here discards or writes depth: hidden fragments are rejected before shading.
layout(early_fragment_tests) in;

layout(location = 0) in vec3 world_position;
layout(location = 1) in vec3 world_normal;
layout(location = 2) flat in uint material;
layout(location = 3) in vec4 world_tangent;
layout(location = 4) in vec2 uv;
layout(location = 5) in vec2 uv1;
layout(location = 0) out vec4 color;

void main() {
  float n2 = dot(world_normal, world_normal);
  // Opposite vertex normals can cancel; the face normal is then the only sensible choice.
  vec3 N = n2 > 1e-20 ? world_normal * inversesqrt(n2)
                      : normalize(cross(dFdx(world_position), dFdy(world_position)));
  vec3 V = normalize(frame.camera_position - world_position);
  SurfaceGeometry g;
  g.P = world_position;
  g.N = N;
  g.T = world_tangent;
  g.uv = uv;
  g.duv_dx = dFdxFine(uv);
  g.duv_dy = dFdyFine(uv);
  g.uv1 = uv1;
  g.duv1_dx = dFdxFine(uv1);
  g.duv1_dy = dFdyFine(uv1);
  // The pipeline's front face accounts for mirroring.
  g = face_viewer(material, g, !gl_FrontFacing);
  MaterialSample ms = evaluate_material(material, g, V);
  color = vec4(min(shade_surface(world_position, V, ms) * pre_exposure(), vec3(TS_MAX_HALF)), 1.0);
}
