// Layouts and constants of the graphics pass (scene + indicators), shared by
// shaders/scene.* and shaders/indicator.* and by src/draw. Both passes pull
// their vertices from storage buffers, so these structs are the whole
// vertex interface; src/draw/draw_layout_checks.h holds the static_asserts.
#ifndef SP_DRAW_TYPES_H
#define SP_DRAW_TYPES_H

#include "sp_types.h"

// Vertices of one indicator quad, a two-triangle strip (four vertex
// invocations where a list of two triangles takes six); the compute pass
// writes the same count into the VkDrawIndirectCommand it keeps
// (Control.draw_vertex_count).
#define SP_INDICATOR_QUAD_VERTICES 4u
// Linear RGB a frame is cleared to; the scene's distance fog fades towards it.
#define SP_CLEAR_RGB 0.02f, 0.022f, 0.03f
// Metres an indicator floats above its surface along its normal: enough to
// win the depth test against that surface with a D32 buffer out to ~100 m,
// too little to be seen as a gap.
#define SP_INDICATOR_LIFT 0.01f
// Fragments fainter than this are discarded: they would round to nothing in
// an 8-bit target anyway.
#define SP_MIN_VISIBLE_ALPHA 0.004f
// Room the indicator quad leaves around the shape for the anti-aliased edge
// and the halo: two 1.5 px rings and half a pixel of edge (3.5 px seen
// square-on; the fragment stage covers nothing further out) and half a pixel
// for the perspective's change across the quad; or a share of the radius
// when the viewport's size is unknown, and never more. The pass costs its
// area, so the quad holds no more than the shape, its tail and this margin.
// Seen at a grazing angle, a pixel spans more of the surface and the halo,
// as wide in the spot's frame in every direction, reaches further: there it
// is cut at the quad's edge (growing the quad with 1 / cosine cost 18% more
// time on the H100 in bench_draw; bench/RESULTS.md).
#define SP_SPOT_MARGIN_PIXELS 4.0f
#define SP_SPOT_MARGIN_RADII 0.45f
// Tail length, in radii, when the sound grazes the surface; head-on it has
// no direction along the surface and no tail.
#define SP_SPOT_MAX_TAIL 1.6f
// Direct sound (first hits) stands out: larger and at full strength, while
// everything reflected or transmitted is drawn a little fainter.
#define SP_SPOT_DIRECT_SIZE 1.25f
#define SP_SPOT_INDIRECT_OPACITY 0.75f

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
  uint layer;  // layer id, or SP_MARKER_LAYER
  vec3 v2;
  uint pad0;
  vec3 color;  // linear RGB tint
  uint pad1;
};
SP_CHECK_LAYOUT(sizeof(SceneTriangle) == 64 && alignof(SceneTriangle) == 4 && offsetof(SceneTriangle, shading) == 12 && offsetof(SceneTriangle, v1) == 16 && offsetof(SceneTriangle, layer) == 28 && offsetof(SceneTriangle, v2) == 32 && offsetof(SceneTriangle, color) == 48);

// Push constants of the scene pass, 96 bytes.
struct ScenePush {
  mat4 view_proj;      // world -> Vulkan clip space
  vec3 eye;            // camera position, world space
  float ambient;       // light every surface gets, in [0, 1]
  vec3 light_dir;      // unit vector towards the light
  float fog_distance;  // metres at which distant surfaces have faded 63% into the clear colour; 0: no fog
};
SP_CHECK_LAYOUT(sizeof(ScenePush) == 96 && offsetof(ScenePush, eye) == 64 && offsetof(ScenePush, ambient) == 76 && offsetof(ScenePush, light_dir) == 80 && offsetof(ScenePush, fog_distance) == 92);

// IndicatorPush.flags: what the display settings (include/soundpaint/
// display.h) turn on.
#define SP_DRAW_DIRECTION 1u  // elongate each spot along its ray's direction
#define SP_DRAW_OUTLINE 2u    // the two-tone halo
#define SP_DRAW_CLIP 4u       // clip spots to their surface with the scene's depth (set 1)
#define SP_DRAW_CAPS 8u       // max_per_category: draw only slots the prepass marked

// Bindings of the indicator pass's descriptor set.
#define SP_DRAW_BINDING_RING 0
#define SP_DRAW_BINDING_SOURCES 1      // DisplaySource per source id
#define SP_DRAW_BINDING_SOURCE_LIVE 2  // per source id: live spots (the prepass)
#define SP_DRAW_BINDING_CATEGORIES 3   // per category: cap histogram and decision (the prepass)
#define SP_DRAW_BINDING_VISIBLE 4      // per ring slot: 1 when drawn under the caps (the prepass)
#define SP_DRAW_BINDING_DRAW_ARGS 5    // the ring's VkDrawIndirectCommand (instance count = filled slots)
#define SP_DRAW_BINDING_SOURCE_CUES 6  // per source id: SP_SOURCE_CUE_* bits for this step
#define SP_DRAW_BINDING_COUNT 7

// The halo's two rings, linear RGB: dark against the spot, light outside
// it. Against any surface one of them keeps at least sqrt(21) = 4.6:1
// (WCAG contrast; src/display/contrast.h derives it and checks these).
#define SP_HALO_DARK_RGB 0.0f, 0.0f, 0.0f
#define SP_HALO_LIGHT_RGB 1.0f, 1.0f, 1.0f

