// The minimal graphics program's one uniform block (std140; FrameBlock in
// bench/minimal_graphics.cpp), read by both stages.
layout(set = 0, binding = 0, std140) uniform Frame {
  mat4 view_proj;
  vec4 camera;          // xyz: eye position
  vec4 light_position[4];
  vec4 light_radiance[4];  // intensity times colour (W/sr): irradiance is this over d^2
  vec4 ambient;
} frame;
