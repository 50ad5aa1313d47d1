// The descriptor set of the indicator pass, its prepass and the off-screen
// arrows (bindings in sp_draw_types.h); each shader declares its own push
// constants.
#include "sp_draw_types.h"
#include "sp_ring.h"
#include "sp_shapes.h"

layout(std430, set = 0, binding = SP_DRAW_BINDING_RING) readonly buffer RingBuffer { Indicator ring[]; };
layout(std430, set = 0, binding = SP_DRAW_BINDING_SOURCES) readonly buffer SourcesBuffer { DisplaySource sources[]; };
layout(std430, set = 0, binding = SP_DRAW_BINDING_SOURCE_LIVE) buffer SourceLiveBuffer { uint source_live[]; };
layout(std430, set = 0, binding = SP_DRAW_BINDING_CATEGORIES) buffer CategoriesBuffer { uint categories[]; };
layout(std430, set = 0, binding = SP_DRAW_BINDING_VISIBLE) buffer VisibleBuffer { uint visible[]; };
layout(std430, set = 0, binding = SP_DRAW_BINDING_DRAW_ARGS) readonly buffer DrawArgsBuffer {
  uint draw_vertex_count;
  uint draw_instance_count;  // ring slots in use
};
layout(std430, set = 0, binding = SP_DRAW_BINDING_SOURCE_CUES) readonly buffer SourceCuesBuffer { uint source_cues[]; };
#ifdef SP_CLIP
// Set 1 holds only the scene's depth, so that the unclipped pipeline needs none.
layout(set = 1, binding = 0) uniform sampler2D scene_depth;
#endif
