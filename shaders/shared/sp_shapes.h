// Shapes of the indicator spots, one per kind of sound, drawn procedurally in
// the fragment shader as signed distance functions: no texture atlas, sharp
// at any size, and the distance gives the anti-aliased edge and an outline
// halo for free. The ids are the values of sp::Shape
// (include/soundpaint/display.h).
//
// Formulas: Inigo Quilez, "2D distance functions" (iquilezles.org/articles/
// distfunctions2d): circle, ring ("annular" shape), box, and the technique
// behind his rhombus, cross, hexagon and star: fold p by the shape's mirror
// symmetries into one wedge, where the boundary is a single segment or two,
// and measure the distance to those alone. The code is ours; every function
// here is exact (|gradient| = 1, zero on the boundary) inside and outside.
//
// Frame: p is in the spot's own frame, where the unit disc is the spot's
// extent; +x is the direction the sound was travelling, +y its left. The
// triangle points along +x. Distances are in the units of p, negative inside.
// Every shape stays inside the disc of radius 0.98; sp_shape_extent gives
// each one's own radius, to which the vertex shader sizes the spot's quad
// (plus room for the anti-aliased edge and the halo).
//
// Design rules (tests/test_shapes.cpp checks each):
//  - the same visual weight: every shape covers SP_SHAPE_AREA_SHARE of the
//    unit disc within 10%, so that loudness, shown by the spot's size, is not
//    read into its shape;
//  - strokes (ring, cross, plus) at least SP_SHAPE_STROKE wide;
//  - the spot's frame turns with the sound's direction on screen, so shapes
//    must differ under any rotation: the diamond is a long rhombus, not a
//    square on its corner, and the cross's arms are slender and cross at 60
//    degrees where the plus's are stout and cross at 90.
#ifndef SP_SHAPES_H
#define SP_SHAPES_H

#include "sp_lang.h"

#define SP_SHAPE_DISC 0u
#define SP_SHAPE_RING 1u
#define SP_SHAPE_DIAMOND 2u
#define SP_SHAPE_CROSS 3u
#define SP_SHAPE_PLUS 4u
#define SP_SHAPE_TRIANGLE 5u
#define SP_SHAPE_SQUARE 6u
#define SP_SHAPE_STAR 7u
#define SP_SHAPE_HEXAGON 8u
#define SP_SHAPE_CLOVER 9u
#define SP_SHAPE_COUNT 10u

// Share of the unit disc each shape covers (within 10%): the largest triangle
// inside the disc (equilateral, corners on the circle) covers
// 3*sqrt(3)/(4*pi) = 41%, and every other shape is sized to match it.
#define SP_SHAPE_AREA_SHARE 0.40f
// Width of the strokes of the ring and the cross (the plus's are wider), as a
// fraction of the spot's radius: 2.7 px at SP_SHAPE_MIN_PIXELS, so a stroke
// keeps a fully covered pixel at any sub-pixel offset.
#define SP_SHAPE_STROKE 0.34f
// Smallest spot diameter on screen, in pixels, at which every two shapes,
// under any rotation, differ by a whole pixel somewhere: the closest pair,
// the disc and the hexagon's corners, gets there at 15.5 px
// (tests/test_shapes.cpp measures it; the vertex shader enforces it).
#define SP_SHAPE_MIN_PIXELS 16.0f

// The comet's tail (indicator_fragment.glsl): it starts SP_TAIL_START radii
// behind the centre, SP_TAIL_ROOT_WIDTH wide (half-width, in radii), and
// narrows to SP_TAIL_TIP_WIDTH at its end.
#define SP_TAIL_START 0.85f
#define SP_TAIL_ROOT_WIDTH 0.22f
#define SP_TAIL_TIP_WIDTH 0.04f

SP_BEGIN_NAMESPACE

// Folds p into the wedge 0 <= angle <= pi/n around +x by the n mirror lines
// of a shape with n-fold rotational symmetry and a mirror on the x axis. The
// distance to such a shape is unchanged, and inside the wedge its boundary is
// one piece.
SP_INLINE vec2 sp_fold_to_wedge(vec2 p, float n) {
  float radius = length(p);
  // atan(0, 0) is undefined in GLSL; at the origin any angle will do.
  float angle = radius > 0.0f ? atan(p.y, p.x) : 0.0f;
  float half_wedge = SP_PI / n;
  float folded = abs(mod(angle + half_wedge, 2.0f * half_wedge) - half_wedge);
  return radius * vec2(cos(folded), sin(folded));
}

