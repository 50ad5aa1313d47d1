// The validation-message sink behind Context's debug messenger (private to
// src/vk and its tests).
#pragma once

#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

namespace sp::vk {

// One Context's messages (Context::Messages derives from this). The debug
// callback may run on any thread that makes a Vulkan call, hence the mutex.
struct MessageLog {
  mutable std::mutex mutex;
  std::uint32_t count = 0;
};

// Create info for a messenger of warning and error severities, all message
// types, that records into `sink` (which must outlive the messenger). Used
// both as VkInstanceCreateInfo::pNext (to catch vkCreateInstance and
// vkDestroyInstance) and for the instance's own messenger.
VkDebugUtilsMessengerCreateInfoEXT debug_messenger_info(MessageLog* sink);

// Every message any Context in this process has received, including those
// reported while a Context is being destroyed: the layer reports leaked
// objects from vkDestroyDevice/vkDestroyInstance, when the Context itself can
// no longer be asked. Tests compare the count before and after teardown.
std::uint32_t process_validation_message_count();
// Texts of messages number `first` onwards (at most the first few thousand of
// the process are kept).
std::vector<std::string> process_validation_messages(std::size_t first = 0);

}  // namespace sp::vk
