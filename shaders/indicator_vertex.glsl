// Indicator pass, vertex stage: one instance per ring slot, drawn with the
// VkDrawIndirectCommand the compute pass (or the host, for the CPU backend)
// wrote. The indicator comes from gl_InstanceIndex, the quad corner from
// gl_VertexIndex. The quad lies in the indicator's surface plane, lifted
// along its normal so it wins the depth test against that surface, and
// turned so that its +x axis is the sound's direction of travel projected
// onto the surface: the shape sits at the hit, a comet's tail trails back
// towards where the sound came from (docs/accessibility.md).
#include "indicator_bindings.glsl"

layout(std430, push_constant) uniform Push { IndicatorPush push; };
#ifdef SP_CLIP
#include "indicator_surface.glsl"
#endif

layout(location = 0) out vec2 out_local;        // the spot's frame, in units of its radius: the shape is |p| <= 1
layout(location = 1) flat out vec4 out_color;   // rgb, opacity
layout(location = 2) flat out vec4 out_shape;   // shape id, tail length (radii), 1 for direct sound, radius (m)
// For clipping (indicator_surface.glsl): the eye's height above the
// surface's plane (negative: the eye is on the normal's side), and the scene
// depth's size, so that the fragment stage never reads past it (a host's
// depth smaller than its framebuffer) without a size query per fragment.
layout(location = 3) flat out float out_plane_depth;
#ifdef SP_CLIP
layout(location = 4) flat out uvec2 out_depth_size;
#endif

// The quad's corners in the spot's frame, before its extents are applied: a
// triangle strip covering [-1, 1]^2.
const vec2 kCorners[SP_INDICATOR_QUAD_VERTICES] =
    vec2[](vec2(-1.0, -1.0), vec2(1.0, -1.0), vec2(-1.0, 1.0), vec2(1.0, 1.0));

// The quad's margin, tail and sizes: SP_SPOT_* in sp_draw_types.h.

void collapse() {
  // Every corner at the same point outside the clip volume: the instance
  // rasterises nothing.
  gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
  out_local = vec2(0.0);
  out_color = vec4(0.0);
  out_shape = vec4(0.0);
  out_plane_depth = 0.0;
#ifdef SP_CLIP
  out_depth_size = uvec2(0u);
#endif
}

#ifdef SP_CLIP
// 1 / w of the quad's plane where the eye sees it at device coordinates q:
// at the point anchor + s * tangent + t * bitangent that projects to q.
// Clip coordinates are linear along the plane, so s and t solve a 2 x 2
// system. Seen edge-on (no solution), the anchor's own.
float plane_inv_w(vec4 anchor_clip, vec4 tangent_clip, vec4 bitangent_clip, vec2 q) {
  vec2 a = anchor_clip.xy - q * anchor_clip.w;
  vec2 u = tangent_clip.xy - q * tangent_clip.w;
  vec2 v = bitangent_clip.xy - q * bitangent_clip.w;
  float det = u.x * v.y - u.y * v.x;
  float w = anchor_clip.w;
  if (abs(det) > 1.0e-12) {
    float s = (a.y * v.x - a.x * v.y) / det;
    float t = (a.x * u.y - a.y * u.x) / det;
    w += s * tangent_clip.w + t * bitangent_clip.w;
  }
  return 1.0 / (w > 0.0 ? w : anchor_clip.w);
}
#endif

