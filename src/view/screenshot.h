// The viewer's --screenshot: the last frame's swapchain image copied into a
// host-visible buffer by that frame's own command buffer, and written as a
// PNG once the frame's fence has passed.
#pragma once

#include <filesystem>

#include "vk/buffer.h"
#include "vk/context.h"

namespace sp::view {

class Screenshot {
 public:
  // Records the copy of `color` (COLOR_ATTACHMENT_OPTIMAL, the frame's
  // passes recorded before) and leaves the image PRESENT_SRC.
  void record(const vk::Context& context, VkCommandBuffer cmd, VkImage color, VkExtent2D extent);

  // After the fence of the frame record() went into: writes the copy to
  // `path` (draw::write_png), its channels reordered from the swapchain's
  // `format`. Throws sp::Exception(Io) naming the path.
  void write(const std::filesystem::path& path, VkFormat format) const;

 private:
  vk::Buffer buffer_;
  VkExtent2D extent_{};
};

}  // namespace sp::view
