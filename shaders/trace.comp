#version 460
// Stage (b)/(d), Active rays: the forward cast, one closest-hit query per
// Active ray of the queue (its front, QueueArgs), from the second wavefront
// iteration on (emit.comp casts the rays it emits). trace_matter.comp
// serves the resolving rays of the same iteration.
#extension GL_GOOGLE_include_directive : require
#include "gpu_bindings.glsl"
#include "sp_traverse.h"
#include "sp_ray_model.h"

layout(local_size_x = SP_WORKGROUP_SIZE, local_size_x_id = SP_SPEC_WORKGROUP_SIZE) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  bool valid = i < control.queues[push.queue_in].active_count;
  if (valid) {
    uint ray_index = queue_entry(push.queue_in, i);
    RayState r = load_ray(ray_index);
    HitInfo hit = sp_closest_hit(r.origin, r.dir, 0.0f, sp_active_reach(r, step_input.params));
    store_hit(ray_index, CastResult(hit.t, hit.triangle, 0.0f, hit.cut_short != 0u ? SP_CAST_CUT_SHORT : 0u));
  }
  uint casts = subgroupAdd(valid ? 1u : 0u);
  if (subgroupElect() && casts > 0u) atomicAdd(control.step_casts, casts);
}
