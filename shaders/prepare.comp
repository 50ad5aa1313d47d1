#version 460
// One thread between wavefront iterations: turns the output queue's length
// into the next indirect dispatch, empties the consumed queue for reuse, and
// on the step's last iteration folds the step into the running totals and
// sizes the admission of its indicators to the ring (admit.comp).
#extension GL_GOOGLE_include_directive : require
#include "gpu_bindings.glsl"

layout(local_size_x = 1) in;

void add64(inout uint lo, inout uint hi, uint value) {
  uint sum = lo + value;
  if (sum < lo) hi += 1u;
  lo = sum;
}

void main() {
  uint queue_in = push.queue_in;
  uint queue_out = 1u - queue_in;
  set_queue_groups(queue_out);
  control.queues[queue_in].active_count = 0u;
  control.queues[queue_in].resolving_count = 0u;
  set_queue_groups(queue_in);
  if (push.finish == 0u) return;

  uint made = control.step_indicators;
  // The admission kernel runs over the step's capture list next.
  control.admit_group_count_x = group_count(made);
  control.admit_group_count_y = 1u;
  control.admit_group_count_z = 1u;
  control.admit_count = 0u;
  // The connect kernel runs over the spots resolve queued for it.
  control.connect_group_count_x = group_count(control.connect_count);
  control.connect_group_count_y = 1u;
  control.connect_group_count_z = 1u;
  add64(control.total_indicators_lo, control.total_indicators_hi, made);
  add64(control.total_casts_lo, control.total_casts_hi, control.step_casts);
  add64(control.total_cut_short_lo, control.total_cut_short_hi, control.step_cut_short);
  add64(control.total_rays_lo, control.total_rays_hi, step_input.total_rays);
  control.max_step_casts = max(control.max_step_casts, control.step_casts);
  control.steps += 1u;
  uint step_counters = step_input.layer_count * SP_COUNTERS_PER_LAYER;
  for (uint k = 0u; k < step_counters; ++k) {
    uint total_index = step_counters + 2u * k;
    add64(counters[total_index], counters[total_index + 1u], counters[k]);
  }
}
