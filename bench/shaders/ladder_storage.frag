#version 460
#extension GL_GOOGLE_include_directive : require
// Ladder rungs storage_shading and vertex_pulling (bench/minimal_graphics.cpp): the minimal
// program's shading with material and lights read from Tessera's storage buffers.
#include "ladder_storage.glsl"
