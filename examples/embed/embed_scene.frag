#version 460
// Flat grey Lambert shading, deliberately colourless so that soundpaint's
// coloured indicators stand out. abs(): level walls are seen from both sides.
layout(location = 0) flat in vec3 in_normal;

layout(location = 0) out vec4 out_color;

// normalize(vec3(0.35, 1.0, 0.55)): light from above and to one side, so
// floors and walls of different orientations differ in brightness.
const vec3 kLight = vec3(0.2938, 0.8394, 0.4617);
const float kAmbient = 0.2;

void main() {
  float lambert = abs(dot(in_normal, kLight));
  out_color = vec4(vec3(kAmbient + 0.5 * lambert), 1.0);
}
