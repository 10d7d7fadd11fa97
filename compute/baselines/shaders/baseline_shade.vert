#version 460
#extension GL_GOOGLE_include_directive : require
// Graphics baseline (benchmarks and tests only): instanced meshes, vertices pulled from the
// same buffers the compute path reads; one instance per object slot (gl_InstanceIndex).
#include "bindings.glsl"

// Maps that may read uv set 1 (TS_MAP_* bits), as the shading pass is specialized: 0 leaves
// out the per-vertex material read.
layout(constant_id = TS_SPEC_UV1_MAPS) const uint UV1_MAPS = TS_MAP_ALL;

layout(location = 0) out vec3 world_position;
layout(location = 1) out vec3 world_normal;
layout(location = 2) flat out uint material;
layout(location = 3) out vec4 world_tangent;
layout(location = 4) out vec2 uv;
layout(location = 5) out vec2 uv1;

void main() {
  GpuObject o = objects[gl_InstanceIndex];
  GpuVertex v = vertices[gl_VertexIndex];
  vec4 world = o.model * vec4(v.position_u.xyz, 1.0);
  world_position = world.xyz;
  world_normal = mat3(o.normal_matrix) * v.normal_v.xyz;
  material = o.material;
  // A mirroring transform flips the handedness of the tangent frame.
  world_tangent = vec4(mat3(o.model) * v.tangent.xyz,
                       v.tangent.w * (o.mirrored != 0u ? -1.0 : 1.0));
  uv = vec2(v.position_u.w, v.normal_v.w);
  // uv1s holds data only when some material reads set 1; this one's mesh has it if it does.
  uv1 = UV1_MAPS != 0u && materials[o.material].uv1_maps != 0u ? uv1s[gl_VertexIndex] : uv;
  gl_Position = frame.view_proj * world;
  // Reverse depth as in the compute path: z / w = near / w, nearer is larger.
  gl_Position.z = frame.near_plane;
}
