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
layout(location = 3) in vec4 in_clip;               // this fragment's point on the quad, clip space
layout(location = 4) flat in vec4 in_anchor_clip;  // the spot's centre on the quad, clip space
layout(location = 5) flat in float in_plane_depth;  // dot(anchor - eye, normal)

layout(location = 0) out vec4 out_color;

const float kHaloPixels = 1.5;  // width of each ring of the halo on screen

// The tail: from the back of the shape along -x, narrowing to a point. It
// starts behind the shape, so it fills no ring's hole and joins no
// clover's discs.
float tail_distance(vec2 p, float length_in_radii) {
  float t = clamp((-SP_TAIL_START - p.x) / length_in_radii, 0.0, 1.0);
  float width = mix(SP_TAIL_ROOT_WIDTH, SP_TAIL_TIP_WIDTH, t);
  return length(p - vec2(-SP_TAIL_START - t * length_in_radii, 0.0)) - width;
}

// Does the scene show the spot's own surface at the quad's point q (given
// in clip space) whose pixel is `at`? The scene's depth there gives the
// point the eye sees along the same ray; that point must lie in the spot's
// plane, which the quad floats SP_INDICATOR_LIFT above. A wall beyond an
// edge, a face round a corner or the floor far below all lie off that plane,
// however close in depth. The tolerance covers depth precision and a
// triangle's own rounding. Outside the depth image nothing is known: yes.
//
// The point seen is eye + (q - eye) * s, s = scene distance / q's distance
// (view depth scales linearly along the ray). As q lies in the quad's plane,
// its height above the surface's plane is h * (s - 1) + lift, where
// h = dot(anchor - eye, normal) is one number per spot: no vector algebra
// per look-up.
#ifdef SP_CLIP
bool on_surface(float q_w, vec2 at, ivec2 size) {
  if (q_w <= 0.0 || any(lessThan(at, vec2(0.0))) || any(greaterThanEqual(at, vec2(size)))) return true;
  float depth = texelFetch(scene_depth, ivec2(at), 0).r;
  float s = push.depth_b / ((depth + push.depth_a) * q_w);
  float off_plane = in_plane_depth * (s - 1.0) + SP_INDICATOR_LIFT;
  return abs(off_plane) <= 0.01 + 0.002 * q_w;
}

// Screen spacing, in pixels, of the look-ups between the spot's centre and
// the fragment: a wall at least this wide on screen between them is found.
const float kClipStepPixels = 4.0;
const int kMaxClipSteps = 3;
#endif

void main() {
  float d = sp_shape_distance(uint(in_shape.x), in_local);
  if (in_shape.y > 0.0) d = min(d, tail_distance(in_local, in_shape.y));
  // One pixel in the spot's units, for the anti-aliased edge and the halo:
  // the longer of the steps one pixel across and one pixel down make in the
  // spot's frame. Seen square-on that is exact whichever way the spot is
  // turned on screen (fwidth's sum would count up to 2 pixels at 45 degrees
  // and draw the halo twice as wide).
  float pixel = max(max(length(dFdx(in_local)), length(dFdy(in_local))), 1.0e-4);
  float halo = (push.flags & SP_DRAW_OUTLINE) != 0u ? kHaloPixels * pixel : 0.0;
  float coverage = 1.0 - smoothstep(-0.5 * pixel, 0.5 * pixel, d - 2.0 * halo);
  if (coverage * in_color.a < SP_MIN_VISIBLE_ALPHA) discard;

#ifdef SP_CLIP
  // The surface must be here, and all the way here from the spot's centre
  // (a wall in between means this part lies in the next room), looked up
  // every kClipStepPixels or so. Without the viewport's size only this
  // fragment's own pixel can be looked up.
  ivec2 size = textureSize(scene_depth, 0);
  if (!on_surface(in_clip.w, gl_FragCoord.xy, size)) discard;
  if (push.viewport_width > 0.0) {
    vec2 half_viewport = 0.5 * vec2(push.viewport_width, push.viewport_height);
    vec2 fragment_ndc = in_clip.xy / in_clip.w;
    vec2 to_anchor = (in_anchor_clip.xy / in_anchor_clip.w - fragment_ndc) * half_viewport;
    int steps = min(kMaxClipSteps, int(length(to_anchor) / kClipStepPixels));
    for (int k = 1; k <= steps; ++k) {
      vec4 q = mix(in_clip, in_anchor_clip, float(k) / float(steps + 1));
      vec2 at = gl_FragCoord.xy + (q.xy / q.w - fragment_ndc) * half_viewport;
      if (!on_surface(q.w, at, size)) discard;
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
