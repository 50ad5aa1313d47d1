// The C API's display structs (sp_display_settings in soundpaint.h,
// sp_draw_options in soundpaint_vulkan.h) checked and turned into their C++
// counterparts. Every field is checked here, not left to the C++ checks, so
// that a message names the C field and NULL arrays never reach a read.
#pragma once

#include "soundpaint/display.h"
#include "soundpaint/soundpaint_vulkan.h"
#include "soundpaint/visualizer.h"

namespace sp::capi {

// Throws InvalidArgument "<function>: settings-><field> ..." for the first
// bad field. Copies every string.
DisplaySettings display_settings_from(const sp_display_settings& in, const char* function);

// Throws InvalidArgument "<function>: options-><field> ..." for the first bad
// field. Whether scene_depth names a registered view is the visualizer's
// check. A 0 x 0 viewport with an area becomes the area's extent.
DrawOptions draw_options_from(const sp_draw_options& in, const char* function);

}  // namespace sp::capi
