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

// Per source slot of `world`, its SP_SOURCE_CUE_* flags: occluded when the
// straight way from the listener to it is blocked (the player hears it but
// cannot see it, so its arrow shows even in view). One cast a source.
std::vector<std::uint32_t> make_source_cues(const World& world);

}  // namespace sp::draw
