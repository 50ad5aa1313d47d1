/* The C consumer of the consumer tests (tests/consumer/CMakeLists.txt): C99,
 * soundpaint only through the installed soundpaint.h (and
 * soundpaint_vulkan.h, to prove it compiles as C with nothing but the prefix
 * and the Vulkan headers) and soundpaint::capi or pkg-config. Makes a
 * one-triangle scene, runs one CPU step and reads the statistics. Exit
 * status 0 when every call succeeds and the step makes an indicator. */
#include <stdio.h>

#include <soundpaint/soundpaint.h>
#include <soundpaint/soundpaint_vulkan.h>

static int failed(const char* what, sp_result result) {
  fprintf(stderr, "consumer_c: %s failed (result %d): %s\n", what, (int)result, sp_last_error_message());
  return 1;
}

int main(void) {
  /* One triangle 1 m in front (+z) of a source at the origin, facing it. */
  static const float vertices[9] = {-4.0f, -4.0f, 1.0f, 0.0f, 4.0f, 1.0f, 4.0f, -4.0f, 1.0f};
  static const uint32_t layers[1] = {0};
  static const char* const layer_names[1] = {"concrete"};
  static const char config[] =
      "{ \"ray_budget\": 64, \"max_bounces\": 0, \"listener\": { \"position\": [0, 0, 0] },"
      "  \"sources\": [ { \"position\": [0, 0, 0], \"loudness\": 1.0 } ] }";
  sp_scene* scene = NULL;
  sp_simulation* simulation = NULL;
  sp_stats stats;
  sp_result r;

  (void)sizeof(sp_host_vulkan); /* the Vulkan part's types compile */

  r = sp_scene_create(vertices, 1, layers, layer_names, 1, &scene);
  if (r != SP_OK) return failed("sp_scene_create", r);
  r = sp_simulation_create(scene, config, SP_BACKEND_CPU, &simulation);
  if (r != SP_OK) return failed("sp_simulation_create", r);
  r = sp_simulation_step(simulation);
  if (r != SP_OK) return failed("sp_simulation_step", r);
  r = sp_simulation_stats(simulation, &stats);
  if (r != SP_OK) return failed("sp_simulation_stats", r);
  if (stats.steps != 1 || stats.indicators == 0) {
    fprintf(stderr, "consumer_c: expected 1 step and some indicators, got %llu steps, %llu indicators\n",
            (unsigned long long)stats.steps, (unsigned long long)stats.indicators);
    return 1;
  }
  r = sp_simulation_destroy(simulation);
  if (r != SP_OK) return failed("sp_simulation_destroy", r);
  r = sp_scene_destroy(scene);
  if (r != SP_OK) return failed("sp_scene_destroy", r);
  printf("soundpaint C consumer: %llu indicators after one CPU step\n", (unsigned long long)stats.indicators);
  return 0;
}
