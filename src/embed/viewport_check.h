// The viewport checks of a draw's options, shared by the C++ API
// (VisualizerBase::record_draw) and the C API (sp_draw_options), each of
// which names the field its own way.
#pragma once

#include <optional>
#include <string>

#include "soundpaint/visualizer.h"

namespace sp::embed {

// What is wrong with a field of DrawOptions: the field's name and the rest
// of the sentence ("viewport_x" "and viewport_y must be ...").
struct FieldProblem {
  std::string field;
  std::string what;
};

// The first problem with the viewport's size, origin and area as the
// indicator pass carries them (16 bits each, draw::kMaxViewportPixels): a
// negative or too large area, a size or origin past the limit, an origin
// unlike the area's offset. The size pair's own rules (both 0 or both set,
// the area's extent) are checked by each API before this.
std::optional<FieldProblem> viewport_problem(const DrawOptions& options);

}  // namespace sp::embed
