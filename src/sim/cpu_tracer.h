// Traces one ray of the CPU backend from emission to death. Every live ray
// gets one cast per wavefront iteration, and each ray's path depends on its
// own state alone, so tracing ray by ray gives exactly the wavefront result;
// indicators carry their iteration so the caller can list them in the
// canonical (iteration, ray) order.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "bvh/bvh.h"
#include "core/default_init_allocator.h"
#include "soundpaint/simulation.h"

namespace sp {

// Adds `more` into `into`, field by field.
inline void accumulate(LayerCounters& into, const LayerCounters& more) {
  into.hits += more.hits;
  into.reflections += more.reflections;
  into.penetrations += more.penetrations;
  into.no_way_out += more.no_way_out;
  into.back_face_hits += more.back_face_hits;
  into.diffractions += more.diffractions;
}

// Per-worker counters, summed after the step (integer sums: order-free).
struct TraceCounters {
  std::uint64_t casts = 0;
  std::uint64_t cut_short = 0;    // casts that ended at SP_MAX_LEAF_VISITS
  std::uint64_t connections = 0;  // casts from a spot to the listener (sp_connect.h)
  std::vector<LayerCounters> layers;
};

class EmbreeTraversal;

struct TraceContext {
  const Bvh* bvh = nullptr;
  std::span<const shader::LayerAcoustics> layers;
  std::span<const shader::StepSource> sources;
  shader::SimParams params{};
  // Casts to the nearest surface when set (cpu_traversal "embree"); the
  // matter queries stay on bvh.
  const EmbreeTraversal* embree = nullptr;
};

// Traces `ray` (already emitted) to its end, appending its indicators.
void trace_ray(const TraceContext& context, shader::RayState ray, DefaultInitVector<shader::Indicator>& indicators,
               TraceCounters& counters);

// Casts each of `indicators`' way to the listener and completes what it
// hears (sp_connect.h), when params.cues asks for it. The cast is the
// GPU's occlusion walk (sp_segment_blocked), so it finds what the GPU's
// finds, Embree or not.
void connect_indicators(const TraceContext& context, std::span<shader::Indicator> indicators, TraceCounters& counters);

}  // namespace sp
