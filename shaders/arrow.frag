#version 460
// Off-screen arrows, fragment stage: the source's shape in its colour with
// an arrowhead outwards of it and, for a source above or below eye level,
// a bar on a stem across the radial line (beyond the head: above; behind
// the shape: below), all inside the two-tone halo of the spots. Every part is
// symmetric about the arrow's +x axis, its radial line (sp_arrows.h).
#extension GL_GOOGLE_include_directive : require
#include "indicator_bindings.glsl"
#include "sp_arrows.h"

layout(location = 0) in vec2 in_local;
layout(location = 1) flat in vec4 in_color;
layout(location = 2) flat in uint in_shape;
layout(location = 3) flat in uint in_mark;

layout(location = 0) out vec4 out_color;

// The arrowhead: a triangle outwards of the shape. Distance as the largest
// of its three edges' (exact inside, a bound outside).
float head_distance(vec2 p) {
  vec2 tip = vec2(SP_ARROW_HEAD_TIP, 0.0);
  vec2 back_top = vec2(SP_ARROW_HEAD_BACK, SP_ARROW_HEAD_HALF_HEIGHT);
  vec2 back_bottom = vec2(SP_ARROW_HEAD_BACK, -SP_ARROW_HEAD_HALF_HEIGHT);
  vec2 n1 = normalize(vec2(back_top.y - tip.y, tip.x - back_top.x));
  vec2 n2 = normalize(vec2(tip.y - back_bottom.y, back_bottom.x - tip.x));
  float d1 = dot(p - tip, n1);
  float d2 = dot(p - tip, n2);
  float d3 = back_top.x - p.x;
  return max(max(d1, d2), d3);
}

// The elevation mark, a bar across the radial line on a stem along it;
// far away when there is none.
float mark_distance(vec2 p, uint mark) {
  if (mark == SP_ARROW_MARK_NONE) return 1.0e6;
  bool above = mark == SP_ARROW_MARK_ABOVE;
  float bar_x = above ? SP_ARROW_MARK_ABOVE_X : SP_ARROW_MARK_BELOW_X;
  float stem_from = above ? SP_ARROW_STEM_ABOVE_FROM : SP_ARROW_STEM_BELOW_FROM;
  float bar = sp_box_distance(p - vec2(bar_x, 0.0), vec2(SP_ARROW_MARK_HALF_THICKNESS, SP_ARROW_MARK_HALF_LENGTH));
  float stem = sp_box_distance(p - vec2(0.5 * (bar_x + stem_from), 0.0),
                               vec2(0.5 * abs(bar_x - stem_from), SP_ARROW_STEM_HALF_WIDTH));
  return min(bar, stem);
}

void main() {
  float d = min(min(sp_shape_distance(in_shape, in_local), head_distance(in_local)), mark_distance(in_local, in_mark));
  float pixel = max(length(fwidth(in_local)), 1.0e-4);
  float halo = 1.5 * pixel;
  float coverage = 1.0 - smoothstep(-0.5 * pixel, 0.5 * pixel, d - 2.0 * halo);
  if (coverage < SP_MIN_VISIBLE_ALPHA) discard;
  float dark = smoothstep(-0.5 * pixel, 0.5 * pixel, d);
  float light = smoothstep(halo - 0.5 * pixel, halo + 0.5 * pixel, d);
  vec3 color = mix(mix(in_color.rgb, vec3(SP_HALO_DARK_RGB), dark), vec3(SP_HALO_LIGHT_RGB), light);
  out_color = vec4(color, in_color.a * coverage);
}
