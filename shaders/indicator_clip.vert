#version 460
// The indicator pass's vertex stage with the scene's depth (set 1), which
// drops a spot whose centre is hidden: indicator_vertex.glsl with SP_CLIP.
#extension GL_GOOGLE_include_directive : require
#define SP_CLIP 1
#include "indicator_vertex.glsl"
