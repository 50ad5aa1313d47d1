#include "sp_types.h"
#include "vk/vk_check.h"

#include <string>
#include <string_view>

#include "soundpaint/result.h"

namespace sp::vk {

const char* result_name(VkResult result) {
  switch (result) {
#define SP_VK_RESULT(name) \
  case name:               \
    return #name
    SP_VK_RESULT(VK_SUCCESS);
    SP_VK_RESULT(VK_NOT_READY);
    SP_VK_RESULT(VK_TIMEOUT);
    SP_VK_RESULT(VK_EVENT_SET);
    SP_VK_RESULT(VK_EVENT_RESET);
    SP_VK_RESULT(VK_INCOMPLETE);
    SP_VK_RESULT(VK_ERROR_OUT_OF_HOST_MEMORY);
    SP_VK_RESULT(VK_ERROR_OUT_OF_DEVICE_MEMORY);
    SP_VK_RESULT(VK_ERROR_INITIALIZATION_FAILED);
    SP_VK_RESULT(VK_ERROR_DEVICE_LOST);
    SP_VK_RESULT(VK_ERROR_MEMORY_MAP_FAILED);
    SP_VK_RESULT(VK_ERROR_LAYER_NOT_PRESENT);
    SP_VK_RESULT(VK_ERROR_EXTENSION_NOT_PRESENT);
    SP_VK_RESULT(VK_ERROR_FEATURE_NOT_PRESENT);
    SP_VK_RESULT(VK_ERROR_INCOMPATIBLE_DRIVER);
    SP_VK_RESULT(VK_ERROR_TOO_MANY_OBJECTS);
    SP_VK_RESULT(VK_ERROR_FORMAT_NOT_SUPPORTED);
    SP_VK_RESULT(VK_ERROR_FRAGMENTED_POOL);
    SP_VK_RESULT(VK_ERROR_UNKNOWN);
    SP_VK_RESULT(VK_ERROR_OUT_OF_POOL_MEMORY);
    SP_VK_RESULT(VK_ERROR_INVALID_EXTERNAL_HANDLE);
    SP_VK_RESULT(VK_ERROR_FRAGMENTATION);
    SP_VK_RESULT(VK_ERROR_INVALID_OPAQUE_CAPTURE_ADDRESS);
    SP_VK_RESULT(VK_PIPELINE_COMPILE_REQUIRED);
    SP_VK_RESULT(VK_ERROR_SURFACE_LOST_KHR);
    SP_VK_RESULT(VK_ERROR_NATIVE_WINDOW_IN_USE_KHR);
    SP_VK_RESULT(VK_SUBOPTIMAL_KHR);
    SP_VK_RESULT(VK_ERROR_OUT_OF_DATE_KHR);
    SP_VK_RESULT(VK_ERROR_INCOMPATIBLE_DISPLAY_KHR);
    SP_VK_RESULT(VK_ERROR_VALIDATION_FAILED_EXT);
    SP_VK_RESULT(VK_ERROR_INVALID_SHADER_NV);
    SP_VK_RESULT(VK_ERROR_INVALID_DRM_FORMAT_MODIFIER_PLANE_LAYOUT_EXT);
    SP_VK_RESULT(VK_ERROR_NOT_PERMITTED_KHR);
    SP_VK_RESULT(VK_ERROR_FULL_SCREEN_EXCLUSIVE_MODE_LOST_EXT);
    SP_VK_RESULT(VK_THREAD_IDLE_KHR);
    SP_VK_RESULT(VK_THREAD_DONE_KHR);
    SP_VK_RESULT(VK_OPERATION_DEFERRED_KHR);
    SP_VK_RESULT(VK_OPERATION_NOT_DEFERRED_KHR);
    SP_VK_RESULT(VK_ERROR_COMPRESSION_EXHAUSTED_EXT);
#undef SP_VK_RESULT
    default:
      break;
  }
  return "VK_RESULT_UNKNOWN";
}

void check_result(VkResult result, const char* call, const char* file, int line) {
  // Positive codes (VK_INCOMPLETE, VK_SUBOPTIMAL_KHR, ...) are successes.
  if (result >= 0) return;
  const std::string_view path(file);
  const std::string_view base = path.substr(path.find_last_of("/\\") + 1);  // npos + 1 == 0
  const char* name = result_name(result);
  // Built by append: GCC 12 reports a false -Wrestrict on `"x" + std::string`.
  std::string message(call);
  message.append(" failed: ").append(name);
  if (std::string_view(name) == "VK_RESULT_UNKNOWN") message.append(" ").append(std::to_string(result));
  message.append(" (").append(base).append(":").append(std::to_string(line)).append(")");
  throw Exception(Error{ErrorCode::Vulkan, std::move(message), static_cast<int>(result)});
}

}  // namespace sp::vk
