// The window's swapchain and, per image, the depth image the scene pass
// writes and the indicator pass reads, and the semaphore that says the
// image's commands are done (presentation waits on it). Recreated whole
// when the window's size changes or presentation reports it out of date.
#pragma once

#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

#include "render/render_target.h"
#include "vk/context.h"
#include "vk/handle.h"

namespace sp::view {

using UniqueSwapchain = vk::DeviceObject<VkSwapchainKHR, vkDestroySwapchainKHR>;
using UniqueSemaphore = vk::DeviceObject<VkSemaphore, vkDestroySemaphore>;

class Swapchain {
 public:
  static constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

  // Picks an 8-bit sRGB format (the scene pass writes linear colour) and
  // FIFO presentation (every driver has it; no tearing). Throws
  // sp::Exception(ErrorCode::Vulkan).
  Swapchain(const vk::Context& context, VkSurfaceKHR surface, VkExtent2D wanted);
  // Recreates for the new size; the caller has waited for the device.
  void recreate(VkExtent2D wanted);

  VkSwapchainKHR handle() const { return swapchain_.get(); }
  VkFormat format() const { return format_; }
  VkExtent2D extent() const { return extent_; }
  std::uint32_t image_count() const { return static_cast<std::uint32_t>(images_.size()); }
  VkImage image(std::uint32_t i) const { return images_[i]; }
  const std::vector<VkImageView>& views() const { return raw_views_; }
  VkImage depth_image(std::uint32_t i) const { return depths_[i].image(); }
  VkImageView depth_view(std::uint32_t i) const { return depths_[i].view(); }
  std::vector<VkImageView> depth_views() const;
  VkSemaphore rendered(std::uint32_t i) const { return rendered_[i].get(); }
  // Whether images can be copied out (for --screenshot).
  bool readable() const { return readable_; }

 private:
  void create(VkExtent2D wanted, VkSwapchainKHR old);

  const vk::Context& context_;
  VkSurfaceKHR surface_;
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  VkColorSpaceKHR color_space_ = VK_COLOR_SPACE_SRGB_NONLINEAR_KHR;
  VkExtent2D extent_{};
  bool readable_ = false;
  UniqueSwapchain swapchain_;
  std::vector<VkImage> images_;
  std::vector<vk::UniqueImageView> views_;
  std::vector<VkImageView> raw_views_;
  std::vector<draw::DeviceImage> depths_;
  std::vector<UniqueSemaphore> rendered_;
};

}  // namespace sp::view
