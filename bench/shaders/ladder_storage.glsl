// The minimal program's shading (minimal_shading.glsl) on Tessera's data, for the ladder's
// rungs between the minimal program and the baseline (bench/minimal_graphics.cpp): the
// material (GpuMaterial, 80 bytes) read per fragment from the material buffer by the flat
// index, the four lights (GpuLight) from the light buffer, eye and ambient from the frame
// constants. The includer declares any further varyings its vertex stage writes.
#include "bindings.glsl"

// Nothing here discards or writes depth: hidden fragments are rejected before shading.
layout(early_fragment_tests) in;

layout(location = 0) in vec3 world_position;
layout(location = 1) in vec3 normal;
layout(location = 2) flat in uint material;
layout(location = 0) out vec4 color;

#define EYE frame.camera_position
#define AMBIENT frame.ambient
#define BASE_COLOR materials[material].base_color
#define METALLIC materials[material].metallic
#define ROUGHNESS materials[material].roughness
#define LIGHT_POSITION(i) lights[i].position
#define LIGHT_RADIANCE(i) lights[i].radiance
#include "minimal_shading.glsl"
