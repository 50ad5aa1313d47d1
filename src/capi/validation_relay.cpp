#include "capi/validation_relay.h"

#include <string>
#include <vector>

#include "capi/context.h"
#include "vk/debug_messenger.h"

namespace sp::capi {

ValidationRelay::ValidationRelay(const sp_context* context) noexcept {
  if (context == nullptr || (context->flags & SP_CONTEXT_VULKAN_VALIDATION) == 0 || context->log == nullptr) return;
  context_ = context;
  first_ = sp::vk::process_validation_message_count();
}

ValidationRelay::~ValidationRelay() {
  if (context_ == nullptr) return;
  try {
    for (const std::string& message : sp::vk::process_validation_messages(first_))
      log(*context_, SP_LOG_WARNING, message.c_str());
  } catch (...) {
    // Out of memory copying the messages: the log misses them, the call stands.
  }
}

}  // namespace sp::capi
