#include "render/host_indicators.h"

#include <algorithm>
#include <cstring>

#include "sp_draw_types.h"

namespace sp::draw {
namespace {

// Starting ring size; growth doubles, so a growing run reallocates rarely.
constexpr std::uint32_t kInitialCapacity = 1024;

}  // namespace

HostIndicators::HostIndicators(vk::Context& context)
    : context_(context),
      args_(context, sizeof(VkDrawIndirectCommand),
            VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::HostVisible,
            "host indicator draw args") {
  upload({});
}

void HostIndicators::upload(std::span<const shader::Indicator> indicators) {
  const auto count = static_cast<std::uint32_t>(indicators.size());
  if (count > capacity_ || !ring_) {
    std::uint32_t capacity = std::max(capacity_, kInitialCapacity);
    while (capacity < count) capacity = capacity > 0x7FFFFFFFu ? count : capacity * 2;
    ring_ = vk::Buffer(context_, VkDeviceSize{capacity} * sizeof(shader::Indicator), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                       vk::MemoryUsage::HostVisible, "host indicator ring");
    capacity_ = capacity;
  }
  if (count > 0) std::memcpy(ring_.mapped(), indicators.data(), indicators.size_bytes());
  VkDrawIndirectCommand command{};
  command.vertexCount = SP_INDICATOR_QUAD_VERTICES;
  command.instanceCount = count;
  std::memcpy(args_.mapped(), &command, sizeof command);
}

gpu::IndicatorView HostIndicators::view() {
  gpu::IndicatorView view;
  view.context = &context_;
  view.ring = ring_.get();
  view.ring_capacity = capacity_;
  view.draw_args = args_.get();
  view.draw_args_offset = 0;
  return view;
}

}  // namespace sp::draw
