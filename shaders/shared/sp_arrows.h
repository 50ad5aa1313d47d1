// The off-screen arrows' geometry (shaders/arrow.*; docs/accessibility.md,
// "Off-screen arrows"), shared with C++ so that tests can check the ring
// keeps every arrow on screen.
//
// The display contract: an arrow's angle about the picture's centre,
// measured clockwise from straight up, is its source's bearing right of the
// view's heading (0 ahead, 90 degrees right, 180 behind), as on the ring
// round a shooter's crosshair. A measuring tool reads that angle from the
// centroid of the arrow's pixels, so every arrow is mirror-symmetric about
// its radial line (every shape of sp_shapes.h has a mirror on its +x axis,
// and the head and marks are built on that axis) and only moves along it:
// inwards when it stacks, and elevation is a mark on the line, never a
// sideways shift.
//
// Frames: "screen" is pixels from the viewport's centre, +x right, +y down
// (Vulkan's viewport). The arrow's own frame has +x outwards along its
// radial line and units of half the shape's diameter (ArrowPush.arrow_pixels
// / 2 pixels): the shape is centred on the origin inside the unit disc, the
// head points outwards.
#ifndef SP_ARROWS_H
#define SP_ARROWS_H

#include "sp_lang.h"
#include "sp_shapes.h"

// The arrowhead: a triangle from its back edge at x = SP_ARROW_HEAD_BACK,
// SP_ARROW_HEAD_HALF_HEIGHT either side of the axis, to its tip.
#define SP_ARROW_HEAD_BACK 1.25f
#define SP_ARROW_HEAD_TIP 2.2f
#define SP_ARROW_HEAD_HALF_HEIGHT 0.75f
// Elevation marks: a bar across the radial line on a stem along it, beyond
// the tip for a source above eye level (a T over the head, for an arrow at
// the top of the picture) and behind the shape for one below (a T turned
// over, under the shape). The stems join each bar to the arrow, so that an
// arrow and its mark are one blob, whatever the shape; they start inside
// the head and inside (or within a halo of) every shape.
#define SP_ARROW_MARK_ABOVE_X 2.7f
#define SP_ARROW_MARK_BELOW_X (-1.6f)
#define SP_ARROW_MARK_HALF_THICKNESS 0.15f
#define SP_ARROW_MARK_HALF_LENGTH 0.8f
#define SP_ARROW_STEM_HALF_WIDTH 0.12f
#define SP_ARROW_STEM_ABOVE_FROM 2.0f
#define SP_ARROW_STEM_BELOW_FROM (-0.3f)
// A source this far above or below eye level (degrees) gets its mark: less
// is "level" for a player, whose view tilts that much without noticing.
#define SP_ARROW_MARK_DEGREES 15.0f
#define SP_ARROW_MARK_NONE 0u
#define SP_ARROW_MARK_ABOVE 1u
#define SP_ARROW_MARK_BELOW 2u
// Room round the drawn parts for the halo (two 1.5 px rings and the
// anti-aliased edge, 3.5 px, under 0.3 units at any size down to 24 px).
#define SP_ARROW_HALO_ROOM 0.3f
// The arrow's quad, marks included whether drawn or not (so that an arrow's
// place does not move when its source climbs a stair): x from LOW to HIGH,
// y within +-HALF_WIDTH.
#define SP_ARROW_LOW (SP_ARROW_MARK_BELOW_X - SP_ARROW_MARK_HALF_THICKNESS - SP_ARROW_HALO_ROOM)
#define SP_ARROW_HIGH (SP_ARROW_MARK_ABOVE_X + SP_ARROW_MARK_HALF_THICKNESS + SP_ARROW_HALO_ROOM)
#define SP_ARROW_HALF_WIDTH (SP_RIM_RADIUS + SP_ARROW_HALO_ROOM)  // the widest shapes reach the rim
// Pixels left between the quad and the viewport's edge, and between the
// quads of two stacked arrows (their halos then stay ~10 px apart).
#define SP_ARROW_EDGE_PIXELS 4.0f
#define SP_ARROW_GAP_PIXELS 4.0f
// Arrows that would cover one another on the ring stack inwards along
// their radial lines: at most SP_ARROW_MAX_STACK places deep, fewer where
// the stack would reach into the disc of SP_ARROW_CLEAR_CENTRE times the
// viewport's smaller half-size round the centre, where the player aims.
// Places are dealt in turn along a run of arrows, so neighbours differ;
// the vertex shader walks a run back at most SP_ARROW_MAX_RUN arrows (it
// bounds its loops over the source table), and arrows further along share
// a place.
#define SP_ARROW_MAX_STACK 4u
#define SP_ARROW_CLEAR_CENTRE 0.15f
#define SP_ARROW_MAX_RUN 8u

