#version 460
// After a step: admits the ring's share of the step's indicators (sp_ring.h)
// in seven dispatches, chosen by push.finish (SP_ADMIT_*):
// - histogram: each indicator's admission bin counted (connect.comp has
//   completed what it hears);
// - select: the budget (the quota, or the ring's free room) and the
//   threshold bins (one thread), while the other threads fold each step
//   source's guide;
// - the histogram of tie-break bins of the bins where a share runs out;
// - the tie-break thresholds (each workgroup's first thread), and the
//   admitted indicators' canonical keys marked in a bitmap; then (one
//   workgroup) the running counts of its words: each one's place in the
//   ring, so that it holds a step's spots in canonical order, as the CPU's;
// - the copy of the admitted indicators into the ring, which also clears
//   the histograms' counts for the next step;
// - the ring's new head and size (one thread).
#extension GL_GOOGLE_include_directive : require
#include "gpu_bindings.glsl"
#include "sp_admission.h"
#include "sp_guide.h"

layout(local_size_x = SP_WORKGROUP_SIZE) in;

shared uint chunk_counts[SP_WORKGROUP_SIZE];
shared uint tiebreak_plan[SP_ADMISSION_CLASSES];

// The canonical key of an indicator of this step: (iteration, ray, kind).
uint order_key(Indicator ind) { return (ind.iteration * push.max_rays + ind.ray_index) * 2u + ind.kind; }

// One workgroup: the running count of admitted keys before each bitmap
// word, stored after the bitmap.
void order_words() {
  uint words = SP_ORDER_WORDS(push.max_rays, push.iterations);
  uint per = (words + SP_WORKGROUP_SIZE - 1u) / SP_WORKGROUP_SIZE;
  uint t = gl_LocalInvocationID.x;
  uint first = min(t * per, words);
  uint last = min(first + per, words);
  uint count = 0u;
  for (uint w = first; w < last; ++w) count += bitCount(admission_histogram[SP_ORDER_BITMAP + w]);
  chunk_counts[t] = count;
  barrier();
  if (t == 0u) {
    uint sum = 0u;
    for (uint k = 0u; k < SP_WORKGROUP_SIZE; ++k) {
      uint here = chunk_counts[k];
      chunk_counts[k] = sum;
      sum += here;
    }
  }
  barrier();
  uint before = chunk_counts[t];
  for (uint w = first; w < last; ++w) {
    admission_histogram[SP_ORDER_BITMAP + words + w] = before;
    before += bitCount(admission_histogram[SP_ORDER_BITMAP + w]);
  }
}

