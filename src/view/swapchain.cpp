#include "sp_types.h"
#include "view/swapchain.h"

#include <algorithm>

#include "soundpaint/result.h"
#include "vk/objects.h"
#include "vk/vk_check.h"

namespace sp::view {

Swapchain::Swapchain(const vk::Context& context, VkSurfaceKHR surface, VkExtent2D wanted)
    : context_(context), surface_(surface) {
  const VkPhysicalDevice physical = context.physical_device();
  VkBool32 presents = VK_FALSE;
  SP_VK_CHECK(vkGetPhysicalDeviceSurfaceSupportKHR(physical, context.queue_family(), surface, &presents));
  if (presents != VK_TRUE)
    throw Exception(ErrorCode::Vulkan, std::string(context.properties().deviceName) +
                                           " cannot present to this window from its compute+graphics queue");
  std::uint32_t count = 0;
  SP_VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(physical, surface, &count, nullptr));
  std::vector<VkSurfaceFormatKHR> formats(count);
  SP_VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(physical, surface, &count, formats.data()));
  if (formats.empty()) throw Exception(ErrorCode::Vulkan, "the window's surface offers no format");
  auto srgb = std::find_if(formats.begin(), formats.end(), [](const VkSurfaceFormatKHR& f) {
    return (f.format == VK_FORMAT_B8G8R8A8_SRGB || f.format == VK_FORMAT_R8G8B8A8_SRGB) &&
           f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR;
  });
  const VkSurfaceFormatKHR chosen = srgb != formats.end() ? *srgb : formats.front();
  format_ = chosen.format;
  color_space_ = chosen.colorSpace;
  create(wanted, VK_NULL_HANDLE);
}

void Swapchain::recreate(VkExtent2D wanted) {
  // The old swapchain is handed to the new one, then destroyed with it.
  UniqueSwapchain old = std::move(swapchain_);
  rendered_.clear();
  depths_.clear();
  raw_views_.clear();
  views_.clear();
  images_.clear();
  create(wanted, old.get());
}

std::vector<VkImageView> Swapchain::depth_views() const {
  std::vector<VkImageView> views;
  for (const draw::DeviceImage& depth : depths_) views.push_back(depth.view());
  return views;
}

void Swapchain::create(VkExtent2D wanted, VkSwapchainKHR old) {
  const VkDevice device = context_.device();
  VkSurfaceCapabilitiesKHR caps{};
  SP_VK_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(context_.physical_device(), surface_, &caps));
  // A current extent of 0xFFFFFFFF means the window takes the swapchain's.
  extent_ = caps.currentExtent.width != 0xFFFFFFFFu
                ? caps.currentExtent
                : VkExtent2D{std::clamp(wanted.width, caps.minImageExtent.width, caps.maxImageExtent.width),
                             std::clamp(wanted.height, caps.minImageExtent.height, caps.maxImageExtent.height)};
  std::uint32_t count = std::max(caps.minImageCount + 1, 3u);
  if (caps.maxImageCount > 0) count = std::min(count, caps.maxImageCount);
  // At most 8: the visualizer clips against at most 8 registered depth views.
  count = std::min(count, 8u);
  readable_ = (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT) != 0;

  VkSwapchainCreateInfoKHR info{};
  info.sType = VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR;
  info.surface = surface_;
  info.minImageCount = count;
  info.imageFormat = format_;
  info.imageColorSpace = color_space_;
  info.imageExtent = extent_;
  info.imageArrayLayers = 1;
  info.imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
  if (readable_) info.imageUsage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.preTransform = caps.currentTransform;
  info.compositeAlpha =
      (caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR) != 0
          ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
          : static_cast<VkCompositeAlphaFlagBitsKHR>(caps.supportedCompositeAlpha & -caps.supportedCompositeAlpha);
  info.presentMode = VK_PRESENT_MODE_FIFO_KHR;
  info.clipped = VK_TRUE;
  info.oldSwapchain = old;
  swapchain_ = vk::create_object<UniqueSwapchain>(context_, vkCreateSwapchainKHR, info, VK_OBJECT_TYPE_SWAPCHAIN_KHR,
                                                  "viewer swapchain");
  const VkSwapchainKHR raw = swapchain_.get();

  std::uint32_t image_count = 0;
  SP_VK_CHECK(vkGetSwapchainImagesKHR(device, raw, &image_count, nullptr));
  images_.resize(image_count);
  SP_VK_CHECK(vkGetSwapchainImagesKHR(device, raw, &image_count, images_.data()));
  if (image_count > 8) throw Exception(ErrorCode::Vulkan, "the swapchain made more than 8 images");
  for (std::uint32_t i = 0; i < image_count; ++i) {
    VkImageViewCreateInfo view_info{};
    view_info.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
    view_info.image = images_[i];
    view_info.viewType = VK_IMAGE_VIEW_TYPE_2D;
    view_info.format = format_;
    view_info.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    views_.push_back(vk::create_object<vk::UniqueImageView>(context_, vkCreateImageView, view_info,
                                                            VK_OBJECT_TYPE_IMAGE_VIEW, "viewer swapchain view"));
    raw_views_.push_back(views_.back().get());
    depths_.emplace_back(context_, extent_.width, extent_.height, kDepthFormat,
                         VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                         VK_IMAGE_ASPECT_DEPTH_BIT, "viewer depth");  // sampled: spots clip to surfaces
    VkSemaphoreCreateInfo semaphore_info{};
    semaphore_info.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO;
    rendered_.push_back(vk::create_object<UniqueSemaphore>(context_, vkCreateSemaphore, semaphore_info,
                                                           VK_OBJECT_TYPE_SEMAPHORE, "viewer image rendered"));
  }
}

}  // namespace sp::view
