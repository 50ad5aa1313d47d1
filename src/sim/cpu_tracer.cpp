#include "sim/cpu_tracer.h"

#include "bvh/bvh.h"
#include "sim/embree_traversal.h"
#include "sp_ray_model.h"

namespace sp {

void trace_ray(const TraceContext& context, shader::RayState ray, DefaultInitVector<shader::Indicator>& indicators,
               TraceCounters& counters) {
  using namespace shader;
  const BvhTriangle* triangles = context.bvh->triangles.data();
  const StepSource& source = context.sources[ray.source];
  const SimParams& p = context.params;
  BvhTriangle no_triangle{};
  const TriangleEdges no_edges{};
  const bool diffraction = p.diffraction != 0u;

  while (ray.state != SP_RAY_DEAD) {
    CastResult found{};
    if (ray.state == SP_RAY_ACTIVE) {
      // The 4-wide CPU traversal: same hits as the GPU's sp_closest_hit.
      // Or Embree's, the same up to float rounding.
      const float reach = sp_active_reach(ray, p);
      const HitInfo hit = context.embree ? context.embree->closest_hit(ray.origin, ray.dir, 0.0f, reach)
                                         : closest_hit(*context.bvh, ray.origin, ray.dir, 0.0f, reach);
      found = CastResult{hit.t, hit.triangle, 0.0f, hit.cut_short != 0u ? SP_CAST_CUT_SHORT : 0u};
    } else {
      // The 4-wide walk again; the same list as the GPU's sp_nearest_hits.
      const HitList list = nearest_hits(*context.bvh, ray.entry, ray.dir, sp_matter_tmin(), p.max_wall_thickness);
      found = sp_find_exit(triangles, context.layers.data(), list, ray.entry_triangle);
    }
    counters.casts += 1;
    const BvhTriangle& triangle = found.triangle != SP_INVALID ? triangles[found.triangle] : no_triangle;
    // The two indicators a cast may make are written where they stay, and
    // not zeroed first (a DefaultInitVector). Built in locals and appended,
    // each copy's 16-byte loads read fields just stored 4 bytes at a time,
    // which the core cannot forward: perf put half of trace_ray's time on
    // those copies. sp_make_indicator writes every field.
    const std::size_t first = indicators.size();
    indicators.resize(first + 2u);
    shader::Indicator& indicator = indicators[first];
    shader::Indicator& sheet_exit = indicators[first + 1u];
    uint outcome;
    if (ray.state == SP_RAY_ACTIVE) {
      // The edge table is filled only while diffraction is on.
      const TriangleEdges& edges =
          diffraction && found.triangle != SP_INVALID ? context.bvh->edges[found.triangle] : no_edges;
      outcome = sp_resolve_active(ray, found, triangle, edges, context.layers[triangle.layer], source, p, indicator,
                                  sheet_exit);
      LayerCounters& layer = counters.layers[triangle.layer];
      layer.hits += (outcome & SP_OUTCOME_HIT) != 0;
      layer.reflections += (outcome & SP_OUTCOME_REFLECT) != 0;
      layer.penetrations += (outcome & SP_OUTCOME_PENETRATE) != 0;
      layer.back_face_hits += (outcome & SP_OUTCOME_BACK_FACE) != 0;
      layer.diffractions += (outcome & SP_OUTCOME_DIFFRACT) != 0;
    } else {
      const uint entry_layer = ray.entry_layer;
      outcome = sp_resolve_matter_exit(ray, found, triangle, source, p, indicator);
      counters.layers[entry_layer].no_way_out += (outcome & SP_OUTCOME_NO_WAY_OUT) != 0;
    }
    counters.cut_short += (outcome & SP_OUTCOME_CUT_SHORT) != 0u;
    const bool made_indicator = (outcome & SP_OUTCOME_INDICATOR) != 0u;
    const bool made_sheet_exit = (outcome & SP_OUTCOME_SHEET_EXIT) != 0u;
    if (made_sheet_exit && !made_indicator) indicators[first] = sheet_exit;
    indicators.resize(first + made_indicator + made_sheet_exit);
  }
}

void connect_indicators(const TraceContext& context, std::span<shader::Indicator> indicators, TraceCounters& counters) {
  using namespace shader;
  const SimParams& p = context.params;
  for (shader::Indicator& ind : indicators) {
    const Connection c = sp_connection(ind, p);
    bool open = false;
    if (c.candidate != 0u) {
      // The GPU's occlusion walk's answer (sp_segment_blocked), from the
      // wide tree: it stops at the first triangle it meets.
      open = !segment_blocked(*context.bvh, c.origin, c.dir, 0.0f, c.distance);
      counters.connections += 1;
    }
    sp_finish_connection(ind, c, open, context.sources[ind.source_slot], p);
  }
}

}  // namespace sp
