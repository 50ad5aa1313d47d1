// An engine's own indicator draw for tests/test_ring_access.cpp: it knows
// nothing of soundpaint's shaders, only the layout visualizer.h documents
// (IndicatorRing), and draws each live slot as one white point.
#version 460

struct Spot {  // sp::Indicator, std430, 128 bytes
  vec3 position;
  float energy;
  vec3 normal;
  float size;
  vec3 color;
  float intensity;
  vec3 dir;
  float path_length;
  uint kind;
  uint source_id;
  uint bounces;
  uint penetrations;
  uint diffractions;
  uint step;
  uint ray_index;
  uint iteration;
  vec3 arrival;
  float heard_energy;
  uint emit_cell;
  uint source_slot;
  float toward;
  uint reserved;
};

layout(set = 0, binding = 0, std430) readonly buffer Ring {
  Spot spots[];
};

layout(push_constant) uniform Push {
  mat4 view_projection;
  uint current_step;
  float dt;
  float lifetime;
} push;

void main() {
  const Spot spot = spots[gl_InstanceIndex];
  // The documented rule: age = (current_step - step) * dt, 0 for a later step.
  const uint steps = push.current_step >= spot.step ? push.current_step - spot.step : 0u;
  const bool live = float(steps) * push.dt < push.lifetime;
  gl_PointSize = 1.0;
  // Not live: outside the clip volume, so nothing is drawn.
  gl_Position = live ? push.view_projection * vec4(spot.position, 1.0) : vec4(2.0, 2.0, 2.0, 1.0);
}
