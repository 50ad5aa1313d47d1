#version 460
// Scene pass, fragment stage: readable rather than realistic shading. A
// fixed light from above plus ambient separates floors from walls, a weak
// headlight term separates walls that face the light equally, and a little
// distance fog gives depth. Surfaces are two-sided (walls are seen from
// both rooms), so the normal is turned towards the eye.
#extension GL_GOOGLE_include_directive : require
#include "sp_draw_types.h"

layout(std430, push_constant) uniform Push { ScenePush push; };

layout(location = 0) in vec3 in_world;
layout(location = 1) flat in vec3 in_normal;
layout(location = 2) flat in vec3 in_color;
layout(location = 3) flat in uint in_shading;

layout(location = 0) out vec4 out_color;

const vec3 kFogColor = vec3(SP_CLEAR_RGB);

void main() {
  vec3 to_eye = push.eye - in_world;
  float distance = length(to_eye);
  to_eye = distance > 0.0 ? to_eye / distance : vec3(0.0, 1.0, 0.0);
  vec3 n = dot(in_normal, to_eye) < 0.0 ? -in_normal : in_normal;
  if (in_shading == SP_SHADE_MARKER) {
    out_color = vec4(in_color * (0.55 + 0.45 * dot(n, to_eye)), 1.0);
    return;
  }
  float sun = max(dot(n, push.light_dir), 0.0);
  float headlight = max(dot(n, to_eye), 0.0);
  float light = push.ambient + (1.0 - push.ambient) * (0.75 * sun + 0.25 * headlight);
  vec3 color = in_color * light;
  if (push.fog_distance > 0.0) color = mix(kFogColor, color, exp(-distance / push.fog_distance));
  out_color = vec4(color, 1.0);
}