void main() {
  uint slot = gl_InstanceIndex;
  Indicator ind = ring[slot];
  DisplaySource source = sources[ind.source_id];
  float age = sp_indicator_age(push.current_step, ind.step, push.dt);
  float opacity = sp_indicator_opacity(ind.intensity, age, push.lifetime);
  // A fade-in, so a spot never pops on (docs/accessibility.md, flashing).
  opacity *= min(1.0, (age + push.dt) / SP_FADE_IN_SECONDS);
  bool direct = sp_is_direct(ind);
  opacity *= direct ? 1.0 : SP_SPOT_INDIRECT_OPACITY;
  bool live = sp_indicator_live(push.current_step, ind.step, push.dt, push.lifetime);
  if (live) opacity = max(opacity * push.opacity_scale, push.min_opacity);
  opacity = min(opacity, 1.0);
  bool hidden = (source.shape_flags & SP_SOURCE_HIDDEN) != 0u;
  bool capped = (push.flags & SP_DRAW_CAPS) != 0u && visible[slot] == 0u;
  // A spot facing away from the eye lies on the far side of its surface,
  // which hides it; skipping it saves rasterising what depth would reject.
  bool facing_away = dot(ind.normal, push.eye - ind.position) <= 0.0;
  if (!live || opacity < SP_MIN_VISIBLE_ALPHA || ind.size <= 0.0 || hidden || capped || facing_away) {
    collapse();
    return;
  }

  vec3 n = normalize(ind.normal);
  // The spot's +x: the direction of travel along the surface; any
  // direction in the plane when the sound arrives head-on.
  vec3 along = ind.dir - n * dot(ind.dir, n);
  float along_length = length(along);
  vec3 helper = abs(n.y) < 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
  vec3 tangent = along_length > 1.0e-3 ? along / along_length : normalize(cross(helper, n));
  vec3 bitangent = cross(n, tangent);
  float tail = (push.flags & SP_DRAW_DIRECTION) != 0u ? SP_SPOT_MAX_TAIL * min(along_length, 1.0) : 0.0;

  // Radius: the indicator's size (a diameter, docs/model.md#indicators) scaled,
  // but never under SP_SHAPE_MIN_PIXELS across on screen, where a shape stops
  // being recognisable (when the viewport's size is known).
  float radius = 0.5 * ind.size * push.size_scale * (direct ? SP_SPOT_DIRECT_SIZE : 1.0);
  vec4 centre_clip = push.view_proj * vec4(ind.position, 1.0);
  float distance = max(centre_clip.w, 1.0e-3);
  float margin = SP_SPOT_MARGIN_RADII;
  if (push.pixel_scale > 0.0) {
    radius = max(radius, 0.5 * SP_SHAPE_MIN_PIXELS * distance / push.pixel_scale);
    margin = min(SP_SPOT_MARGIN_RADII, SP_SPOT_MARGIN_PIXELS * distance / (push.pixel_scale * radius));
  }

  vec3 anchor = ind.position + n * SP_INDICATOR_LIFT;
  vec4 anchor_clip = push.view_proj * vec4(anchor, 1.0);
  float plane_depth = dot(anchor - push.eye, n);
#ifdef SP_CLIP
  // A spot shows only if the scene shows its centre: one depth look-up per
  // vertex, where each fragment looking it up cost a sixth of the pass
  // (bench/RESULTS.md). A centre hidden behind a wall leaves nothing to
  // reach under it into the next room, and none in the air past an edge.
  // The test compares the depth at the centre's pixel with the quad's
  // plane at that pixel's centre, not at the centre itself: half a pixel
  // along a plane seen at a slant is more than the tolerance far away.
  // Off screen, outside the depth image or with the viewport unknown,
  // nothing is known: it shows.
  uvec2 depth_size = uvec2(textureSize(scene_depth, 0));
  uvec2 viewport = uvec2(push.viewport_size & 0xFFFFu, push.viewport_size >> 16);
  if (all(greaterThan(viewport, uvec2(0u))) && anchor_clip.w > 0.0) {
    vec2 ndc = anchor_clip.xy / anchor_clip.w;
    uvec2 origin = uvec2(push.viewport_origin & 0xFFFFu, push.viewport_origin >> 16);
    uvec2 pixel = min(uvec2((0.5 * ndc + 0.5) * vec2(viewport)), viewport - 1u);
    uvec2 texel = origin + pixel;
    if (all(lessThan(abs(ndc), vec2(1.0))) && all(lessThan(texel, depth_size))) {
      vec2 pixel_centre = (vec2(pixel) + 0.5) / vec2(viewport) * 2.0 - 1.0;
      float inv_w = plane_inv_w(anchor_clip, push.view_proj * vec4(tangent, 0.0), push.view_proj * vec4(bitangent, 0.0),
                                pixel_centre);
      if (!sp_on_spot_surface(ivec2(texel), inv_w, plane_depth)) {
        collapse();
        return;
      }
    }
  }
  out_depth_size = depth_size;
#endif

  vec2 corner = kCorners[gl_VertexIndex];
  // x from the tail's end (or the shape's back) to past the head, y across
  // (the tail is narrower than any shape): all with the margin.
  uint shape = source.shape_flags & 0xFFu;
  float extent = sp_shape_extent(shape);
  float back = tail > 0.0 ? max(extent, SP_TAIL_START + tail + SP_TAIL_TIP_WIDTH) : extent;
  vec2 local = vec2(corner.x < 0.0 ? -back - margin : extent + margin, corner.y * (extent + margin));
  vec3 p = anchor + (tangent * local.x + bitangent * local.y) * radius;
  out_local = local;
  out_color = vec4(ind.color, opacity);
  out_shape = vec4(float(shape), tail, direct ? 1.0 : 0.0, radius);
  gl_Position = push.view_proj * vec4(p, 1.0);
  out_plane_depth = plane_depth;
}
