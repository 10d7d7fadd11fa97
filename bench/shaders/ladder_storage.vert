#version 460
#extension GL_GOOGLE_include_directive : require
// Ladder rung storage_shading (bench/minimal_graphics.cpp): the minimal program's vertex stage
// (the unit sphere's vertex through vertex input, moved and scaled by its instance), drawing
// with Tessera's descriptor set: the view from its frame constants, and each instance's
// material index passed on for the fragment stage to read the material.
#include "bindings.glsl"

layout(location = 0) in vec3 position;  // unit sphere: the normal too
layout(location = 1) in vec4 centre_radius;
layout(location = 2) in uint material_index;

layout(location = 0) out vec3 world_position;
layout(location = 1) out vec3 normal;
layout(location = 2) flat out uint material;

void main() {
  world_position = centre_radius.xyz + centre_radius.w * position;
  normal = position;
  material = material_index;
  gl_Position = frame.view_proj * vec4(world_position, 1.0);
  // Reverse depth as the baseline: z / w = near / w, nearer is larger.
  gl_Position.z = frame.near_plane;
}
