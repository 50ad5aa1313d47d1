#version 460
// The indicator pass's vertex stage without clipping: indicator_vertex.glsl.
#extension GL_GOOGLE_include_directive : require
#include "indicator_vertex.glsl"
