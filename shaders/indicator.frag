#version 460
// Indicator pass, fragment stage: a soft round spot rather than a hard
// square -- full opacity in the middle, smoothly falling to zero at the
// quad's inscribed circle -- alpha-blended over the scene.
#extension GL_GOOGLE_include_directive : require
#include "sp_draw_types.h"

layout(location = 0) in vec2 in_corner;
layout(location = 1) flat in vec4 in_color;

layout(location = 0) out vec4 out_color;

void main() {
  float r2 = dot(in_corner, in_corner);
  float falloff = 1.0 - smoothstep(0.15, 1.0, r2);
  float alpha = in_color.a * falloff;
  if (alpha < SP_MIN_VISIBLE_ALPHA) discard;
  out_color = vec4(in_color.rgb, alpha);
}
