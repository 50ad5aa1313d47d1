// VK_CHECK that also checks in release builds: a failed call becomes an
// sp::Exception(ErrorCode::Vulkan) naming the call, the VkResult and where.
#pragma once

#include <vulkan/vulkan.h>

#include "sp_types.h"

namespace sp::vk {

const char* result_name(VkResult result);

// Throws sp::Exception{ErrorCode::Vulkan, "<call> failed: VK_ERROR_... (file:line)", vk_result}.
void check_result(VkResult result, const char* call, const char* file, int line);

}  // namespace sp::vk

#define SP_VK_CHECK(call) ::sp::vk::check_result((call), #call, __FILE__, __LINE__)
