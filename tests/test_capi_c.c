/* The C API used from C99: loads the bundled closed room, runs a few CPU
 * steps and checks that indicators and statistics agree, then adds, moves,
 * removes and emits sources through the sound scene. Exit status 0 on
 * success; otherwise prints the reason and returns 1. The Vulkan header is
 * included only to prove it compiles as C99; nothing here needs a device. */
#include <stdio.h>
#include <stdlib.h>

#include "soundpaint/soundpaint.h"
#include "soundpaint/soundpaint_vulkan.h"

static int failed(const char* what, sp_result result) {
  fprintf(stderr, "test_capi_c: %s failed (result %d): %s\n", what, (int)result, sp_last_error_message());
  return 1;
}

/* How many of the last step's live indicators come from `source_id`; -1 on error. */
static long last_step_indicators_of(sp_simulation* simulation, uint32_t source_id, uint32_t step) {
  sp_indicator* list = NULL;
  uint32_t count = 0;
  uint32_t i;
  long found = 0;
  sp_result r = sp_simulation_live_indicators(simulation, NULL, 0, &count);
  if (r != SP_OK) {
    failed("sp_simulation_live_indicators (size)", r);
    return -1;
  }
  if (count == 0) return 0;
  list = (sp_indicator*)malloc(count * sizeof(sp_indicator));
  if (list == NULL) return -1;
  r = sp_simulation_live_indicators(simulation, list, count, &count);
  if (r != SP_OK) {
    free(list);
    failed("sp_simulation_live_indicators", r);
    return -1;
  }
  for (i = 0; i < count; ++i)
    if (list[i].source_id == source_id && list[i].step == step) ++found;
  free(list);
  return found;
}

/* Adds a red source next to the room's own, moves it, removes it, and
 * emits a one-shot; the room has one scene source (id 0) and 5 steps run. */
static int scene_controls(sp_simulation* simulation) {
  sp_sound_scene* scene = NULL;
  sp_source_desc desc;
  uint32_t id = 0;
  uint32_t shot = 0;
  int live = 0;
  long n;
  sp_result r;
  /* Compile-time use of the Vulkan part's types. */
  (void)sizeof(sp_host_vulkan);
  (void)sizeof(sp_draw_target);

  r = sp_simulation_scene(simulation, &scene);
  if (r != SP_OK) return failed("sp_simulation_scene", r);
  sp_source_desc_init(&desc);
  desc.position[0] = 0.5f;
  desc.position[1] = 1.0f;
  desc.color[0] = 1.0f; /* its own red; all three left at -1 would take the palette's colour for "alarm" */
  desc.color[1] = 0.0f;
  desc.color[2] = 0.0f;
  desc.category = "alarm";
  r = sp_sound_scene_add_source(scene, &desc, &id);
  if (r != SP_OK) return failed("sp_sound_scene_add_source", r);
  if (id != 1) {
    fprintf(stderr, "test_capi_c: expected the added source to get id 1, got %u\n", (unsigned)id);
    return 1;
  }
  r = sp_sound_scene_move_source(scene, id, -0.5f, 1.0f, 0.5f);
  if (r != SP_OK) return failed("sp_sound_scene_move_source", r);
  r = sp_simulation_step(simulation); /* step 5 */
  if (r != SP_OK) return failed("sp_simulation_step", r);
  n = last_step_indicators_of(simulation, id, 5);
  if (n <= 0) {
    fprintf(stderr, "test_capi_c: the added source made no indicators (%ld)\n", n);
    return 1;
  }

  r = sp_sound_scene_remove_source(scene, id);
  if (r != SP_OK) return failed("sp_sound_scene_remove_source", r);
  if (sp_sound_scene_remove_source(scene, id) != SP_ERROR_INVALID_ARGUMENT || sp_last_error_message()[0] == '\0') {
    fprintf(stderr, "test_capi_c: removing twice was not an error with a message\n");
    return 1;
  }
  r = sp_sound_scene_emit(scene, &desc, 0.0, &shot); /* ends before it sounds */
  if (r != SP_OK) return failed("sp_sound_scene_emit", r);
  r = sp_simulation_step(simulation); /* step 6 */
  if (r != SP_OK) return failed("sp_simulation_step", r);
  n = last_step_indicators_of(simulation, id, 6);
  if (n != 0) {
    fprintf(stderr, "test_capi_c: a removed source still made %ld indicators\n", n);
    return 1;
  }
  r = sp_sound_scene_has_source(scene, shot, &live);
  if (r != SP_OK) return failed("sp_sound_scene_has_source", r);
  if (live != 0) {
    fprintf(stderr, "test_capi_c: a zero-length one-shot outlived its step\n");
    return 1;
  }
  return 0;
}

/* The context API from C: the version, a context with a thread cap, a
 * scene loaded and a simulation created in it, its per-layer counters. */