SP_BEGIN_NAMESPACE

// The point the arrow is placed by (the middle of its quad along its
// radial line), in the arrow's frame, and the quad's half-length.
SP_INLINE float sp_arrow_anchor_x() { return 0.5f * (SP_ARROW_LOW + SP_ARROW_HIGH); }
SP_INLINE float sp_arrow_half_length() { return 0.5f * (SP_ARROW_HIGH - SP_ARROW_LOW); }

// The outward unit vector on screen at angle theta (radians clockwise from
// straight up).
SP_INLINE vec2 sp_arrow_direction(float theta) { return vec2(sin(theta), -cos(theta)); }

// Bearing of `to` (source minus eye, world space, +Y up) right of `heading`
// (a unit vector in the horizontal plane, as world (x, z)), radians in
// [-pi, pi]: both projected on the horizontal plane, so it does not depend
// on how far the source is above or below. Right of heading (x, z) is
// (-z, x): the horizontal part of heading x up. Straight above or below
// the eye the bearing is undefined; 0 (ahead).
SP_INLINE float sp_arrow_bearing(vec3 to, vec2 heading) {
  vec2 flat_to = vec2(to.x, to.z);
  if (dot(flat_to, flat_to) < 1.0e-12f) return 0.0f;
  vec2 right = vec2(-heading.y, heading.x);
  return atan(dot(flat_to, right), dot(flat_to, heading));
}

// SP_ARROW_MARK_* for a source at `to` from the eye: above or below eye
// level by more than SP_ARROW_MARK_DEGREES.
SP_INLINE uint sp_arrow_elevation_mark(vec3 to) {
  float flat_distance = length(vec2(to.x, to.z));
  if (flat_distance == 0.0f && to.y == 0.0f) return SP_ARROW_MARK_NONE;  // atan(0, 0) is undefined in GLSL
  float elevation = atan(to.y, flat_distance);
  float limit = SP_ARROW_MARK_DEGREES * (SP_PI / 180.0f);
  if (elevation > limit) return SP_ARROW_MARK_ABOVE;
  if (elevation < -limit) return SP_ARROW_MARK_BELOW;
  return SP_ARROW_MARK_NONE;
}

// Distance from the viewport's centre, pixels, of the anchor of an arrow
// at angle theta on the ring: a superellipse (|x/a|^4 + |y/b|^4 = 1, a
// rounded rectangle that keeps to the screen's edge better than an
// ellipse) whose half-axes a, b are the viewport's half-size less this
// arrow's reach along each axis at this angle and SP_ARROW_EDGE_PIXELS.
// The anchor lies inside the box |x| <= a, |y| <= b, so the whole quad
// stays on screen. `scale` is pixels per arrow unit. 0 when the viewport is
// too small to hold the arrow anywhere but the centre.
SP_INLINE float sp_arrow_ring_distance(float theta, vec2 half_size, float scale) {
  vec2 dir = sp_arrow_direction(theta);
  vec2 along = abs(dir) * (sp_arrow_half_length() * scale);
  vec2 across = vec2(abs(dir.y), abs(dir.x)) * (SP_ARROW_HALF_WIDTH * scale);
  vec2 box = half_size - along - across - vec2(SP_ARROW_EDGE_PIXELS);
  if (box.x <= 0.0f || box.y <= 0.0f) return 0.0f;
  vec2 u = dir / box;
  u = u * u;
  return 1.0f / sqrt(sqrt(u.x * u.x + u.y * u.y));
}

SP_END_NAMESPACE

#endif  // SP_ARROWS_H
