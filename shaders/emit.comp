#version 460
// Stage (a), then (b) for its rays: emits the step's rays from the active
// sources into queue 0 (uniformly, or a share from each source's guide:
// sp_guide.h) and casts each at once, the first wavefront iteration's
// forward cast (trace.comp's query), so that no dispatch and barrier stand
// between the two. The host has written the step's starting counts and
// queue arguments before (gpu::step_start_control).
#extension GL_GOOGLE_include_directive : require
#include "gpu_bindings.glsl"
#include "sp_guide.h"
#include "sp_ray_model.h"
#include "sp_traverse.h"

layout(local_size_x = SP_WORKGROUP_SIZE, local_size_x_id = SP_SPEC_WORKGROUP_SIZE) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  bool valid = i < step_input.total_rays;
  if (valid) {
    // Sources own contiguous ray ranges in ascending order: binary search.
    uint lo = 0u;
    uint hi = step_input.source_count - 1u;
    while (lo < hi) {
      uint mid = (lo + hi + 1u) / 2u;
      if (step_source_first_ray(mid) <= i) lo = mid; else hi = mid - 1u;
    }
    uint cell;
    StepSource source = load_step_source(lo);
    vec3 dir = sp_source_emission(source, i, step_input.params, cell);
    RayState r = sp_emit_ray(source, lo, i, dir, cell);
    store_ray(i, r);
    queue_entries[i] = i;
    HitInfo hit = sp_closest_hit(r.origin, r.dir, 0.0f, sp_active_reach(r, step_input.params));
    store_hit(i, CastResult(hit.t, hit.triangle, 0.0f, hit.cut_short != 0u ? SP_CAST_CUT_SHORT : 0u));
  }
  uint casts = subgroupAdd(valid ? 1u : 0u);
  if (subgroupElect() && casts > 0u) atomicAdd(control.step_casts, casts);
}
