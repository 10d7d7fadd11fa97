#version 460
#extension GL_GOOGLE_include_directive : require
// Ladder rung baseline_vertex (bench/minimal_graphics.cpp): as ladder_storage.frag, taking
// all 15 varyings of the baseline's vertex stage (compute/baselines/shaders/baseline_shade.vert).
// The baseline's fragment stage reads tangent and uv sets only for texture maps, which the
// yardstick's materials lack: here they are declared and left unread, as the driver's linker
// finds them there.
layout(location = 3) in vec4 world_tangent;
layout(location = 4) in vec2 uv;
layout(location = 5) in vec2 uv1;
#include "ladder_storage.glsl"
