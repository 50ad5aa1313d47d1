// How a colour looks to a dichromat, and how far apart two colours look:
// the tools that check the palettes stay readable for colour-blind players.
#pragma once

#include <glm/vec3.hpp>

namespace sp {

enum class ColorVision { Normal, Protanopia, Deuteranopia, Tritanopia };

// The colour a dichromat with this deficiency (severity 1) sees, in linear
// RGB, clamped to [0, 1] as a display would show it. Input: linear RGB in
// [0, 1]. Normal returns the input.
glm::vec3 simulate_color_vision(glm::vec3 linear_rgb, ColorVision vision);

// CIE L*a*b*, D65 white. L* in [0, 100].
struct Lab {
  double l = 0.0;
  double a = 0.0;
  double b = 0.0;
};

// Linear sRGB in [0, 1] to CIE L*a*b* (D65); white (1, 1, 1) maps to
// L* = 100, a* = b* = 0 exactly.
Lab lab_from_linear_srgb(glm::vec3 linear_rgb);

// The CIEDE2000 colour difference (kL = kC = kH = 1). Symmetric; 0 for
// equal colours; about 1 is a just-noticeable difference between large
// patches seen side by side.
double ciede2000(const Lab& first, const Lab& second);

}  // namespace sp
