#version 460
// Off-screen arrows, fragment stage: the source's shape in its colour with
// an arrowhead ahead of it, both inside the two-tone halo of the spots.
#extension GL_GOOGLE_include_directive : require
#include "indicator_bindings.glsl"

layout(location = 0) in vec2 in_local;
layout(location = 1) flat in vec4 in_color;
layout(location = 2) flat in uint in_shape;

layout(location = 0) out vec4 out_color;

// The arrowhead: a triangle ahead of the shape, tip at x = 2.2. Distance as
// the largest of its three edges' (exact inside, a bound outside).
float head_distance(vec2 p) {
  vec2 tip = vec2(2.2, 0.0);
  vec2 back_top = vec2(1.25, 0.75);
  vec2 back_bottom = vec2(1.25, -0.75);
  vec2 n1 = normalize(vec2(back_top.y - tip.y, tip.x - back_top.x));
  vec2 n2 = normalize(vec2(tip.y - back_bottom.y, back_bottom.x - tip.x));
  float d1 = dot(p - tip, n1);
  float d2 = dot(p - tip, n2);
  float d3 = back_top.x - p.x;
  return max(max(d1, d2), d3);
}

void main() {
  float d = min(sp_shape_distance(in_shape, in_local), head_distance(in_local));
  float pixel = max(length(fwidth(in_local)), 1.0e-4);
  float halo = 1.5 * pixel;
  float coverage = 1.0 - smoothstep(-0.5 * pixel, 0.5 * pixel, d - 2.0 * halo);
  if (coverage < SP_MIN_VISIBLE_ALPHA) discard;
  float dark = smoothstep(-0.5 * pixel, 0.5 * pixel, d);
  float light = smoothstep(halo - 0.5 * pixel, halo + 0.5 * pixel, d);
  vec3 color = mix(mix(in_color.rgb, vec3(SP_HALO_DARK_RGB), dark), vec3(SP_HALO_LIGHT_RGB), light);
  out_color = vec4(color, in_color.a * coverage);
}
