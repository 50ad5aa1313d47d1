/* The C consumer of the consumer tests (tests/consumer/CMakeLists.txt): C99,
 * soundpaint only through the installed soundpaint.h (and
 * soundpaint_vulkan.h, to prove it compiles as C with nothing but the prefix
 * and the Vulkan headers) and soundpaint::capi or pkg-config. Checks the ABI
 * a binding relies on (the library's version against the header's, the
 * sizes of the public structs and sp_indicator's offsets, written out by
 * hand here), that a context's log hears a bad config's key, then makes a
 * one-triangle scene, runs one CPU step and reads the statistics. Exit
 * status 0 when every check and call succeeds and the step makes an
 * indicator. */
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include <soundpaint/soundpaint.h>
#include <soundpaint/soundpaint_vulkan.h>

static int failed(const char* what, sp_result result) {
  fprintf(stderr, "consumer_c: %s failed (result %d): %s\n", what, (int)result, sp_last_error_message());
  return 1;
}

/* Fails with the name of a layout fact that does not hold. */
static int layout_holds(int holds, const char* what) {
  if (!holds) fprintf(stderr, "consumer_c: ABI: %s does not hold\n", what);
  return holds;
}
#define SP_LAYOUT(expression) layout_holds((expression), #expression)

/* The public structs as a binding (C#, Rust) declares them, for LP64
 * targets: sizes of every struct, sp_indicator's every offset (it is fixed
 * forever), and struct_size first in the sized ones. */
static int abi_holds(void) {
  int ok = 1;
  if (sizeof(void*) != 8) return 1; /* the numbers below are LP64's */
  ok &= SP_LAYOUT(sizeof(sp_indicator) == 108);
  ok &= SP_LAYOUT(offsetof(sp_indicator, position) == 0);
  ok &= SP_LAYOUT(offsetof(sp_indicator, normal) == 12);
  ok &= SP_LAYOUT(offsetof(sp_indicator, energy) == 24);
  ok &= SP_LAYOUT(offsetof(sp_indicator, size) == 28);
  ok &= SP_LAYOUT(offsetof(sp_indicator, color) == 32);
  ok &= SP_LAYOUT(offsetof(sp_indicator, intensity) == 44);
  ok &= SP_LAYOUT(offsetof(sp_indicator, kind) == 48);
  ok &= SP_LAYOUT(offsetof(sp_indicator, source_id) == 52);
  ok &= SP_LAYOUT(offsetof(sp_indicator, bounces) == 56);
  ok &= SP_LAYOUT(offsetof(sp_indicator, penetrations) == 60);
  ok &= SP_LAYOUT(offsetof(sp_indicator, path_length) == 64);
  ok &= SP_LAYOUT(offsetof(sp_indicator, step) == 68);
  ok &= SP_LAYOUT(offsetof(sp_indicator, direction) == 72);
  ok &= SP_LAYOUT(offsetof(sp_indicator, diffractions) == 84);
  ok &= SP_LAYOUT(offsetof(sp_indicator, heard_energy) == 88);
  ok &= SP_LAYOUT(offsetof(sp_indicator, arrival) == 92);
  ok &= SP_LAYOUT(offsetof(sp_indicator, toward) == 104);
  ok &= SP_LAYOUT(sizeof(sp_stats) == 32);
  ok &= SP_LAYOUT(sizeof(sp_layer_stats) == 48);
  ok &= SP_LAYOUT(sizeof(sp_allocator) == 24);
  ok &= SP_LAYOUT(sizeof(sp_source_desc) == 64);
  ok &= SP_LAYOUT(sizeof(sp_display_settings) == 72);
  ok &= SP_LAYOUT(sizeof(sp_context_settings) == 56);
  ok &= SP_LAYOUT(sizeof(sp_scene_load_options) == 16);
  ok &= SP_LAYOUT(sizeof(sp_simulation_options) == 40);
  ok &= SP_LAYOUT(sizeof(sp_draw_options) == 40);
  ok &= SP_LAYOUT(sizeof(sp_visualizer_options) == 24);
  ok &= SP_LAYOUT(offsetof(sp_context_settings, struct_size) == 0);
  ok &= SP_LAYOUT(offsetof(sp_simulation_options, struct_size) == 0);
  ok &= SP_LAYOUT(offsetof(sp_scene_load_options, struct_size) == 0);
  ok &= SP_LAYOUT(offsetof(sp_draw_options, struct_size) == 0);
  ok &= SP_LAYOUT(offsetof(sp_visualizer_options, struct_size) == 0);
  return ok;
}

/* The last message a context's log received. */
static char logged[512];
static void remember_log(void* user_data, sp_log_level level, const char* message) {
  (void)user_data;
  if (level == SP_LOG_ERROR) {
    strncpy(logged, message, sizeof logged - 1);
    logged[sizeof logged - 1] = '\0';
  }
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

  sp_context_settings context_settings;
  sp_context* context = NULL;

  (void)sizeof(sp_host_vulkan); /* the Vulkan part's types compile */

  if (sp_get_version() != SOUNDPAINT_VERSION) {
    fprintf(stderr, "consumer_c: the library is version %lx, its header says %lx\n", (unsigned long)sp_get_version(),
            (unsigned long)SOUNDPAINT_VERSION);
    return 1;
  }
  if (!abi_holds()) return 1;

  r = sp_scene_create(vertices, 1, layers, layer_names, 1, &scene);
  if (r != SP_OK) return failed("sp_scene_create", r);
  /* A context whose log hears the config's bad key. */
  sp_context_settings_init(&context_settings);
  context_settings.log = remember_log;
  context_settings.max_threads = 1;
  r = sp_context_create(&context_settings, &context);
  if (r != SP_OK) return failed("sp_context_create", r);
  r = sp_simulation_create_in(context, scene, "{ \"ray_budget\": -1 }", NULL, &simulation);
  if (r != SP_ERROR_INVALID_CONFIG || strstr(logged, "ray_budget") == NULL) {
    fprintf(stderr, "consumer_c: a ray_budget of -1 gave result %d and logged \"%s\"\n", (int)r, logged);
    return 1;
  }
  r = sp_simulation_create_in(context, scene, config, NULL, &simulation);
  if (r != SP_OK) return failed("sp_simulation_create_in", r);
  r = sp_context_destroy(context);
  if (r != SP_OK) return failed("sp_context_destroy", r);
  r = sp_simulation_destroy(simulation);
  if (r != SP_OK) return failed("sp_simulation_destroy", r);

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
