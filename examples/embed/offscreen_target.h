// The host's render target: a colour and a depth image that each frame
// clears and renders into with dynamic rendering, and a host-visible buffer
// the last frame copies the colour into, since there is no window.
#pragma once

#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

#include "host_vulkan.h"
#include "vulkan_objects.h"

class OffscreenTarget {
 public:
  static constexpr VkFormat kColorFormat = VK_FORMAT_R8G8B8A8_UNORM;
  static constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

  OffscreenTarget(const HostContext& host, std::uint32_t width, std::uint32_t height);

  std::uint32_t width() const { return width_; }
  std::uint32_t height() const { return height_; }

  // Begins rendering (colour cleared dark, depth to 1) with a full-image
  // viewport and scissor set.
  void begin(VkCommandBuffer cmd) const;
  // Ends the scene's rendering and begins the overlays': colour kept, depth
  // read-only, so that an overlay can both depth-test against the scene and
  // sample depth_view() (soundpaint clips its spots to surfaces that way).
  void begin_overlays(VkCommandBuffer cmd) const;
  VkImageView depth_view() const { return depth_.view.get(); }
  void end(VkCommandBuffer cmd) const;
  // After end(): copies the colour image to the readback buffer.
  void record_readback(VkCommandBuffer cmd) const;
  // RGBA, 8 bits a channel, rows top to bottom; valid once the command
  // buffer holding record_readback has finished.
  std::vector<std::uint8_t> pixels() const;

 private:
  struct Attachment {
    Image image;
    Memory memory;
    ImageView view;
  };
  Attachment make_attachment(VkFormat format, VkImageUsageFlags usage, VkImageAspectFlags aspect) const;

  const HostContext& host_;
  std::uint32_t width_;
  std::uint32_t height_;
  Attachment color_;
  Attachment depth_;
  Buffer readback_;
  Memory readback_memory_;
};
