#include "embed/viewport_check.h"

#include <cstdint>

#include "draw/display_frame.h"

namespace sp::embed {

std::optional<FieldProblem> viewport_problem(const DrawOptions& options) {
  const std::uint32_t limit = draw::kMaxViewportPixels;
  const std::string at_most = "must be at most " + std::to_string(limit);
  if (const VkRect2D* area = options.area) {
    if (area->offset.x < 0 || area->offset.y < 0) return FieldProblem{"area", "offset must not be negative"};
    if (std::uint32_t(area->offset.x) > limit || std::uint32_t(area->offset.y) > limit || area->extent.width > limit ||
        area->extent.height > limit)
      return FieldProblem{"area", "offset and extent " + at_most + " pixels a side"};
  }
  if (options.viewport_width > limit || options.viewport_height > limit)
    return FieldProblem{"viewport_width", "and viewport_height " + at_most + " pixels a side"};
  if (options.viewport_x > limit || options.viewport_y > limit)
    return FieldProblem{"viewport_x", "and viewport_y " + at_most};
  if (options.area != nullptr && (options.viewport_x != 0 || options.viewport_y != 0) &&
      (options.viewport_x != std::uint32_t(options.area->offset.x) ||
       options.viewport_y != std::uint32_t(options.area->offset.y)))
    return FieldProblem{"viewport_x", "and viewport_y must be 0 or the area's offset"};
  return std::nullopt;
}

}  // namespace sp::embed
