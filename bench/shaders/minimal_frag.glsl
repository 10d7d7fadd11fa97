// The minimal graphics program's fragment stage (bench/minimal_graphics.cpp): minimal_shading's
// Cook-Torrance for the uniform block's four lights. With MINIMAL_REVERSE_DEPTH (the ladder's
// reverse_depth rung) it also declares early fragment tests, as the baseline does.
#include "minimal_frame.glsl"

#ifdef MINIMAL_REVERSE_DEPTH
// Nothing here discards or writes depth: hidden fragments are rejected before shading.
layout(early_fragment_tests) in;
#endif

layout(location = 0) in vec3 world_position;
layout(location = 1) in vec3 normal;
layout(location = 2) flat in vec4 material;
layout(location = 3) flat in float perceptual_roughness;
layout(location = 0) out vec4 color;

#define EYE frame.camera.xyz
#define AMBIENT frame.ambient.rgb
#define BASE_COLOR material.rgb
#define METALLIC material.a
#define ROUGHNESS perceptual_roughness
#define LIGHT_POSITION(i) frame.light_position[i].xyz
#define LIGHT_RADIANCE(i) frame.light_radiance[i].rgb
#include "minimal_shading.glsl"
