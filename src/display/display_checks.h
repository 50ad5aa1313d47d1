// Checks display settings made in code rather than parsed from a config
// (the parser checks its own input, with key paths).
#pragma once

#include "soundpaint/display.h"

namespace sp {

// Throws sp::Exception(InvalidConfig) naming the key ("display.size_scale")
// when a setting is out of its range (docs/accessibility.md, section 4), or
// a category list is longer than kMaxDisplayCategories or names a category
// longer than kMaxCategoryNameBytes. Linear in the lists' lengths.
void check_display_settings(const DisplaySettings& settings);

}  // namespace sp
