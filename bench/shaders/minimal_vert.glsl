// The minimal graphics program's vertex stage (bench/minimal_graphics.cpp): a unit sphere's
// vertex moved to its instance's centre and scaled by its radius. With MINIMAL_REVERSE_DEPTH
// (the ladder's reverse_depth rung) depth is written as the hardware baseline writes it.
#include "minimal_frame.glsl"

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
#ifdef MINIMAL_REVERSE_DEPTH
  // Reverse depth as the baseline (and the compute path): z / w = near / w, nearer is larger.
  gl_Position.z = 0.1;  // the near plane of make_frame's projection (minimal_graphics.cpp)
#endif
}
