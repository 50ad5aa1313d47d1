#version 460
// Stage (c)/(d): resolves each queued ray's cast with the shared ray model --
// air loss, indicators, reflect or penetrate, forward steps, backcast
// thickness -- and queues the rays still alive for the next iteration.
#extension GL_GOOGLE_include_directive : require
#include "gpu_bindings.glsl"
#include "sp_ray_model.h"

layout(local_size_x = SP_WORKGROUP_SIZE) in;

void count_event(uint layer, uint which) { atomicAdd(counters[layer * SP_COUNTERS_PER_LAYER + which], 1u); }

void main() {
  uint i = gl_GlobalInvocationID.x;
  uint queue_out = 1u - push.queue_in;
  bool valid = i < control.queues[push.queue_in].count;
  bool alive = false;
  bool has_indicator = false;
  uint ray_index = 0u;
  Indicator indicator;
  if (valid) {
    ray_index = queue_entries[push.queue_in * push.max_rays + i];
    RayState r = rays[ray_index];
    HitInfo hit = hits[ray_index];
    // On a miss the model reads no triangle field but the layer index the
    // caller passes; triangle 0 keeps that index in range.
    BvhTriangle tri = bvh_triangles[hit.triangle != SP_INVALID ? hit.triangle : 0u];
    StepSource source = step_sources[r.source];
    uint outcome;
    if (r.state == SP_RAY_ACTIVE) {
      outcome = sp_resolve_active(r, hit, tri, layers[tri.layer], source, step_input.params, indicator);
      if ((outcome & SP_OUTCOME_HIT) != 0u) count_event(tri.layer, 0u);
      if ((outcome & SP_OUTCOME_REFLECT) != 0u) count_event(tri.layer, 1u);
      if ((outcome & SP_OUTCOME_PENETRATE) != 0u) count_event(tri.layer, 2u);
    } else {
      uint entry_layer = r.entry_layer;
      outcome = sp_resolve_backcast(r, hit, tri, layers[entry_layer], source, step_input.params, indicator);
      if ((outcome & SP_OUTCOME_BACKCAST_MISS) != 0u) count_event(entry_layer, 3u);
    }
    rays[ray_index] = r;
    alive = r.state != SP_RAY_DEAD;
    has_indicator = (outcome & SP_OUTCOME_INDICATOR) != 0u;
  }

  // Indicators: one atomic per subgroup reserves slots in the step's
  // capture list; the ring slot follows from the step's ring head.
  uvec4 ballot = subgroupBallot(has_indicator);
  uint total = subgroupBallotBitCount(ballot);
  if (total > 0u) {
    uint base = 0u;
    if (subgroupElect()) base = atomicAdd(control.step_indicators, total);
    base = subgroupBroadcastFirst(base);
    if (has_indicator) {
      uint k = base + subgroupBallotExclusiveBitCount(ballot);
      capture[k] = indicator;
      ring[(control.ring_head + k) % step_input.ring_capacity] = indicator;
    }
  }
  append_to_queue(queue_out, alive, ray_index);
}
