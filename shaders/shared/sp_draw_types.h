// Layouts and constants of the graphics pass (scene + indicators), shared by
// shaders/scene.* and shaders/indicator.* and by src/draw. Both passes pull
// their vertices from storage buffers, so these structs are the whole
// vertex interface; src/draw/draw_layout_checks.h holds the static_asserts.
#ifndef SP_DRAW_TYPES_H
#define SP_DRAW_TYPES_H

#include "sp_types.h"

// Vertices of one indicator quad (two triangles); the compute pass writes the
// same count into the VkDrawIndirectCommand it keeps (Control.draw_vertex_count).
#define SP_INDICATOR_QUAD_VERTICES 6u
// Metres an indicator floats above its surface along its normal: enough to
// win the depth test against that surface with a D32 buffer out to ~100 m,
// too little to be seen as a gap.
#define SP_INDICATOR_LIFT 0.01f
// Fragments fainter than this are discarded: they would round to nothing in
// an 8-bit target anyway.
#define SP_MIN_VISIBLE_ALPHA 0.004f

// SceneTriangle.shading: level surfaces lit by the scene's light, or markers
// that light themselves (bright from every side, shaded only by how far each
// face turns from the eye) so they read as "not part of the level".
#define SP_SHADE_LIT 0u
#define SP_SHADE_MARKER 1u
// SceneTriangle.layer of marker triangles (they belong to no layer).
#define SP_MARKER_LAYER 0xFFFFFFFFu

SP_BEGIN_NAMESPACE

#ifdef __cplusplus
using glm::mat4;
#endif

// One triangle of the scene pass, 64 bytes; vertex i of the draw reads
// triangle i / 3, corner i % 3. The flat normal is derived in the vertex
// shader from the corners (counter-clockwise seen from its front).
struct SceneTriangle {
  vec3 v0;
  uint shading;  // SP_SHADE_*
  vec3 v1;
  uint layer;    // layer id, or SP_MARKER_LAYER
  vec3 v2;
  uint pad0;
  vec3 color;    // linear RGB tint
  uint pad1;
};

// Push constants of the scene pass, 96 bytes.
struct ScenePush {
  mat4 view_proj;   // world -> Vulkan clip space
  vec3 eye;         // camera position, world space
  float ambient;    // light every surface gets, in [0, 1]
  vec3 light_dir;   // unit vector towards the light
  float fog_distance;  // metres at which distant surfaces have faded 63% into the clear colour; 0: no fog
};

// Push constants of the indicator pass, 96 bytes.
struct IndicatorPush {
  mat4 view_proj;      // world -> Vulkan clip space
  vec3 eye;            // camera position: indicators facing away from it are skipped
  uint current_step;   // the step the picture shows (the last one run)
  float dt;            // seconds per step
  float lifetime;      // indicator_lifetime, seconds (> 0)
  uint pad0;
  uint pad1;
};

SP_END_NAMESPACE

#endif  // SP_DRAW_TYPES_H
