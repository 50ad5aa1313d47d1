#include "view/screenshot.h"

#include <cstdint>
#include <utility>

#include "draw/image_barrier.h"
#include "render/png_writer.h"
#include "vk/barriers.h"

namespace sp::view {

void Screenshot::record(const vk::Context& context, VkCommandBuffer cmd, VkImage color, VkExtent2D extent) {
  extent_ = extent;
  const VkDeviceSize bytes = VkDeviceSize{extent.width} * extent.height * 4;
  buffer_ =
      vk::Buffer(context, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUsage::Readback, "viewer screenshot");
  // RAW: the passes' colour writes land before the copy reads the image.
  draw::image_barrier(cmd, color, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                      VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                      VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                      VK_ACCESS_2_TRANSFER_READ_BIT);
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {extent.width, extent.height, 1};
  vkCmdCopyImageToBuffer(cmd, color, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer_.get(), 1, &region);
  // Device -> host: the copy is visible to host reads after the fence.
  vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                     VK_ACCESS_2_HOST_READ_BIT);
  draw::image_barrier(cmd, color, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                      VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_PIPELINE_STAGE_2_COPY_BIT, 0, VK_PIPELINE_STAGE_2_NONE, 0);
}

void Screenshot::write(const std::filesystem::path& path, VkFormat format) const {
  draw::RgbaImage picture;
  picture.width = extent_.width;
  picture.height = extent_.height;
  const auto* bytes = static_cast<const std::uint8_t*>(buffer_.mapped());
  picture.pixels.assign(bytes, bytes + std::size_t{picture.width} * picture.height * 4);
  if (format == VK_FORMAT_B8G8R8A8_SRGB || format == VK_FORMAT_B8G8R8A8_UNORM) {
    for (std::size_t i = 0; i < picture.pixels.size(); i += 4) std::swap(picture.pixels[i], picture.pixels[i + 2]);
  }
  draw::write_png(path, picture);
}

}  // namespace sp::view
