#version 450
// The minimal graphics program's vertex stage (bench/minimal_graphics.cpp): a unit sphere's
// vertex moved to its instance's centre and scaled by its radius.

layout(set = 0, binding = 0, std140) uniform Frame {
  mat4 view_proj;
  vec4 camera;          // xyz: eye position
  vec4 light_position[4];
  vec4 light_radiance[4];  // intensity times colour (W/sr): irradiance is this over d^2
  vec4 ambient;
} frame;

layout(location = 0) in vec3 position;  // unit sphere: the normal too
layout(location = 1) in vec4 centre_radius;
layout(location = 2) in vec4 base_metallic;
layout(location = 3) in float roughness;

layout(location = 0) out vec3 world_position;
layout(location = 1) out vec3 normal;
layout(location = 2) flat out vec4 material;  // base colour, metallic
layout(location = 3) flat out float perceptual_roughness;

void main() {
  world_position = centre_radius.xyz + centre_radius.w * position;
  normal = position;
  material = base_metallic;
  perceptual_roughness = roughness;
  gl_Position = frame.view_proj * vec4(world_position, 1.0);
}
