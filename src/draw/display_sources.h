// The draw's table of sources (shaders/shared/sp_draw_types.h
// DisplaySource): per source id, where it is, its category, colour and
// shape, and whether the display settings hide it.
#pragma once

#include <cstdint>
#include <vector>

#include "soundpaint/display.h"
#include "soundpaint/simulation.h"
#include "sp_draw_types.h"

namespace sp::draw {

// One entry per source slot of `world` (removed ones marked absent).
std::vector<shader::DisplaySource> make_display_sources(const World& world, const DisplaySettings& settings);

}  // namespace sp::draw
