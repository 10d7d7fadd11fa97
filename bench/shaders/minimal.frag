#version 450
#extension GL_GOOGLE_include_directive : require
// The minimal graphics program (bench/minimal_graphics.cpp), ladder rung 0: the issue's program.
#include "minimal_frag.glsl"
