#include "vk/debug_messenger.h"

#include <cstdio>

namespace sp::vk {
namespace {

// A misbehaving program can report a message per call; keep the texts
// bounded, but count them all.
constexpr std::size_t kMaxStoredMessages = 4096;

struct ProcessLog {
  std::mutex mutex;
  std::uint32_t count = 0;
  std::vector<std::string> texts;
};

ProcessLog& process_log() {
  static ProcessLog log;  // built on first use, whatever the static initialisation order
  return log;
}

const char* severity_name(VkDebugUtilsMessageSeverityFlagBitsEXT severity) {
  return (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) != 0 ? "error" : "warning";
}

VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                          VkDebugUtilsMessageTypeFlagsEXT /*types*/,
                                          const VkDebugUtilsMessengerCallbackDataEXT* data, void* user_data) {
  std::string text = std::string(severity_name(severity)) + ": ";
  if (data != nullptr && data->pMessageIdName != nullptr) text += std::string("[") + data->pMessageIdName + "] ";
  text += (data != nullptr && data->pMessage != nullptr) ? data->pMessage : "(no message)";

  // Validation is a debug mode: say what went wrong where it is seen, since
  // messages reported during teardown cannot be asked for afterwards.
  std::fprintf(stderr, "soundpaint: Vulkan validation %s\n", text.c_str());

  {
    ProcessLog& log = process_log();
    const std::lock_guard lock(log.mutex);
    ++log.count;
    if (log.texts.size() < kMaxStoredMessages) log.texts.push_back(text);
  }
  if (auto* sink = static_cast<MessageLog*>(user_data)) {
    const std::lock_guard lock(sink->mutex);
    ++sink->count;
  }
  return VK_FALSE;  // never abort the call that triggered the message
}

}  // namespace

VkDebugUtilsMessengerCreateInfoEXT debug_messenger_info(MessageLog* sink) {
  VkDebugUtilsMessengerCreateInfoEXT info{};
  info.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT;
  info.messageSeverity =
      VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  info.pfnUserCallback = on_message;
  info.pUserData = sink;
  return info;
}

std::uint32_t process_validation_message_count() {
  ProcessLog& log = process_log();
  const std::lock_guard lock(log.mutex);
  return log.count;
}

std::vector<std::string> process_validation_messages(std::size_t first) {
  ProcessLog& log = process_log();
  const std::lock_guard lock(log.mutex);
  if (first >= log.texts.size()) return {};
  return {log.texts.begin() + static_cast<std::ptrdiff_t>(first), log.texts.end()};
}

}  // namespace sp::vk
