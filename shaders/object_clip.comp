#version 460
#extension GL_GOOGLE_include_directive : require
// Each object's clip-space transform for this frame, one thread per object: setup, the clip pass
// and analytic coverage read it (view_clip.glsl's triangle_clip_coords) instead of multiplying
// the two matrices again for every triangle, 64 of setup's ~250 instructions per triangle.
#define TS_OBJECT_CLIP_PASS
#include "bindings.glsl"

layout(local_size_x = TS_GROUP_SIZE) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i < frame.object_count) object_clip[i] = frame.view_proj * objects[i].model;
}
