#version 460
// Off-screen arrows, vertex stage: one instance per source. A source that
// is heard (it has live spots, counted by the prepass) gets an arrow when it
// lies outside the view, or inside it but hidden from the listener
// (SP_SOURCE_CUE_OCCLUDED): on a ring round the picture's centre at the
// angle of its bearing, head outwards, in its colour, with its category's
// shape and a mark for its elevation. Arrows that would cover one another
// step inwards along their own radial lines, so each keeps its angle
// (geometry: sp_arrows.h; meaning: docs/accessibility.md).
#extension GL_GOOGLE_include_directive : require
#include "indicator_bindings.glsl"
#include "sp_arrows.h"

layout(std430, push_constant) uniform Push { ArrowPush push; };

layout(location = 0) out vec2 out_local;       // the arrow's frame (sp_arrows.h): +x outwards, shape in |p| <= 1
layout(location = 1) flat out vec4 out_color;  // rgb, opacity
layout(location = 2) flat out uint out_shape;
layout(location = 3) flat out uint out_mark;  // SP_ARROW_MARK_*

const vec2 kCorners[SP_INDICATOR_QUAD_VERTICES] =
    vec2[](vec2(-1.0, -1.0), vec2(1.0, -1.0), vec2(-1.0, 1.0), vec2(1.0, 1.0));
const uint kNone = 0xFFFFFFFFu;

void collapse() {
  gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
  out_local = vec2(0.0);
  out_color = vec4(0.0);
  out_shape = 0u;
  out_mark = SP_ARROW_MARK_NONE;
}

// Whether source `id` gets an arrow, and its bearing (radians) if it does.
bool arrow_shown(uint id, out float bearing) {
  bearing = 0.0;
  DisplaySource source = sources[id];
  if ((source.shape_flags & SP_SOURCE_PRESENT) == 0u || (source.shape_flags & SP_SOURCE_HIDDEN) != 0u ||
      source_live[id] == 0u)
    return false;
  vec4 clip = push.view_proj * vec4(source.position, 1.0);
  bool in_view = clip.w > 0.0 && all(lessThanEqual(abs(clip.xy), vec2(clip.w)));
  // In view and not hidden, its spots are its cue.
  if (in_view && (source_cues[id] & SP_SOURCE_CUE_OCCLUDED) == 0u) return false;
  bearing = sp_arrow_bearing(source.position - push.eye, push.heading);
  return true;
}

// The inner end of the arrow at `bearing` in its outermost place: arrows
// converge towards the centre, so two side by side come closest there.
vec2 inner_end(float bearing, vec2 half_size, float scale) {
  float ring = sp_arrow_ring_distance(bearing, half_size, scale);
  return sp_arrow_direction(bearing) * max(ring - sp_arrow_half_length() * scale, 0.0);
}

// The arrow's place in its run, counted from the run's start (at most
// SP_ARROW_MAX_RUN). Arrows that would cover their neighbour on the ring
// form a run, in clockwise order (ties by id). Walking the run back one
// arrow at a time, rather than counting the arrows near this one, numbers
// a run of three 0, 1, 2: the third is near the second only. Every
// instance walks the same table the same way, so their numbers agree.
uint run_position(uint id, float bearing, vec2 half_size, float scale) {
  float reach = 2.0 * SP_ARROW_HALF_WIDTH * scale + SP_ARROW_GAP_PIXELS;  // closer, two arrows touch
  uint current = id;
  float current_bearing = bearing;
  vec2 current_end = inner_end(bearing, half_size, scale);
  uint position = 0u;
  for (; position < SP_ARROW_MAX_RUN; ++position) {
    uint previous = kNone;
    float previous_gap = 2.0 * SP_PI;
    float previous_bearing = 0.0;
    for (uint k = 0u; k < push.source_count; ++k) {
      float k_bearing;
      if (k == current || !arrow_shown(k, k_bearing)) continue;
      // How far counter-clockwise of the current arrow k lies, in [0, 2 pi).
      float gap = mod(current_bearing - k_bearing, 2.0 * SP_PI);
      if (gap >= SP_PI || (gap == 0.0 && k > current)) continue;  // it comes after
      if (distance(inner_end(k_bearing, half_size, scale), current_end) >= reach) continue;
      if (gap < previous_gap || (gap == previous_gap && k > previous)) {
        previous = k;
        previous_gap = gap;
        previous_bearing = k_bearing;
      }
    }
    if (previous == kNone) break;
    current = previous;
    current_bearing = previous_bearing;
    current_end = inner_end(previous_bearing, half_size, scale);
  }
  return position;
}

void main() {
  uint id = gl_InstanceIndex;
  float bearing;
  if (!arrow_shown(id, bearing)) {
    collapse();
    return;
  }
  DisplaySource source = sources[id];
  vec2 half_size = 0.5 * push.viewport;
  float scale = 0.5 * push.arrow_pixels;  // pixels per unit of the arrow's frame
  vec2 way = sp_arrow_direction(bearing);
  float ring = sp_arrow_ring_distance(bearing, half_size, scale);
  // One place inwards is the arrow's length and a gap; the innermost place
  // keeps the arrow out of the clear disc round the centre. Along a run the
  // places go in turn, outermost first, so that neighbours never share one.
  float step = (SP_ARROW_HIGH - SP_ARROW_LOW) * scale + SP_ARROW_GAP_PIXELS;
  float room = ring - sp_arrow_half_length() * scale - SP_ARROW_CLEAR_CENTRE * min(half_size.x, half_size.y);
  uint places = min(uint(max(floor(room / step), 0.0)) + 1u, SP_ARROW_MAX_STACK);
  uint place = places > 1u ? run_position(id, bearing, half_size, scale) % places : 0u;
  vec2 anchor = way * (ring - float(place) * step);

  vec2 corner = kCorners[gl_VertexIndex] * 0.5 + 0.5;
  vec2 local = mix(vec2(SP_ARROW_LOW, -SP_ARROW_HALF_WIDTH), vec2(SP_ARROW_HIGH, SP_ARROW_HALF_WIDTH), corner);
  vec2 side = vec2(-way.y, way.x);
  vec2 pixel = anchor + (way * (local.x - sp_arrow_anchor_x()) + side * local.y) * scale;
  out_local = local;
  out_color = vec4(source.color, 1.0);
  out_shape = source.shape_flags & 0xFFu;
  out_mark = sp_arrow_elevation_mark(source.position - push.eye);
  gl_Position = vec4(pixel / half_size, 0.0, 1.0);
}
