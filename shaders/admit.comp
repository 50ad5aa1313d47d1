#version 460
// After a step: admits the ring's share of the step's indicators (sp_ring.h)
// in six dispatches, chosen by push.finish (SP_ADMIT_*): a histogram of the
// capture list's admission bins, the threshold bin (one thread, which also
// clears the histogram), the same two for the tie-break bins of the bin
// where the quota runs out, the copy of the admitted indicators into the
// ring, and the ring's new head and size (one thread).
#extension GL_GOOGLE_include_directive : require
#include "gpu_bindings.glsl"
#include "sp_admission.h"

layout(local_size_x = SP_WORKGROUP_SIZE) in;

void clear_histogram() {
  for (uint b = 0u; b < SP_ADMISSION_BINS; ++b) admission_histogram[b] = 0u;
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  uint phase = push.finish;
  uint capacity = step_input.ring_capacity;
  if (phase == SP_ADMIT_SELECT) {
    if (i != 0u) return;
    sp_plan_admission(step_input.ring_quota);
    clear_histogram();
    return;
  }
  if (phase == SP_ADMIT_TIEBREAK_SELECT) {
    if (i != 0u) return;
    sp_plan_tiebreak(SP_ADMISSION_CLASSES);
    clear_histogram();
    return;
  }
  if (phase == SP_ADMIT_FINISH) {
    if (i != 0u) return;
    uint admitted = control.admit_count;
    control.ring_head = (control.ring_head + admitted) % capacity;
    control.ring_filled = min(capacity, control.ring_filled + admitted);
    control.draw_instance_count = control.ring_filled;
    return;
  }
  // The histograms and the copy run over the capture list; the copy reaches
  // the subgroup operations below in uniform control flow.
  bool valid = i < control.step_indicators;
  Indicator ind;
  uint bin = 0u;
  if (valid) {
    ind = capture[i];
    bin = sp_admission_bin(ind, step_input.inv_indicator_size);
  }
  if (phase == SP_ADMIT_HISTOGRAM) {
    if (valid) atomicAdd(admission_histogram[bin], 1u);
    return;
  }
  uint tiebreak = valid ? sp_admission_tiebreak(ind) : 0u;
  if (phase == SP_ADMIT_TIEBREAK_HISTOGRAM) {
    if (valid && sp_in_tiebreak_bin(bin)) atomicAdd(admission_histogram[tiebreak], 1u);
    return;
  }
  bool admit = valid && sp_admitted(bin, tiebreak);
  uvec4 ballot = subgroupBallot(admit);
  uint total = subgroupBallotBitCount(ballot);
  if (total == 0u) return;
  uint base = 0u;
  if (subgroupElect()) base = atomicAdd(control.admit_count, total);
  base = subgroupBroadcastFirst(base);
  // At most ring_quota <= capacity are admitted, so no two share a slot.
  if (admit) ring[(control.ring_head + base + subgroupBallotExclusiveBitCount(ballot)) % capacity] = ind;
}
