#version 460
// The indicator pass's fragment stage without clipping (no scene depth):
// indicator_fragment.glsl.
#extension GL_GOOGLE_include_directive : require
#include "indicator_fragment.glsl"
