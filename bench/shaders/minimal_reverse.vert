#version 450
#extension GL_GOOGLE_include_directive : require
// Ladder rung reverse_depth (bench/minimal_graphics.cpp): the minimal program with the
// baseline's depth (z = near, GREATER, cleared to 0).
#define MINIMAL_REVERSE_DEPTH
#include "minimal_vert.glsl"
