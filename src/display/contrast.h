// Luminance contrast (WCAG 2.x) and the halo that keeps every spot legible
// on any surface.
//
// The halo is two rings round each spot: kHaloDark inside, against the spot,
// and kHaloLight outside it. Whatever the surface's relative luminance Y in
// [0, 1], one of them has contrast >= 3:1 with it (the WCAG 2.x minimum for
// graphical objects), shown thus. The light ring's contrast (Yl + 0.05) /
// (Y + 0.05) falls as Y rises and the dark ring's (Y + 0.05) / (Yd + 0.05)
// rises, so the better of the two is least where they are equal:
//   (Y + 0.05)^2 = (Yl + 0.05)(Yd + 0.05),
// and there each is sqrt((Yl + 0.05) / (Yd + 0.05)): the square root of the
// rings' contrast with each other. The guarantee of 3:1 needs the rings 9:1
// apart; black and white are 21:1, so the worst surface (Y = 0.179, a mid
// grey) still sees 4.58:1. Every palette colour has Y >= 0.1, 3:1 against
// the dark ring (src/display/palette.cpp), so the spot's own edge shows too.
// These hold where the halo is opaque; drawn translucent it blends toward the
// surface and its contrast falls.
#pragma once

#include <glm/vec3.hpp>

#include "sp_draw_types.h"

namespace sp {

// Linear RGB, the colours the indicator shader draws (sp_draw_types.h).
inline constexpr glm::vec3 kHaloDark(SP_HALO_DARK_RGB);
inline constexpr glm::vec3 kHaloLight(SP_HALO_LIGHT_RGB);

// WCAG 2.x relative luminance of a linear RGB colour (Rec. 709 weights), in [0, 1].
float relative_luminance(glm::vec3 linear_rgb);

// WCAG 2.x contrast ratio of two relative luminances, in [1, 21]; order-free.
float contrast_ratio(float luminance_a, float luminance_b);

// The least contrast, over every surface luminance in [0, 1], that the
// better of the two halo rings has with the surface (see above).
float halo_worst_case_contrast();

}  // namespace sp
