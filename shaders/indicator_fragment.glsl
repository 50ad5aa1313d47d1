// Indicator pass, fragment stage: the category's shape (sp_shapes.h) at the
// hit, a tapered tail trailing back towards where the sound came from, and
// a two-tone halo around both, alpha-blended over the scene. Compiled twice:
// indicator.frag, and indicator_clip.frag with SP_CLIP, which samples the
// scene's depth (set 1) to clip a spot to the surface it lies on: no colour
// in the air past an edge, none under a wall in the next room.
#include "indicator_bindings.glsl"

layout(std430, push_constant) uniform Push { IndicatorPush push; };

layout(location = 0) in vec2 in_local;
layout(location = 1) flat in vec4 in_color;
layout(location = 2) flat in vec4 in_shape;  // shape id, tail length, direct, radius (m)
layout(location = 3) in vec3 in_world;
layout(location = 4) flat in vec3 in_anchor;

layout(location = 0) out vec4 out_color;

const float kHaloPixels = 1.5;  // width of each ring of the halo on screen

// The tail: from the back of the shape along -x, narrowing to a point. It
// starts behind the shape, so it fills no ring's hole and joins no
// clover's discs.
const float kTailStart = -0.85;
float tail_distance(vec2 p, float length_in_radii) {
  float t = clamp((kTailStart - p.x) / length_in_radii, 0.0, 1.0);
  float width = mix(0.22, 0.04, t);
  return length(p - vec2(kTailStart - t * length_in_radii, 0.0)) - width;
}

// Does the scene's surface lie where the quad is, at world point q? The
// quad floats SP_INDICATOR_LIFT above its surface, so along the view ray
// the two are that far apart, more at grazing angles; depth has its own
// precision. Outside the picture nothing is known: yes.
#ifdef SP_CLIP
bool on_surface(vec3 q) {
  vec4 clip = push.view_proj * vec4(q, 1.0);
  if (clip.w <= 0.0) return true;
  vec2 ndc = clip.xy / clip.w;
  if (any(greaterThan(abs(ndc), vec2(1.0)))) return true;
  ivec2 size = textureSize(scene_depth, 0);
  ivec2 pixel = clamp(ivec2((ndc * 0.5 + 0.5) * vec2(size)), ivec2(0), size - 1);
  float depth = texelFetch(scene_depth, pixel, 0).r;
  float scene_distance = push.depth_b / (depth + push.depth_a);
  float tolerance = 0.03 + 0.01 * clip.w;
  return abs(scene_distance - clip.w) <= tolerance;
}
#endif

void main() {
  float d = sp_shape_distance(uint(in_shape.x), in_local);
  if (in_shape.y > 0.0) d = min(d, tail_distance(in_local, in_shape.y));
  // One pixel in the spot's units, for the anti-aliased edge and the halo.
  float pixel = max(length(fwidth(in_local)), 1.0e-4);
  float halo = (push.flags & SP_DRAW_OUTLINE) != 0u ? kHaloPixels * pixel : 0.0;
  float coverage = 1.0 - smoothstep(-0.5 * pixel, 0.5 * pixel, d - 2.0 * halo);
  if (coverage * in_color.a < SP_MIN_VISIBLE_ALPHA) discard;

#ifdef SP_CLIP
  // The surface must be here, and all the way here from the spot's centre
  // (a wall in between means this part lies in the next room).
  if (!on_surface(in_world)) discard;
  for (int k = 1; k < 4; ++k) {
    if (!on_surface(mix(in_anchor, in_world, float(k) / 4.0))) discard;
  }
#endif

  vec3 color = in_color.rgb;
  if (halo > 0.0) {
    // Body for d <= 0, the dark ring next, the light ring outside it.
    float dark = smoothstep(-0.5 * pixel, 0.5 * pixel, d);
    float light = smoothstep(halo - 0.5 * pixel, halo + 0.5 * pixel, d);
    color = mix(mix(in_color.rgb, vec3(SP_HALO_DARK_RGB), dark), vec3(SP_HALO_LIGHT_RGB), light);
  }
  out_color = vec4(color, in_color.a * coverage);
}
