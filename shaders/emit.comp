#version 460
// Stage (a): emits the step's rays from the active sources into queue 0
// (uniformly, or a share from each source's guide: sp_guide.h) and resets
// the per-step counters (this kernel runs first in every step).
#extension GL_GOOGLE_include_directive : require
#include "gpu_bindings.glsl"
#include "sp_guide.h"
#include "sp_ray_model.h"
#include "sp_ring.h"

layout(local_size_x = SP_WORKGROUP_SIZE, local_size_x_id = SP_SPEC_WORKGROUP_SIZE) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  uint total = step_input.total_rays;
  if (i == 0u) {
    control.queues[0].active_count = total;
    control.queues[0].resolving_count = 0u;
    set_queue_groups(0u);
    control.queues[1].active_count = 0u;
    control.queues[1].resolving_count = 0u;
    set_queue_groups(1u);
    control.step_indicators = 0u;
    control.step_casts = 0u;
    control.step_cut_short = 0u;
    control.step_connections = 0u;
    control.connect_count = 0u;
    control.admit_count = 0u;
    control.tiebreak_count = 0u;
    control.resolve_done = 0u;
    control.connect_done = 0u;
    control.tiebreak_done = 0u;
    control.copy_done = 0u;
    // The passes after the wavefront, until resolve says more: the connect
    // pass always runs (its last workgroup plans the admission and keeps
    // the totals); the admission's passes run over no indicator.
    control.connect_group_count_x = 1u;
    control.connect_group_count_y = 1u;
    control.connect_group_count_z = 1u;
    control.admit_group_count_x = 0u;
    control.admit_group_count_y = 1u;
    control.admit_group_count_z = 1u;
  }
  if (i < step_input.layer_count * SP_COUNTERS_PER_LAYER) counters[i] = 0u;
  // The admission's order bitmap, which the last step's copy read.
  uint order_words = SP_ORDER_WORDS(push.max_rays, push.iterations);
  for (uint w = i; w < order_words; w += gl_NumWorkGroups.x * kGroupWidth)
    admission_histogram[SP_ORDER_BITMAP + w] = 0u;
  if (i >= total) return;

  // Sources own contiguous ray ranges in ascending order: binary search.
  uint lo = 0u;
  uint hi = step_input.source_count - 1u;
  while (lo < hi) {
    uint mid = (lo + hi + 1u) / 2u;
    if (step_sources[mid].first_ray <= i) lo = mid; else hi = mid - 1u;
  }
  uint cell;
  vec3 dir = sp_source_emission(step_sources[lo], i, step_input.params, cell);
  rays[i] = sp_emit_ray(step_sources[lo], lo, i, dir, cell);
  queue_entries[i] = i;
}
