#version 460
// Indicator pass, vertex stage: one instance per ring slot, drawn with the
// VkDrawIndirectCommand the compute pass (or the host, for the CPU backend)
// wrote. The indicator comes from gl_InstanceIndex, the quad corner from
// gl_VertexIndex; the quad lies in the indicator's surface plane, lifted
// along its normal so it wins the depth test against that surface.
#extension GL_GOOGLE_include_directive : require
#include "sp_draw_types.h"

layout(std430, set = 0, binding = 0) readonly buffer RingBuffer { Indicator ring[]; };
layout(std430, push_constant) uniform Push { IndicatorPush push; };

layout(location = 0) out vec2 out_corner;  // in [-1, 1]^2 across the quad
layout(location = 1) flat out vec4 out_color;  // rgb, opacity

// Two counter-clockwise triangles covering [-1, 1]^2.
const vec2 kCorners[SP_INDICATOR_QUAD_VERTICES] =
    vec2[](vec2(-1.0, -1.0), vec2(1.0, -1.0), vec2(1.0, 1.0), vec2(-1.0, -1.0), vec2(1.0, 1.0), vec2(-1.0, 1.0));

void main() {
  Indicator ind = ring[gl_InstanceIndex];
  // SPEC 1.4: opacity at age a is I * max(0, 1 - a / lifetime).
  uint age_steps = push.current_step >= ind.step ? push.current_step - ind.step : 0u;
  float age = float(age_steps) * push.dt;
  float opacity = ind.intensity * max(0.0, 1.0 - age / push.lifetime);
  // A spot facing away from the eye lies on the far side of its surface,
  // which hides it; skipping it saves rasterising what depth would reject.
  bool facing_away = dot(ind.normal, push.eye - ind.position) <= 0.0;
  if (opacity < SP_MIN_VISIBLE_ALPHA || ind.size <= 0.0 || facing_away) {
    // Expired, invisible or hidden: every corner at the same point outside
    // the clip volume, so the instance rasterises nothing.
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
    out_corner = vec2(0.0);
    out_color = vec4(0.0);
    return;
  }
  vec3 n = normalize(ind.normal);
  vec3 helper = abs(n.y) < 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
  vec3 tangent = normalize(cross(helper, n));
  vec3 bitangent = cross(n, tangent);
  vec2 corner = kCorners[gl_VertexIndex];
  float radius = 0.5 * ind.size;  // size is the disc's diameter
  vec3 p = ind.position + n * SP_INDICATOR_LIFT + (tangent * corner.x + bitangent * corner.y) * radius;
  out_corner = corner;
  out_color = vec4(ind.color, opacity);
  gl_Position = push.view_proj * vec4(p, 1.0);
}
