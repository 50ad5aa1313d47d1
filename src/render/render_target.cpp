#include "render/render_target.h"

#include <cstring>
#include <string>

#include "draw/image_barrier.h"
#include "draw/rendering.h"
#include "soundpaint/result.h"
#include "sp_types.h"
#include "vk/barriers.h"
#include "vk/buffer.h"
#include "vk/objects.h"
#include "vk/vk_check.h"

namespace sp::draw {
DeviceImage::DeviceImage(const vk::Context& context, std::uint32_t width, std::uint32_t height, VkFormat format,
                         VkImageUsageFlags usage, VkImageAspectFlags aspect, const char* name) {
  const VkDevice device = context.device();
  VkImageCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = format;
  info.extent = {width, height, 1};
  info.mipLevels = 1;
  info.arrayLayers = 1;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  image_ = vk::create_object<vk::UniqueImage>(context, vkCreateImage, info, VK_OBJECT_TYPE_IMAGE, name);
  const VkImage raw_image = image_.get();

  VkMemoryRequirements requirements{};
  vkGetImageMemoryRequirements(device, raw_image, &requirements);
  memory_ = vk::allocate_memory(context, requirements, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0, name);
  const VkDeviceMemory raw_memory = memory_.get();
  SP_VK_CHECK(vkBindImageMemory(device, raw_image, raw_memory, 0));

  // Views are for attachments; transfers address the image itself.
  if ((usage & (VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT)) == 0) return;
  VkImageViewCreateInfo view_info{};
  view_info.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
  view_info.image = raw_image;
  view_info.viewType = VK_IMAGE_VIEW_TYPE_2D;
  view_info.format = format;
  view_info.subresourceRange = {aspect, 0, 1, 0, 1};
  view_ = vk::create_object<vk::UniqueImageView>(context, vkCreateImageView, view_info, VK_OBJECT_TYPE_IMAGE_VIEW,
                                                 (std::string(name) + " view").c_str());
}

RenderTarget::RenderTarget(const vk::Context& context, std::uint32_t width, std::uint32_t height)
    : width_(width), height_(height) {
  const std::uint32_t max_dimension = context.properties().limits.maxImageDimension2D;
  if (width == 0 || height == 0 || width > max_dimension || height > max_dimension) {
    throw Exception(ErrorCode::LimitExceeded, "image size " + std::to_string(width) + "x" + std::to_string(height) +
                                                  " is outside 1.." + std::to_string(max_dimension) +
                                                  " (the device's maxImageDimension2D)");
  }
  color_ = DeviceImage(context, width, height, kColorFormat,
                       VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, VK_IMAGE_ASPECT_COLOR_BIT,
                       "render colour");
  // Blits between these formats (BLIT_SRC of RGBA16F, BLIT_DST of RGBA8
  // sRGB) are features every Vulkan device must support.
  output_ = DeviceImage(context, width, height, kOutputFormat,
                        VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, VK_IMAGE_ASPECT_COLOR_BIT,
                        "render output");
  depth_ = DeviceImage(context, width, height, kDepthFormat,
                       VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                       VK_IMAGE_ASPECT_DEPTH_BIT, "render depth");
  readback_ = vk::Buffer(context, VkDeviceSize{width} * height * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                         vk::MemoryUsage::Readback, "render readback");
}

void RenderTarget::begin(VkCommandBuffer cmd, const float (&clear)[4]) const {
  // WAR: the previous frame's blit out of the colour image (an earlier
  // submission) finishes before this frame's clear overwrites it.
  image_barrier(cmd, color_.image(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_NONE,
                VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
  // WAW: the previous frame's depth tests finish before this frame's clear.
  const VkPipelineStageFlags2 depth_stages =
      VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
  image_barrier(cmd, depth_.image(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, depth_stages, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                depth_stages,
                VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);

  VkRenderingAttachmentInfo color = attachment({color_.view(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                                                VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE});
  std::memcpy(color.clearValue.color.float32, clear, sizeof clear);
  // Depth is kept for the overlays (begin_overlays), which test against it.
  VkRenderingAttachmentInfo depth = attachment({depth_.view(), VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                                                VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE});
  depth.clearValue.depthStencil = {1.0f, 0};
  begin_rendering(cmd, {width_, height_}, color, depth);

  const VkViewport viewport{0.0f, 0.0f, static_cast<float>(width_), static_cast<float>(height_), 0.0f, 1.0f};
  const VkRect2D scissor{{0, 0}, {width_, height_}};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &scissor);
}

void RenderTarget::end_and_copy(VkCommandBuffer cmd) const {
  vkCmdEndRendering(cmd);
  // RAW: the frame's colour writes land before the blit reads the image.
  image_barrier(cmd, color_.image(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
  // WAR: the previous frame's copy out of the output image finishes before
  // the blit overwrites it (its old contents are discarded).
  image_barrier(cmd, output_.image(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE,
                VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  // Same size, so the blit only converts: half float to 8-bit sRGB.
  VkImageBlit2 region{};
  region.sType = VK_STRUCTURE_TYPE_IMAGE_BLIT_2;
  region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.srcOffsets[1] = {static_cast<std::int32_t>(width_), static_cast<std::int32_t>(height_), 1};
  region.dstSubresource = region.srcSubresource;
  region.dstOffsets[1] = region.srcOffsets[1];
  VkBlitImageInfo2 blit{};
  blit.sType = VK_STRUCTURE_TYPE_BLIT_IMAGE_INFO_2;
  blit.srcImage = color_.image();
  blit.srcImageLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  blit.dstImage = output_.image();
  blit.dstImageLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  blit.regionCount = 1;
  blit.pRegions = &region;
  blit.filter = VK_FILTER_NEAREST;
  vkCmdBlitImage2(cmd, &blit);
  // RAW: the converted pixels land before the copy reads them.
  image_barrier(cmd, output_.image(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
  VkBufferImageCopy copy{};
  copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  copy.imageExtent = {width_, height_, 1};
  vkCmdCopyImageToBuffer(cmd, output_.image(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback_.get(), 1, &copy);
  // RAW (device -> host): the copied pixels become visible to read() after
  // the fence; the fence alone would not make them visible.
  vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                     VK_ACCESS_2_HOST_READ_BIT);
}

void RenderTarget::begin_overlays(VkCommandBuffer cmd) const {
  vkCmdEndRendering(cmd);
  // RAW: the scene's depth writes land before the overlays test and sample
  // it (the indicators' vertex stage samples each spot's centre).
  const VkPipelineStageFlags2 depth_stages =
      VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
  image_barrier(cmd, depth_.image(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL, depth_stages, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                depth_stages | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  begin_rendering(cmd, {width_, height_},
                  attachment({color_.view(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_ATTACHMENT_LOAD_OP_LOAD,
                              VK_ATTACHMENT_STORE_OP_STORE}),
                  attachment({depth_.view(), VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL, VK_ATTACHMENT_LOAD_OP_LOAD,
                              VK_ATTACHMENT_STORE_OP_NONE}));
}

RgbaImage RenderTarget::read() const {
  RgbaImage image;
  image.width = width_;
  image.height = height_;
  image.pixels.resize(std::size_t{width_} * height_ * 4);
  std::memcpy(image.pixels.data(), readback_.mapped(), image.pixels.size());
  return image;
}

}  // namespace sp::draw
