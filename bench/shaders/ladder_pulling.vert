#version 460
#extension GL_GOOGLE_include_directive : require
// Ladder rung vertex_pulling (bench/minimal_graphics.cpp): no vertex input. The vertex
// (GpuVertex, 48 bytes) is pulled from Tessera's vertex buffer by gl_VertexIndex and the
// object (GpuObject: model and normal matrices, material) from its object buffer by
// gl_InstanceIndex, with the baseline's transforms of position and normal; the baseline's
// tangent and uv sets (compute/baselines/shaders/baseline_shade.vert) are the next rung.
#include "bindings.glsl"

layout(location = 0) out vec3 world_position;
layout(location = 1) out vec3 normal;
layout(location = 2) flat out uint material;

void main() {
  GpuObject o = objects[gl_InstanceIndex];
  vec4 world = o.model * vec4(vertices[gl_VertexIndex].position_u.xyz, 1.0);
  world_position = world.xyz;
  normal = mat3(o.normal_matrix) * vertices[gl_VertexIndex].normal_v.xyz;
  material = o.material;
  gl_Position = frame.view_proj * world;
  // Reverse depth as the baseline: z / w = near / w, nearer is larger.
  gl_Position.z = frame.near_plane;
}