// Slots of the ring whose indicator is live at step `now`. Births only grow
// from the oldest slot to the newest, so the first live one is found by
// bisection (the CPU's RingWriter counts the same from its runs).
uint live_slots(uint now) {
  uint capacity = step_input.ring_capacity;
  uint filled = control.ring_filled;
  uint oldest = (control.ring_head + capacity - filled) % capacity;
  uint lo = 0u;
  uint hi = filled;
  while (lo < hi) {
    uint mid = (lo + hi) / 2u;
    uint birth = ring[(oldest + mid) % capacity].step;
    if (sp_indicator_live(now, birth, float(step_input.dt), step_input.lifetime)) hi = mid; else lo = mid + 1u;
  }
  return filled - lo;
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  uint phase = push.finish;
  uint capacity = step_input.ring_capacity;
  if (phase == SP_ADMIT_SELECT) {
    if (i < step_input.source_count) sp_guide_fold(sp_guide_base(step_sources[i].source_id));
    if (i != 0u) return;
    uint live = live_slots(step_input.params.step);
    sp_plan_admission(sp_admission_budget(step_input.ring_quota, capacity, live));
    return;
  }

  if (phase == SP_ADMIT_ORDER) {
    order_words();
    return;
  }
  if (phase == SP_ADMIT_FINISH) {
    if (i != 0u) return;
    uint admitted = control.admit_count;
    control.ring_head = (control.ring_head + admitted) % capacity;
    control.ring_filled = min(capacity, control.ring_filled + admitted);
    control.draw_instance_count = control.ring_filled;
    uint before = control.total_connections_lo;
    control.total_connections_lo = before + control.step_connections;
    if (control.total_connections_lo < before) control.total_connections_hi += 1u;
    return;
  }
  // The histograms and the copy run over the capture list; the copy and
  // the counts reach the subgroup operations below in uniform control flow.
  bool valid = i < control.step_indicators;
  Indicator ind;
  uint bin = 0u;
  if (valid) {
    ind = capture[i];
    bin = sp_admission_bin(ind, step_input.inv_indicator_size);
  }
  if (phase == SP_ADMIT_HISTOGRAM) {
    if (valid) {
      atomicAdd(admission_histogram[bin], 1u);
      atomicAdd(admission_histogram[SP_ADMISSION_CLASS_COUNTS + sp_bin_class(bin)], 1u);
    }
    return;
  }
  uint tiebreak = valid ? sp_admission_tiebreak(ind) : 0u;
  if (phase == SP_ADMIT_TIEBREAK_HISTOGRAM) {
    if (valid && sp_in_tiebreak_bin(bin)) atomicAdd(admission_histogram[SP_ADMISSION_TIEBREAKS + tiebreak], 1u);
    return;
  }
  if (phase == SP_ADMIT_MARK) {
    // Each workgroup's first thread plans the tie-breaks (a few classes'
    // worth of work, where a dispatch of its own would cost more), the
    // first workgroup's also into the buffer for the copy.
    if (gl_LocalInvocationID.x == 0u) {
      for (uint c = 0u; c < SP_ADMISSION_CLASSES; ++c) {
        uint remaining = admission_histogram[SP_ADMISSION_PLAN_REMAINING + c];
        tiebreak_plan[c] = remaining == 0u ? sp_section_first(c) + sp_section_levels(c)
                                           : sp_class_threshold(c, remaining, SP_ADMISSION_TIEBREAKS);
        if (gl_WorkGroupID.x == 0u) admission_histogram[SP_ADMISSION_PLAN_TIEBREAK + c] = tiebreak_plan[c];
      }
    }
    barrier();
    uint c = sp_bin_class(bin);
    uint threshold = admission_histogram[SP_ADMISSION_PLAN_THRESHOLD + c];
    bool admitted = valid && (bin >= threshold || (bin + 1u == threshold && tiebreak >= tiebreak_plan[c]));
    uint mark_key = valid ? order_key(ind) : 0u;
    if (admitted) atomicOr(admission_histogram[SP_ORDER_BITMAP + mark_key / 32u], 1u << (mark_key % 32u));
    return;
  }
  bool admit = valid && sp_admitted(bin, tiebreak);
  uint key = valid ? order_key(ind) : 0u;
  uint word = key / 32u;
  uint bit = 1u << (key % 32u);
  // The copy also clears what the histograms counted, for the next step:
  // only the bins and classes of this step's indicators can be non-zero,
  // and only the plan and the order are read below.
  if (valid) {
    admission_histogram[bin] = 0u;
    admission_histogram[SP_ADMISSION_TIEBREAKS + tiebreak] = 0u;
    admission_histogram[SP_ADMISSION_CLASS_COUNTS + sp_bin_class(bin)] = 0u;
  }
  uint total = subgroupAdd(admit ? 1u : 0u);
  if (subgroupElect() && total > 0u) atomicAdd(control.admit_count, total);
  if (!admit) return;
  // Its place: how many admitted keys come before it. At most the budget
  // <= capacity are admitted, so no two share a slot.
  uint words = SP_ORDER_WORDS(push.max_rays, push.iterations);
  uint rank = admission_histogram[SP_ORDER_BITMAP + words + word] +
              bitCount(admission_histogram[SP_ORDER_BITMAP + word] & (bit - 1u));
  ring[(control.ring_head + rank) % capacity] = ind;
}