static int context_in_c(void) {
  sp_context_settings settings;
  sp_simulation_options options;
  sp_context* context = NULL;
  sp_scene* scene = NULL;
  sp_simulation* simulation = NULL;
  sp_layer_stats layers[8];
  uint32_t layer_count = 0;
  uint32_t threads = 0;
  uint64_t hits = 0;
  uint32_t k;
  sp_result r;

  if (sp_get_version() != SOUNDPAINT_VERSION) {
    fprintf(stderr, "test_capi_c: sp_get_version() is not SOUNDPAINT_VERSION\n");
    return 1;
  }
  sp_context_settings_init(&settings);
  settings.max_threads = 1;
  r = sp_context_create(&settings, &context);
  if (r != SP_OK) return failed("sp_context_create", r);
  r = sp_scene_load_in(context, SP_SCENES_DIR "/closed_room.gltf", NULL, &scene);
  if (r != SP_OK) return failed("sp_scene_load_in", r);
  sp_simulation_options_init(&options);
  options.backend = SP_BACKEND_CPU;
  r = sp_simulation_create_in(context, scene, "{ \"ray_budget\": 100 }", &options, &simulation);
  sp_scene_destroy(scene);
  sp_context_destroy(context); /* the simulation keeps it */
  if (r != SP_OK) return failed("sp_simulation_create_in", r);
  r = sp_simulation_step(simulation);
  if (r == SP_OK) r = sp_simulation_thread_count(simulation, &threads);
  if (r == SP_OK) r = sp_simulation_layer_stats(simulation, layers, 8, &layer_count);
  sp_simulation_destroy(simulation);
  if (r != SP_OK) return failed("a context's simulation", r);
  for (k = 0; k < layer_count && k < 8; ++k) hits += layers[k].hits;
  /* A closed room: each of the 100 rays hits a wall at least once. */
  if (threads != 1 || layer_count == 0 || hits < 100) {
    fprintf(stderr, "test_capi_c: %u threads, %u layers, %llu hits\n", (unsigned)threads, (unsigned)layer_count,
            (unsigned long long)hits);
    return 1;
  }
  return 0;
}

int main(void) {
  const char* config = "{ \"ray_budget\": 100, \"seed\": 7 }";
  sp_scene* scene = NULL;
  sp_simulation* simulation = NULL;
  sp_indicator* indicators = NULL;
  sp_stats stats;
  uint32_t sources = 0;
  uint32_t count = 0;
  uint32_t written = 0;
  uint32_t i;
  int step;
  int status = 1;
  sp_result r;

  if (context_in_c() != 0) return 1;
  r = sp_scene_load(SP_SCENES_DIR "/closed_room.gltf", &scene);
  if (r != SP_OK) return failed("sp_scene_load", r);
  r = sp_simulation_create(scene, config, SP_BACKEND_CPU, &simulation);
  sp_scene_destroy(scene); /* the simulation does not reference the scene */
  if (r != SP_OK) return failed("sp_simulation_create", r);

  r = sp_simulation_source_count(simulation, &sources);
  if (r != SP_OK) {
    failed("sp_simulation_source_count", r);
    goto done;
  }
  if (sources != 1) {
    fprintf(stderr, "test_capi_c: expected 1 source, got %u\n", (unsigned)sources);
    goto done;
  }

  for (step = 0; step < 5; ++step) {
    r = sp_simulation_step(simulation);
    if (r != SP_OK) {
      failed("sp_simulation_step", r);
      goto done;
    }
  }

  r = sp_simulation_live_indicators(simulation, NULL, 0, &count); /* size query */
  if (r != SP_OK) {
    failed("sp_simulation_live_indicators (size)", r);
    goto done;
  }
  if (count == 0) {
    fprintf(stderr, "test_capi_c: no live indicators after 5 steps\n");
    goto done;
  }
  indicators = (sp_indicator*)malloc(count * sizeof(sp_indicator));
  if (indicators == NULL) {
    fprintf(stderr, "test_capi_c: out of memory\n");
    goto done;
  }
  r = sp_simulation_live_indicators(simulation, indicators, count, &written);
  if (r != SP_OK) {
    failed("sp_simulation_live_indicators", r);
    goto done;
  }
  if (written != count) {
    fprintf(stderr, "test_capi_c: live count changed between calls: %u then %u\n", (unsigned)count, (unsigned)written);
    goto done;
  }
  for (i = 0; i < count; ++i) {
    if (indicators[i].source_id != 0 || indicators[i].step > 4 || !(indicators[i].energy > 0.0f) ||
        indicators[i].energy > 1.0f || indicators[i].kind > SP_INDICATOR_KIND_EXIT) {
      fprintf(stderr, "test_capi_c: indicator %u is inconsistent (source %u, step %u, energy %g)\n", (unsigned)i,
              (unsigned)indicators[i].source_id, (unsigned)indicators[i].step, (double)indicators[i].energy);
      goto done;
    }
  }

  r = sp_simulation_stats(simulation, &stats);
  if (r != SP_OK) {
    failed("sp_simulation_stats", r);
    goto done;
  }
  if (stats.steps != 5 || stats.rays_emitted != 500 || stats.indicators < count || stats.casts < stats.rays_emitted) {
    fprintf(stderr, "test_capi_c: inconsistent stats: steps %llu, rays %llu, casts %llu, indicators %llu, live %u\n",
            (unsigned long long)stats.steps, (unsigned long long)stats.rays_emitted, (unsigned long long)stats.casts,
            (unsigned long long)stats.indicators, (unsigned)count);
    goto done;
  }
  printf("test_capi_c: %u live indicators, %llu created, %llu casts\n", (unsigned)count,
         (unsigned long long)stats.indicators, (unsigned long long)stats.casts);
  if (scene_controls(simulation) != 0) goto done;
  status = 0;

done:
  free(indicators);
  if (sp_simulation_destroy(simulation) != SP_OK) return failed("sp_simulation_destroy", SP_ERROR_INTERNAL);
  /* A second destroy is detected, not undefined. */
  if (status == 0 && sp_simulation_destroy(simulation) != SP_ERROR_INVALID_ARGUMENT) {
    fprintf(stderr, "test_capi_c: destroying twice was not detected\n");
    return 1;
  }
  return status;
}
