#version 460
// The indicator pass's fragment stage clipped to the surface with the
// scene's depth: indicator_fragment.glsl with SP_CLIP.
#extension GL_GOOGLE_include_directive : require
#define SP_CLIP 1
#include "indicator_fragment.glsl"
