#version 460
// Before a frame's indicator draw, over the ring: how many live spots each
// source has (a source with none is not heard: no off-screen arrow), and,
// with max_per_category, which spots each category draws, the most
// energetic first (energy relative to the source's loudness). Four phases
// chosen by push.phase (SP_PREPASS_*):
//   CLEAR      zero the per-source counts and per-category histograms;
//   COUNT      per live spot: count its source; bin it in its category;
//   THRESHOLD  per category: the lowest bin drawn whole, and how many of
//              the bin below may still be drawn to reach the cap exactly;
//   MARK       per slot: drawn or not (the bin below the threshold is
//              shared out first come, first served).
#extension GL_GOOGLE_include_directive : require
#include "indicator_bindings.glsl"

layout(std430, push_constant) uniform Push { DisplayPrepassPush push; };

layout(local_size_x = 64) in;

uint cap_bin(Indicator ind) {
  float relative = clamp(ind.size * push.inv_indicator_size, 0.0, 1.0);
  return min(uint(relative * float(SP_CAP_BINS)), SP_CAP_BINS - 1u);
}

// A slot that the indicator draw would show, caps aside.
bool shown(uint slot, out Indicator ind, out uint category) {
  ind = ring[slot];
  DisplaySource source = sources[ind.source_id];
  category = source.category;
  return sp_indicator_live(push.current_step, ind.step, push.dt, push.lifetime) &&
         (source.shape_flags & SP_SOURCE_HIDDEN) == 0u;
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (push.phase == SP_PREPASS_CLEAR) {
    if (i < sources.length()) source_live[i] = 0u;
    if (i < push.category_count * SP_CATEGORY_STRIDE) categories[i] = 0u;
    return;
  }
  if (push.phase == SP_PREPASS_THRESHOLD) {
    if (i >= push.category_count) return;
    uint base = i * SP_CATEGORY_STRIDE;
    uint drawn = 0u;
    uint threshold = SP_CAP_BINS;  // none drawn whole
    for (uint b = SP_CAP_BINS; b > 0u; --b) {
      uint more = drawn + categories[base + b - 1u];
      if (more > push.max_per_category) break;
      drawn = more;
      threshold = b - 1u;
    }
    categories[base + SP_CAP_BINS] = threshold;
    categories[base + SP_CAP_BINS + 1u] = push.max_per_category - drawn;  // room in the bin below
    categories[base + SP_CAP_BINS + 2u] = 0u;
    return;
  }
  if (i >= min(draw_instance_count, push.ring_capacity)) return;
  Indicator ind;
  uint category;
  bool is_shown = shown(i, ind, category);
  if (push.phase == SP_PREPASS_COUNT) {
    if (!is_shown) return;
    atomicAdd(source_live[ind.source_id], 1u);
    if (push.max_per_category != 0xFFFFFFFFu) atomicAdd(categories[category * SP_CATEGORY_STRIDE + cap_bin(ind)], 1u);
    return;
  }
  // SP_PREPASS_MARK
  uint drawn = 0u;
  if (is_shown) {
    uint base = category * SP_CATEGORY_STRIDE;
    uint bin = cap_bin(ind);
    uint threshold = categories[base + SP_CAP_BINS];
    if (bin >= threshold) {
      drawn = 1u;
    } else if (bin + 1u == threshold && categories[base + SP_CAP_BINS + 1u] > 0u) {
      uint taken = atomicAdd(categories[base + SP_CAP_BINS + 2u], 1u);
      drawn = taken < categories[base + SP_CAP_BINS + 1u] ? 1u : 0u;
    }
  }
  visible[i] = drawn;
}
