#version 460
// Scene pass, vertex stage: pulls corner gl_VertexIndex % 3 of triangle
// gl_VertexIndex / 3 from the triangle buffer (no vertex input state) and
// hands the triangle's flat normal and tint to the fragment stage.
#extension GL_GOOGLE_include_directive : require
#include "sp_draw_types.h"

layout(std430, set = 0, binding = 0) readonly buffer TrianglesBuffer { SceneTriangle triangles[]; };
layout(std430, push_constant) uniform Push { ScenePush push; };

layout(location = 0) out vec3 out_world;
layout(location = 1) flat out vec3 out_normal;
layout(location = 2) flat out vec3 out_color;
layout(location = 3) flat out uint out_shading;

void main() {
  SceneTriangle tri = triangles[gl_VertexIndex / 3];
  uint corner = uint(gl_VertexIndex) % 3u;
  vec3 p = corner == 0u ? tri.v0 : (corner == 1u ? tri.v1 : tri.v2);
  vec3 n = cross(tri.v1 - tri.v0, tri.v2 - tri.v0);
  float len = length(n);
  // Degenerate triangles rasterise to nothing; any unit normal will do.
  out_normal = len > 0.0 ? n / len : vec3(0.0, 1.0, 0.0);
  out_world = p;
  out_color = tri.color;
  out_shading = tri.shading;
  gl_Position = push.view_proj * vec4(p, 1.0);
}
