// The colours of the display palettes (include/soundpaint/display.h), in
// linear RGB: the renderer works in linear light and encodes sRGB on output,
// and the `color` a config gives a source is linear RGB too. The choice of
// each colour, and how far apart they stay under colour-vision deficiencies,
// is in docs/accessibility.md ("Colour"); tests/test_palette.cpp checks it.
#pragma once

#include <glm/vec3.hpp>
#include <span>

#include "soundpaint/display.h"

namespace sp {

// The palette's colours, linear RGB in [0, 1]. Entry i of every palette
// belongs to the same built-in category (builtin_categories()[i] for
// i < kBuiltinCategoryCount); the entries after those are for other
// categories. Every palette has more entries than there are built-ins.
// The span points into storage that lives as long as the program;
// thread-safe.
std::span<const glm::vec3> palette_colors(Palette palette);

// The sRGB transfer function (IEC 61966-2-1), per channel; inputs in [0, 1].
glm::vec3 srgb_to_linear(glm::vec3 srgb);
glm::vec3 linear_to_srgb(glm::vec3 linear);

}  // namespace sp
