/* The C API used from C99: loads the bundled closed room, runs a few CPU
 * steps and checks that indicators and statistics agree. Exit status 0 on
 * success; otherwise prints the reason and returns 1. */
#include <stdio.h>
#include <stdlib.h>

#include "soundpaint/soundpaint.h"

static int failed(const char* what, sp_result result) {
  fprintf(stderr, "test_capi_c: %s failed (result %d): %s\n", what, (int)result, sp_last_error_message());
  return 1;
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

  r = sp_scene_load(SP_SCENES_DIR "/closed_room.gltf", &scene);
  if (r != SP_OK) return failed("sp_scene_load", r);
  r = sp_simulation_create(scene, config, SP_BACKEND_CPU, &simulation);
  sp_scene_destroy(scene); /* the simulation does not reference the scene */
  if (r != SP_OK) return failed("sp_simulation_create", r);

  r = sp_simulation_source_count(simulation, &sources);
  if (r != SP_OK) { failed("sp_simulation_source_count", r); goto done; }
  if (sources != 1) { fprintf(stderr, "test_capi_c: expected 1 source, got %u\n", (unsigned)sources); goto done; }

  for (step = 0; step < 5; ++step) {
    r = sp_simulation_step(simulation);
    if (r != SP_OK) { failed("sp_simulation_step", r); goto done; }
  }

  r = sp_simulation_live_indicators(simulation, NULL, 0, &count); /* size query */
  if (r != SP_OK) { failed("sp_simulation_live_indicators (size)", r); goto done; }
  if (count == 0) { fprintf(stderr, "test_capi_c: no live indicators after 5 steps\n"); goto done; }
  indicators = (sp_indicator*)malloc(count * sizeof(sp_indicator));
  if (indicators == NULL) { fprintf(stderr, "test_capi_c: out of memory\n"); goto done; }
  r = sp_simulation_live_indicators(simulation, indicators, count, &written);
  if (r != SP_OK) { failed("sp_simulation_live_indicators", r); goto done; }
  if (written != count) {
    fprintf(stderr, "test_capi_c: live count changed between calls: %u then %u\n", (unsigned)count,
            (unsigned)written);
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
  if (r != SP_OK) { failed("sp_simulation_stats", r); goto done; }
  if (stats.steps != 5 || stats.rays_emitted != 500 || stats.indicators < count || stats.casts < stats.rays_emitted) {
    fprintf(stderr,
            "test_capi_c: inconsistent stats: steps %llu, rays %llu, casts %llu, indicators %llu, live %u\n",
            (unsigned long long)stats.steps, (unsigned long long)stats.rays_emitted,
            (unsigned long long)stats.casts, (unsigned long long)stats.indicators, (unsigned)count);
    goto done;
  }
  printf("test_capi_c: %u live indicators, %llu created, %llu casts\n", (unsigned)count,
         (unsigned long long)stats.indicators, (unsigned long long)stats.casts);
  status = 0;

done:
  free(indicators);
  sp_simulation_destroy(simulation);
  return status;
}
