// What the display needs of each source, kept in the World beside the source:
// its category's index (display/categories.h numbering: built-ins first, then
// first appearance) and its colour: its own when it sets one, else its
// category's colour in the config's palette (docs/model.md#indicators).
#pragma once

#include <cstdint>

#include "soundpaint/simulation.h"

namespace sp {

// Fills World::category_names with the built-in categories; then resolves
// every source. Called by make_world.
void resolve_all_source_display(World& world);

// (Re)resolves source `id` after it was added or replaced, growing the
// per-source vectors as needed and numbering a new category.
void resolve_source_display(World& world, std::uint32_t id);

}  // namespace sp
