// The offscreen target one frame is drawn into: a half-float colour image
// and a D32 depth image; at the end the colour is converted into an 8-bit
// sRGB image and copied into a host-readable buffer.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

#include "vk/buffer.h"
#include "vk/context.h"
#include "vk/handle.h"

namespace sp::draw {

// Tightly packed 8-bit RGBA pixels, rows top to bottom, sRGB-encoded.
struct RgbaImage {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<std::uint8_t> pixels;  // width * height * 4

  const std::uint8_t* at(std::uint32_t x, std::uint32_t y) const {
    return pixels.data() + (std::size_t{y} * width + x) * 4;
  }
};

// One 2D image with its own memory and, when it is an attachment, a view of
// its single mip level.
class DeviceImage {
 public:
  DeviceImage() = default;
  DeviceImage(const vk::Context& context, std::uint32_t width, std::uint32_t height, VkFormat format,
              VkImageUsageFlags usage, VkImageAspectFlags aspect, const char* name);

  VkImage image() const { return image_.get(); }
  VkImageView view() const { return view_.get(); }  // null unless an attachment

 private:
  // Declaration order is destruction order reversed: view, image, memory.
  vk::UniqueMemory memory_;
  vk::UniqueImage image_;
  vk::UniqueImageView view_;
};

class RenderTarget {
 public:
  // Drawn in linear half float: thousands of faint, overlapping indicators
  // blend without 8-bit rounding at every layer, which would make the
  // picture depend on their order (the GPU ring's order is not fixed).
  static constexpr VkFormat kColorFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
  // What is read back: sRGB-encoded bytes, as a PNG viewer expects.
  static constexpr VkFormat kOutputFormat = VK_FORMAT_R8G8B8A8_SRGB;
  static constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

  // width, height in [1, maxImageDimension2D]; throws sp::Exception
  // (LimitExceeded naming the limit, Vulkan on failure).
  RenderTarget(const vk::Context& context, std::uint32_t width, std::uint32_t height);

  std::uint32_t width() const { return width_; }
  std::uint32_t height() const { return height_; }

  // Transitions both images for drawing (their old contents are discarded)
  // and begins dynamic rendering with them cleared to `clear` and depth 1.
  void begin(VkCommandBuffer cmd, const float (&clear)[4]) const;
  // Ends the scene's rendering and begins the overlays': colour kept, depth
  // kept and read-only (VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL), so that
  // the indicator pass can both test against it and sample depth_view().
  void begin_overlays(VkCommandBuffer cmd) const;
  // The depth image's view, for sampling while the overlays are drawn.
  VkImageView depth_view() const { return depth_.view(); }
  // Ends rendering, converts the colour image to kOutputFormat and copies it
  // into the readback buffer, visible to the host once the submission's
  // fence has signalled.
  void end_and_copy(VkCommandBuffer cmd) const;
  // The pixels of the last completed copy.
  RgbaImage read() const;

 private:
  std::uint32_t width_ = 0;
  std::uint32_t height_ = 0;
  DeviceImage color_;
  DeviceImage output_;  // kOutputFormat; only a blit destination and copy source
  DeviceImage depth_;
  vk::Buffer readback_;
};

}  // namespace sp::draw