// Signed distance from q to the segment a-b, negative on its left (looking
// from a to b). Valid as a shape's distance only where the segment is the
// whole of the boundary near q, as in a folded wedge.
SP_INLINE float sp_edge_distance(vec2 q, vec2 a, vec2 b) {
  vec2 ab = b - a;
  vec2 aq = q - a;
  float t = clamp(dot(aq, ab) / dot(ab, ab), 0.0f, 1.0f);
  float distance = length(aq - ab * t);
  float left = ab.x * aq.y - ab.y * aq.x;
  return left > 0.0f ? -distance : distance;
}

// A star with n points on the circle of radius `outer` (one on +x) and its n
// inner corners on the circle of radius `inner`; with inner = outer *
// cos(pi/n) the corners fall on straight edges and it is a regular polygon.
SP_INLINE float sp_star_distance(vec2 p, float n, float outer, float inner) {
  vec2 q = sp_fold_to_wedge(p, n);
  float half_wedge = SP_PI / n;
  return sp_edge_distance(q, vec2(outer, 0.0f), inner * vec2(cos(half_wedge), sin(half_wedge)));
}

SP_INLINE float sp_regular_polygon_distance(vec2 p, float n, float circumradius) {
  return sp_star_distance(p, n, circumradius, circumradius * cos(SP_PI / n));
}

// Axis-aligned box (Quilez's sdBox).
SP_INLINE float sp_box_distance(vec2 p, vec2 half_size) {
  vec2 beyond = abs(p) - half_size;
  return length(max(beyond, vec2(0.0f))) + min(max(beyond.x, beyond.y), 0.0f);
}

// Two bars of half-length `half_length` and half-width `half_width` through
// the origin, at +-angle from the x axis, arm = (cos, sin) of it. Folded
// into the first quadrant, only the upper bar's boundary remains, from where
// it leaves the lower bar (on the x axis) to where it meets its mirror image
// (on the y axis).
SP_INLINE float sp_cross_distance(vec2 p, vec2 arm, float half_length, float half_width) {
  vec2 q = abs(p);
  vec2 bar = vec2(dot(q, arm), arm.x * q.y - arm.y * q.x);  // along, across the upper bar
  vec2 beyond = vec2(bar.x - half_length, abs(bar.y) - half_width);
  if (beyond.x > 0.0f || beyond.y > 0.0f) return length(max(beyond, vec2(0.0f)));
  // Inside: the nearest of the end cap and the two sides, each side starting
  // where the bar leaves the other arm.
  float lower_start = half_width * arm.x / arm.y;
  float upper_start = half_width * arm.y / arm.x;
  float to_lower = bar.x >= lower_start ? half_width + bar.y : length(bar - vec2(lower_start, -half_width));
  float to_upper = bar.x >= upper_start ? half_width - bar.y : length(bar - vec2(upper_start, half_width));
  return -min(-beyond.x, min(to_lower, to_upper));
}

// The sizes the shapes below share with sp_shape_extent. Areas in units of
// p squared.
#define SP_SHAPE_AREA (SP_SHAPE_AREA_SHARE * SP_PI)
// Ring: area 2*pi*mid*stroke.
#define SP_RING_MID_RADIUS (SP_SHAPE_AREA_SHARE / (2.0f * SP_SHAPE_STROKE))
// Plus: stout arms, area 8*L*w - 4*w^2.
#define SP_PLUS_HALF_WIDTH 0.24f
#define SP_PLUS_HALF_LENGTH \
  ((SP_SHAPE_AREA + 4.0f * SP_PLUS_HALF_WIDTH * SP_PLUS_HALF_WIDTH) / (8.0f * SP_PLUS_HALF_WIDTH))
#define SP_SQUARE_HALF_SIDE (0.5f * sqrt(SP_SHAPE_AREA))
// Hexagon: area 3*sqrt(3)/2 * R^2, at the top of the band (the disc is at its
// bottom): the closest pair of all, told apart only by the corners.
#define SP_HEXAGON_RADIUS sqrt(2.0f * 1.1f * SP_SHAPE_AREA / (3.0f * 1.7320508f))
#define SP_DISC_RADIUS sqrt(0.9f * SP_SHAPE_AREA_SHARE)
#define SP_DIAMOND_HALF_LONG 0.97f
#define SP_STAR_OUTER 0.97f
// The shapes that reach out to the rim: the triangle's corners, the cross's
// arms and the clover's lobes.
#define SP_RIM_RADIUS 0.98f

