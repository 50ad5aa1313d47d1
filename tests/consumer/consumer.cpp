// The C++ consumer of the consumer tests (tests/consumer/CMakeLists.txt):
// uses soundpaint only through its installed headers and
// soundpaint::soundpaint. Parses a config from a string, builds a world from
// a one-triangle scene and runs one CPU step. Exit status 0 when every call
// succeeds and the step makes an indicator; otherwise the reason on stderr.
#include <cstdio>
#include <utility>

#include <soundpaint/config.h>
#include <soundpaint/scene.h>
#include <soundpaint/simulation.h>

int main() {
  // A source at the origin with the listener on it; the triangle, 1 m in
  // front (+z) and facing it (front face clockwise as seen from the source,
  // as a wall's is), takes a good part of the sphere of rays.
  auto config = sp::parse_config(R"({
    "ray_budget": 64, "max_bounces": 0,
    "listener": { "position": [0, 0, 0] },
    "sources": [ { "position": [0, 0, 0], "loudness": 1.0 } ]
  })");
  if (!config) {
    std::fprintf(stderr, "consumer: parse_config: %s\n", config.error().message.c_str());
    return 1;
  }
  sp::Scene scene;
  scene.vertices = {{-4.0f, -4.0f, 1.0f}, {0.0f, 4.0f, 1.0f}, {4.0f, -4.0f, 1.0f}};
  scene.triangle_layers = {0};
  scene.layer_names = {"concrete"};
  auto world = sp::make_world(scene, *config);
  if (!world) {
    std::fprintf(stderr, "consumer: make_world: %s\n", world.error().message.c_str());
    return 1;
  }
  sp::CpuSettings settings;
  settings.threads = 1;
  auto simulator = sp::create_cpu_simulator(std::move(*world), settings);
  if (!simulator) {
    std::fprintf(stderr, "consumer: create_cpu_simulator: %s\n", simulator.error().message.c_str());
    return 1;
  }
  auto step = (*simulator)->step();
  if (!step) {
    std::fprintf(stderr, "consumer: step: %s\n", step.error().message.c_str());
    return 1;
  }
  auto indicators = (*simulator)->last_step_indicators();
  if (!indicators) {
    std::fprintf(stderr, "consumer: last_step_indicators: %s\n", indicators.error().message.c_str());
    return 1;
  }
  if (indicators->empty()) {
    std::fprintf(stderr, "consumer: one step against the triangle made no indicator\n");
    return 1;
  }
  std::printf("soundpaint C++ consumer: %zu indicators after one CPU step\n", indicators->size());
  return 0;
}
