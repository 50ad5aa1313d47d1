// Indicator pass, fragment stage: the category's shape (sp_shapes.h) at the
// hit, a tapered tail trailing back towards where the sound came from, and
// a two-tone halo around both, alpha-blended over the scene. Compiled twice:
// indicator.frag, and indicator_clip.frag with SP_CLIP, which samples the
// scene's depth (set 1) to clip a spot to the surface it lies on: no colour
// in the air past an edge, none under a wall in the next room.
#include "indicator_bindings.glsl"

// Depth is tested before shading: the pass writes no depth, so a discard
// cannot change what the test sees, and spots behind walls cost nothing.
layout(early_fragment_tests) in;

layout(std430, push_constant) uniform Push { IndicatorPush push; };

layout(location = 0) in vec2 in_local;
layout(location = 1) flat in vec4 in_color;
layout(location = 2) flat in vec4 in_shape;  // shape id, tail length, direct, radius (m)
layout(location = 3) in vec3 in_world;
layout(location = 4) flat in vec3 in_anchor;
layout(location = 5) flat in vec3 in_normal;

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

// Does the scene show the spot's own surface at the quad's world point q?
// The scene's depth at q's pixel gives the point the eye sees along the
// same ray (view depth scales linearly along it); that point must lie in
// the spot's plane, which the quad floats SP_INDICATOR_LIFT above. A wall
// beyond an edge, a face round a corner or the floor far below all lie off
// that plane, however close in depth. The tolerance covers depth precision
// and a triangle's own rounding. q's pixel is found from this fragment's
// own (gl_FragCoord, so any viewport offset is right) and the offset of q
// from it on screen; depth is the host's, the size of its framebuffer.
// Outside the depth image nothing is known: yes.
#ifdef SP_CLIP
vec2 to_ndc(vec3 q, out float w) {
  vec4 clip = push.view_proj * vec4(q, 1.0);
  w = clip.w;
  return clip.xy / clip.w;
}

bool on_surface(vec3 q, vec2 fragment_ndc) {
  float w;
  vec2 ndc = to_ndc(q, w);
  if (w <= 0.0) return true;
  vec2 viewport = vec2(push.viewport_width, push.viewport_height);
  vec2 at = gl_FragCoord.xy + (ndc - fragment_ndc) * 0.5 * viewport;
  ivec2 size = textureSize(scene_depth, 0);
  if (any(lessThan(at, vec2(0.0))) || any(greaterThanEqual(at, vec2(size)))) return true;
  float depth = texelFetch(scene_depth, ivec2(at), 0).r;
  float scene_distance = push.depth_b / (depth + push.depth_a);
  vec3 seen = push.eye + (q - push.eye) * (scene_distance / w);
  float off_plane = dot(seen - in_anchor, in_normal) + SP_INDICATOR_LIFT;
  float tolerance = 0.01 + 0.002 * w;
  return abs(off_plane) <= tolerance;
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
  // (a wall in between means this part lies in the next room). Without the
  // viewport's size only this fragment's own pixel can be looked up.
  float fragment_w;
  vec2 fragment_ndc = to_ndc(in_world, fragment_w);
  if (!on_surface(in_world, fragment_ndc)) discard;
  if (push.viewport_width > 0.0) {
    for (int k = 1; k < 4; ++k) {
      if (!on_surface(mix(in_anchor, in_world, float(k) / 4.0), fragment_ndc)) discard;
    }
  }
#endif

  vec3 color = in_color.rgb;
  float alpha = in_color.a;
  if (halo > 0.0) {
    // Body for d <= 0, the dark ring next, the light ring outside it. The
    // halo is drawn at twice the body's opacity: it keeps its 3:1 contrast
    // against any surface (docs/accessibility.md) while the spot is at 0.5
    // or more, and fades out with it after.
    float dark = smoothstep(-0.5 * pixel, 0.5 * pixel, d);
    float light = smoothstep(halo - 0.5 * pixel, halo + 0.5 * pixel, d);
    color = mix(mix(in_color.rgb, vec3(SP_HALO_DARK_RGB), dark), vec3(SP_HALO_LIGHT_RGB), light);
    alpha = mix(alpha, min(1.0, 2.0 * alpha), dark);
  }
  out_color = vec4(color, alpha * coverage);
}
