#include "sim/cpu_tracer.h"

#include "soundpaint/bvh.h"
#include "sp_ray_model.h"

namespace sp {

void trace_ray(const TraceContext& context, shader::RayState ray, std::vector<Indicator>& indicators,
               TraceCounters& counters) {
  using namespace shader;
  const BvhTriangle* triangles = context.bvh->triangles.data();
  const StepSource& source = context.sources[ray.source];
  const SimParams& p = context.params;
  BvhTriangle no_triangle{};

  while (ray.state != SP_RAY_DEAD) {
    // The 4-wide CPU traversal; same hits as the GPU's sp_closest_hit.
    HitInfo hit = closest_hit(*context.bvh, sp_cast_origin(ray), ray.dir, sp_cast_tmin(ray), sp_cast_tmax(ray, p));
    counters.casts += 1;
    const BvhTriangle& triangle = hit.triangle != SP_INVALID ? triangles[hit.triangle] : no_triangle;
    Indicator indicator;
    uint outcome;
    if (ray.state == SP_RAY_ACTIVE) {
      outcome = sp_resolve_active(ray, hit, triangle, context.layers[triangle.layer], source, p, indicator);
      LayerCounters& layer = counters.layers[triangle.layer];
      layer.hits += (outcome & SP_OUTCOME_HIT) != 0;
      layer.reflections += (outcome & SP_OUTCOME_REFLECT) != 0;
      layer.penetrations += (outcome & SP_OUTCOME_PENETRATE) != 0;
    } else {
      uint entry_layer = ray.entry_layer;
      outcome = sp_resolve_backcast(ray, hit, triangle, context.layers[entry_layer], source, p, indicator);
      counters.layers[entry_layer].backcast_misses += (outcome & SP_OUTCOME_BACKCAST_MISS) != 0;
    }
    if (outcome & SP_OUTCOME_INDICATOR) indicators.push_back(indicator);
  }
}

}  // namespace sp
