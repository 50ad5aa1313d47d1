// Indicator pass, fragment stage: the category's shape (sp_shapes.h) at the
// hit, a tapered tail trailing back towards where the sound came from, and
// a two-tone halo around both, alpha-blended over the scene. Compiled twice:
// indicator.frag, and indicator_clip.frag with SP_CLIP, which samples the
// scene's depth (set 1) to clip a spot to the surface it lies on: no colour
// in the air past an edge, nor on a face round a corner (the vertex stage
// has already dropped each spot whose centre is hidden, so none reaches
// under a wall into the next room either).
#include "indicator_bindings.glsl"

// Depth is tested before shading: the pass writes no depth, so a discard
// cannot change what the test sees, and spots behind walls cost nothing.
layout(early_fragment_tests) in;

layout(std430, push_constant) uniform Push { IndicatorPush push; };

layout(location = 0) in vec2 in_local;
layout(location = 1) flat in vec4 in_color;
layout(location = 2) flat in vec4 in_shape;  // shape id, tail length, direct, radius (m)
layout(location = 3) flat in float in_plane_depth;  // dot(anchor - eye, normal)
#ifdef SP_CLIP
layout(location = 4) flat in uvec2 in_depth_size;  // the scene depth's size in texels
#endif

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

#ifdef SP_CLIP
#include "indicator_surface.glsl"
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
  // The scene must show the spot's own surface at this pixel (where the
  // depth image has one: a host's may be smaller than its framebuffer).
  // gl_FragCoord.w is 1 / w of the quad's point there.
  uvec2 texel = uvec2(gl_FragCoord.xy);
  if (all(lessThan(texel, in_depth_size)) && !sp_on_spot_surface(ivec2(texel), gl_FragCoord.w, in_plane_depth)) discard;
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