// DisplaySource.shape_flags: the shape (SP_SHAPE_*) in the low byte, then:
#define SP_SOURCE_HIDDEN 0x100u   // its category is in hide_categories
#define SP_SOURCE_PRESENT 0x200u  // a source with this id exists

// Per source id in the source cues buffer (SP_DRAW_BINDING_SOURCE_CUES),
// what the simulation found this step:
//   bit 0  SP_SOURCE_CUE_OCCLUDED  the direct path from the source to the
//          listener is blocked: a source heard but hidden gets its arrow
//          even when its direction is on screen.
//   bits 1..31 unused, 0.
#define SP_SOURCE_CUE_OCCLUDED 1u

// Per category in the categories buffer: a histogram of live spots by
// energy relative to their source (SP_CAP_BINS bins), then the lowest bin
// drawn whole, how many of the bin below it may still be drawn, and how
// many of those the prepass has taken.
#define SP_CAP_BINS 64u
#define SP_CATEGORY_STRIDE (SP_CAP_BINS + 3u)

// The prepass's phases (DisplayPrepassPush.phase).
#define SP_PREPASS_CLEAR 0u
#define SP_PREPASS_COUNT 1u
#define SP_PREPASS_THRESHOLD 2u
#define SP_PREPASS_MARK 3u

// A spot fades in over SP_FADE_IN_SECONDS, so it never pops on, and out
// over the rest of its display lifetime (sp_ring.h SP_MIN_DISPLAY_LIFETIME).
#define SP_FADE_IN_SECONDS 0.1f

// One source as the display sees it, 32 bytes.
struct DisplaySource {
  vec3 position;
  uint category;     // index in the world's category table
  vec3 color;        // linear RGB: its own colour, else its category's palette colour
  uint shape_flags;  // SP_SHAPE_* | SP_SOURCE_*
};
SP_CHECK_LAYOUT(sizeof(DisplaySource) == 32 && offsetof(DisplaySource, category) == 12 && offsetof(DisplaySource, color) == 16 && offsetof(DisplaySource, shape_flags) == 28);

// Push constants of the indicator pass, 128 bytes (Vulkan's guaranteed
// minimum of maxPushConstantsSize).
struct IndicatorPush {
  mat4 view_proj;            // world -> Vulkan clip space
  vec3 eye;                  // camera position: indicators facing away from it are skipped
  uint current_step;         // the step the picture shows (the last one run)
  float dt;                  // seconds per step
  float lifetime;            // the display's lifetime: max(indicator_lifetime, SP_MIN_DISPLAY_LIFETIME), seconds
  float pixel_scale;         // pixels per metre at 1 m in front of the eye, |projection[1][1]| * viewport height / 2;
                             // 0 when the viewport is unknown (no minimum size)
  uint viewport_size;        // pixels, width | height << 16; 0 when unknown
  float size_scale;          // display.size_scale
  float opacity_scale;       // display.opacity_scale
  float min_opacity;         // display.min_opacity
  uint flags;                // SP_DRAW_*
  float depth_a;             // the projection's depth terms, projection[2][2] and [3][2]:
  float depth_b;             //   view distance = depth_b / (depth + depth_a) for a perspective projection
  float inv_indicator_size;  // 1 / indicator_size: size * this = E / E0
  uint viewport_origin;      // the viewport's top-left pixel in the framebuffer (and the scene's depth), x | y << 16
};
SP_CHECK_LAYOUT(sizeof(IndicatorPush) == 128 && offsetof(IndicatorPush, eye) == 64 && offsetof(IndicatorPush, current_step) == 76 && offsetof(IndicatorPush, dt) == 80 && offsetof(IndicatorPush, lifetime) == 84 && offsetof(IndicatorPush, flags) == 108 && offsetof(IndicatorPush, depth_a) == 112);

// Push constants of the display prepass (display_prepass.comp), 32 bytes.
struct DisplayPrepassPush {
  uint phase;  // SP_PREPASS_*
  uint current_step;
  float dt;
  float lifetime;       // the display's lifetime, as IndicatorPush.lifetime
  uint category_count;  // categories in the categories buffer
  uint max_per_category;
  uint ring_capacity;
  float inv_indicator_size;
};
SP_CHECK_LAYOUT(sizeof(DisplayPrepassPush) == 32);

// Push constants of the off-screen arrows, 112 bytes.
struct ArrowPush {
  mat4 view_proj;      // world -> Vulkan clip space
  vec2 viewport;       // pixels
  float arrow_pixels;  // the arrow's shape's diameter, pixels: 2 units of its frame (sp_arrows.h)
  uint source_count;   // entries of the source table in use
  vec3 eye;            // camera position, world space
  uint pad0;
  vec2 heading;  // the view's heading, world (x, z), unit (DrawView::heading)
  vec2 pad1;
};
SP_CHECK_LAYOUT(sizeof(ArrowPush) == 112 && offsetof(ArrowPush, viewport) == 64 && offsetof(ArrowPush, arrow_pixels) == 72 && offsetof(ArrowPush, source_count) == 76 && offsetof(ArrowPush, eye) == 80 && offsetof(ArrowPush, heading) == 96);
// Vulkan guarantees 128 bytes of push constants on every device.
SP_CHECK_LAYOUT(sizeof(ScenePush) <= 128 && sizeof(IndicatorPush) <= 128 && sizeof(ArrowPush) <= 128);

SP_END_NAMESPACE

#endif  // SP_DRAW_TYPES_H
