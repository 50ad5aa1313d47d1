#version 460
// Stage (c)/(d): resolves each queued ray's cast with the shared ray model --
// air loss, indicators, reflect or penetrate, where a penetrating ray leaves
// matter -- and queues the rays still alive for the next iteration. Its
// last subgroup to finish turns the queue's length into the next
// iteration's indirect arguments, and the step's counts so far into the
// dispatches after the wavefront (a one-thread prepare dispatch did both).
#extension GL_GOOGLE_include_directive : require
#include "gpu_bindings.glsl"
#include "sp_ray_model.h"
#include "sp_ring.h"

layout(local_size_x = SP_WORKGROUP_SIZE, local_size_x_id = SP_SPEC_WORKGROUP_SIZE) in;

// With diffraction off its code is compiled out (SP_SPEC_DIFFRACTION): the
// step's params then say 0 too, which the host checks.
layout(constant_id = SP_SPEC_DIFFRACTION) const bool kDiffraction = true;

void count_event(uint layer, uint slot) { atomicAdd(counters[layer * SP_COUNTERS_PER_LAYER + slot], 1u); }

void main() {
  uint i = gl_GlobalInvocationID.x;
  uint queue_out = 1u - push.queue_in;
  bool valid = i < queue_length(push.queue_in);
  bool alive = false;
  bool resolving = false;
  uint made = 0u;  // indicators this ray wrote: 0, 1, or 2 (a sheet's hit and exit)
  bool cut_short = false;
  uint ray_index = 0u;
  Indicator indicator;
  Indicator sheet_exit;
  if (valid) {
    ray_index = queue_entry(push.queue_in, i);
    RayState r = load_ray(ray_index);
    CastResult found = load_hit(ray_index);
    // On a miss the model reads no triangle field but the layer index the
    // caller passes; triangle 0 keeps that index in range.
    BvhTriangle tri = sp_bvh_triangle(found.triangle != SP_INVALID ? found.triangle : 0u);
    StepSource source = load_step_source(r.source);
    SimParams params = step_input.params;
    if (!kDiffraction) params.diffraction = 0u;
    // The edge table holds one entry only while diffraction is off.
    TriangleEdges edges = TriangleEdges(vec3(0.0), 0u, vec3(0.0), 0u);
    if (params.diffraction != 0u && found.triangle != SP_INVALID) edges = triangle_edges[found.triangle];
    uint outcome;
    if (r.state == SP_RAY_ACTIVE) {
      outcome = sp_resolve_active(r, found, tri, edges, layers[tri.layer], source, params, indicator,
                                  sheet_exit);
      if ((outcome & SP_OUTCOME_HIT) != 0u) count_event(tri.layer, SP_COUNTER_HITS);
      if ((outcome & SP_OUTCOME_REFLECT) != 0u) count_event(tri.layer, SP_COUNTER_REFLECTIONS);
      if ((outcome & SP_OUTCOME_PENETRATE) != 0u) count_event(tri.layer, SP_COUNTER_PENETRATIONS);
      if ((outcome & SP_OUTCOME_BACK_FACE) != 0u) count_event(tri.layer, SP_COUNTER_BACK_FACE_HITS);
      if ((outcome & SP_OUTCOME_DIFFRACT) != 0u) count_event(tri.layer, SP_COUNTER_DIFFRACTIONS);
    } else {
      outcome = sp_resolve_matter_exit(r, found, tri, source, step_input.params, indicator);
      if ((outcome & SP_OUTCOME_NO_WAY_OUT) != 0u) count_event(r.entry_layer, SP_COUNTER_NO_WAY_OUT);
    }
    cut_short = (outcome & SP_OUTCOME_CUT_SHORT) != 0u;
    store_ray(ray_index, r);
    alive = r.state != SP_RAY_DEAD;
    resolving = r.state == SP_RAY_RESOLVING;
    made = (outcome & SP_OUTCOME_INDICATOR) != 0u ? ((outcome & SP_OUTCOME_SHEET_EXIT) != 0u ? 2u : 1u) : 0u;
  }

  uint cut = subgroupAdd(cut_short ? 1u : 0u);
  if (subgroupElect() && cut > 0u) atomicAdd(control.step_cut_short, cut);

  // Indicators: one atomic per subgroup reserves slots in the step's
  // capture list; admit.comp picks the ring's share of them after the step.
  // A spot worth casting to the listener (sp_connection) is queued for the
  // connect kernel, so that it casts from a compact list; the others are
  // not heard, and say so at once.
  bool connect_first = false;
  bool connect_second = false;
  if (made > 0u) {
    connect_first = sp_connection(indicator, step_input.params).candidate != 0u;
    if (!connect_first) indicator.heard = 0.0f;
  }
  if (made > 1u) {
    connect_second = sp_connection(sheet_exit, step_input.params).candidate != 0u;
    if (!connect_second) sheet_exit.heard = 0.0f;
  }
  uint total = subgroupAdd(made);
  uint base = 0u;
  if (total > 0u) {
    if (subgroupElect()) base = atomicAdd(control.step_indicators, total);
    base = subgroupBroadcastFirst(base) + subgroupExclusiveAdd(made);
    if (made > 0u) store_capture(base, indicator);
    if (made > 1u) store_capture(base + 1u, sheet_exit);
  }
  uint connect_made = (connect_first ? 1u : 0u) + (connect_second ? 1u : 0u);
  uint connect_total = subgroupAdd(connect_made);
  if (connect_total > 0u) {
    uint at = 0u;
    if (subgroupElect()) at = atomicAdd(control.connect_count, connect_total);
    at = subgroupBroadcastFirst(at) + subgroupExclusiveAdd(connect_made);
    if (connect_first) connect_queue[at++] = base;
    if (connect_second) connect_queue[at] = base + 1u;
  }
  append_to_queue(queue_out, alive, resolving, ray_index);

  // A spot not worth a cast is not heard: its admission bin is final now.
  // (connect.comp bins the others once they are heard.)
  float inv_size = step_input.inv_indicator_size;
  if (made > 0u && !connect_first) {
    uint bin = sp_admission_bin(indicator, inv_size);
    atomicAdd(admission_histogram[bin], 1u);
    atomicAdd(admission_histogram[SP_ADMISSION_CLASS_COUNTS + sp_bin_class(bin)], 1u);
  }
  if (made > 1u && !connect_second) {
    uint bin = sp_admission_bin(sheet_exit, inv_size);
    atomicAdd(admission_histogram[bin], 1u);
    atomicAdd(admission_histogram[SP_ADMISSION_CLASS_COUNTS + sp_bin_class(bin)], 1u);
  }

  if (last_subgroup(SP_TICKET_RESOLVE) && subgroupElect()) {
    control.resolve_done = 0u;
    // The next iteration runs over what this one queued; the queue it
    // consumed is emptied for the iteration after.
    uint active_rays = atomicAdd(control.queues[queue_out].active_count, 0u);
    uint waiting = atomicAdd(control.queues[queue_out].resolving_count, 0u);
    control.queues[queue_out] = sp_queue_args(active_rays, waiting, kGroupWidth);
    control.queues[push.queue_in] = sp_queue_args(0u, 0u, kGroupWidth);
    // The passes after the wavefront, for the step so far: the casts to the
    // listener (at least one workgroup: its last plans the admission; at
    // most kConnectGroupsMax, whose lanes then take several spots each) and
    // the admission over the capture list.
    uint connect_groups = sp_group_count(atomicAdd(control.connect_count, 0u), kGroupWidth);
    control.connect_group_count_x = clamp(connect_groups, 1u, kConnectGroupsMax);
    control.admit_group_count_x = sp_group_count(atomicAdd(control.step_indicators, 0u), kGroupWidth);
  }
}
