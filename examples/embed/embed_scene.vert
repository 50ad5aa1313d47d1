#version 460
// The host's scene pass: world-space triangles, each vertex carrying its
// triangle's normal, transformed by one view-projection matrix.
layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;

layout(push_constant) uniform Push { mat4 view_projection; } push;

layout(location = 0) flat out vec3 out_normal;

void main() {
  out_normal = in_normal;
  gl_Position = push.view_projection * vec4(in_position, 1.0);
}