SP_INLINE float sp_shape_distance(uint shape, vec2 p) {
  const float area = SP_SHAPE_AREA;
  const float sqrt3 = 1.7320508f;
  switch (shape) {
    case SP_SHAPE_RING:
      return abs(length(p) - SP_RING_MID_RADIUS) - 0.5f * SP_SHAPE_STROKE;
    case SP_SHAPE_DIAMOND: {
      // Area 2*a*b; 1.5:1 along the travel direction, so that no rotation
      // makes it the square.
      float half_long = SP_DIAMOND_HALF_LONG;
      float half_short = area / (2.0f * half_long);
      return sp_edge_distance(abs(p), vec2(half_long, 0.0f), vec2(0.0f, half_short));
    }
    case SP_SHAPE_CROSS: {
      // Slender arms at +-60 degrees from +x, long enough for their corners
      // to reach radius 0.98. Area 8*L*w - 4*w^2/sin(120 degrees): 0.375 of
      // the disc, as much as strokes this thin can cover, within the band.
      float half_width = 0.5f * SP_SHAPE_STROKE;
      vec2 arm = vec2(0.5f, 0.5f * sqrt3);  // 60 degrees from +x
      float half_length = sqrt(SP_RIM_RADIUS * SP_RIM_RADIUS - half_width * half_width);
      return sp_cross_distance(p, arm, half_length, half_width);
    }
    case SP_SHAPE_PLUS: {
      // A Swiss cross. The cross function's arms lie at +-45 degrees; p
      // turned by -45 degrees puts them on the axes.
      const float cos45 = 0.70710678f;
      vec2 turned = cos45 * vec2(p.x + p.y, p.y - p.x);
      return sp_cross_distance(turned, vec2(cos45, cos45), SP_PLUS_HALF_LENGTH, SP_PLUS_HALF_WIDTH);
    }
    case SP_SHAPE_TRIANGLE:
      // Corners just inside the rim, one on +x: it points where the sound went.
      return sp_regular_polygon_distance(p, 3.0f, SP_RIM_RADIUS);
    case SP_SHAPE_SQUARE:
      return sp_box_distance(p, vec2(SP_SQUARE_HALF_SIDE));
    case SP_SHAPE_STAR: {
      // Five points near the rim; area 5*R*r*sin(36 degrees) sets the inner radius.
      float outer = SP_STAR_OUTER;
      float inner = area / (5.0f * outer * sin(SP_PI / 5.0f));
      return sp_star_distance(p, 5.0f, outer, inner);
    }
    case SP_SHAPE_HEXAGON:
      return sp_regular_polygon_distance(p, 6.0f, SP_HEXAGON_RADIUS);
    case SP_SHAPE_CLOVER: {
      // Three separate discs reaching radius 0.98, apart by a third of the
      // radius so the gaps survive at small sizes; one on -x, so that the
      // clover does not point where the triangle does.
      float lobe_radius = sqrt(SP_SHAPE_AREA_SHARE / 3.0f);
      vec2 q = sp_fold_to_wedge(vec2(-p.x, p.y), 3.0f);
      return length(q - vec2(SP_RIM_RADIUS - lobe_radius, 0.0f)) - lobe_radius;
    }
    default:  // SP_SHAPE_DISC, and any unknown id: at the bottom of the band
      return length(p) - SP_DISC_RADIUS;
  }
}

// Radius of the smallest disc around the spot's centre that holds the
// shape. The vertex shader sizes the spot's quad to it: the pass costs its
// area, on a software rasteriser and on GPUs with few fragment units alike,
// and the compact shapes need a little over half the unit disc's square.
SP_INLINE float sp_shape_extent(uint shape) {
  switch (shape) {
    case SP_SHAPE_RING:
      return SP_RING_MID_RADIUS + 0.5f * SP_SHAPE_STROKE;
    case SP_SHAPE_PLUS:
      return sqrt(SP_PLUS_HALF_LENGTH * SP_PLUS_HALF_LENGTH + SP_PLUS_HALF_WIDTH * SP_PLUS_HALF_WIDTH);
    case SP_SHAPE_SQUARE:
      return 1.4142136f * SP_SQUARE_HALF_SIDE;
    case SP_SHAPE_HEXAGON:
      return SP_HEXAGON_RADIUS;
    case SP_SHAPE_DIAMOND:
      return SP_DIAMOND_HALF_LONG;
    case SP_SHAPE_STAR:
      return SP_STAR_OUTER;
    case SP_SHAPE_CROSS:
    case SP_SHAPE_TRIANGLE:
    case SP_SHAPE_CLOVER:
      return SP_RIM_RADIUS;
    default:
      return SP_DISC_RADIUS;
  }
}

SP_END_NAMESPACE

#endif  // SP_SHAPES_H
