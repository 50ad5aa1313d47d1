#version 460
// Off-screen arrows, vertex stage: one instance per source. A source that is
// heard (it has live spots, counted by the prepass) but lies outside the
// view, or inside it but hidden from the listener (SP_SOURCE_CUE_OCCLUDED),
// gets an arrow at the screen's edge, pointing the way to turn, in its
// colour and with its category's shape (docs/accessibility.md).
#extension GL_GOOGLE_include_directive : require
#include "indicator_bindings.glsl"

layout(std430, push_constant) uniform Push { ArrowPush push; };

layout(location = 0) out vec2 out_local;       // the arrow's frame: +x towards the source, shape in |p| <= 1
layout(location = 1) flat out vec4 out_color;  // rgb, opacity
layout(location = 2) flat out uint out_shape;

const vec2 kCorners[SP_INDICATOR_QUAD_VERTICES] =
    vec2[](vec2(-1.0, -1.0), vec2(1.0, -1.0), vec2(-1.0, 1.0), vec2(1.0, 1.0));
// The arrow's extent in its frame: the shape at the origin, the head ahead of it.
const vec2 kLow = vec2(-1.35, -1.35);
const vec2 kHigh = vec2(2.35, 1.35);

void collapse() {
  gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
  out_local = vec2(0.0);
  out_color = vec4(0.0);
  out_shape = 0u;
}

void main() {
  uint id = gl_InstanceIndex;
  DisplaySource source = sources[id];
  bool shown = (source.shape_flags & SP_SOURCE_PRESENT) != 0u && (source.shape_flags & SP_SOURCE_HIDDEN) == 0u &&
               source_live[id] > 0u;
  vec4 clip = push.view_proj * vec4(source.position, 1.0);
  bool in_view = clip.w > 0.0 && all(lessThanEqual(abs(clip.xy), vec2(clip.w)));
  // In view and not hidden, its spots are its cue.
  bool cued = !in_view || (source_cues[id] & SP_SOURCE_CUE_OCCLUDED) != 0u;
  if (!shown || !cued) {
    collapse();
    return;
  }
  // The way to turn, on screen: clip x and y keep their sign behind the eye
  // too (only the division by w would flip them), so a source behind and to
  // the left points left. Straight behind: down.
  vec2 half_size = 0.5 * push.viewport;
  vec2 way = clip.xy * half_size * vec2(1.0, 1.0);
  if (length(way) < 1.0e-6) way = vec2(0.0, 1.0);
  way = normalize(way);
  // From the centre along `way` to a frame inset from the screen's edge.
  float scale = push.arrow_pixels * 0.5;  // pixels per unit of the arrow's frame
  vec2 inset = half_size - vec2(kHigh.x * scale + 4.0);
  float reach = min(inset.x / max(abs(way.x), 1.0e-6), inset.y / max(abs(way.y), 1.0e-6));
  vec2 centre = way * max(reach, 0.0);
  vec2 corner = kCorners[gl_VertexIndex];
  vec2 local = mix(kLow, kHigh, corner * 0.5 + 0.5);
  vec2 side = vec2(-way.y, way.x);
  vec2 pixel = centre + (way * local.x + side * local.y) * scale;
  out_local = local;
  out_color = vec4(source.color, 1.0);
  out_shape = source.shape_flags & 0xFFu;
  gl_Position = vec4(pixel / half_size, 0.0, 1.0);
}
