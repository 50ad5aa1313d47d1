#version 460
// Stage (b)/(d), ResolvingPenetration rays: the matter query that replaces the
// paper's backcast (docs/model.md#matter-where-a-penetrating-ray-leaves) -- the
// nearest faces behind p_in, then where the ray leaves matter (sp_matter.h) --
// one per resolving ray of the queue (its back, QueueArgs).
#extension GL_GOOGLE_include_directive : require
#include "gpu_bindings.glsl"
#include "sp_traverse.h"
#include "sp_ray_model.h"

layout(local_size_x = SP_WORKGROUP_SIZE, local_size_x_id = SP_SPEC_WORKGROUP_SIZE) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  bool valid = i < control.queues[push.queue_in].resolving_count;
  if (valid) {
    uint ray_index = queue_entry(push.queue_in, control.queues[push.queue_in].active_count + i);
    RayState r = load_ray(ray_index);
    HitList list;
    sp_nearest_hits(r.entry, r.dir, sp_matter_tmin(), step_input.params.max_wall_thickness, list);
    store_hit(ray_index, sp_find_exit(list, r.entry_triangle));
  }
  uint casts = subgroupAdd(valid ? 1u : 0u);
  if (subgroupElect() && casts > 0u) atomicAdd(control.step_casts, casts);
}
