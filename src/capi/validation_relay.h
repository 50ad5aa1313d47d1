// The Vulkan validation layer's messages, relayed to a context's log
// (SP_CONTEXT_VULKAN_VALIDATION): the layer reports to a process-wide sink
// (src/vk/debug_messenger.h); a relay notes how many messages it held when
// a call began and, when the call ends, logs the ones that came since.
#pragma once

#include <cstddef>

#include "soundpaint/soundpaint.h"

namespace sp::capi {

class ValidationRelay {
 public:
  // Relays nothing unless `context` asks for validation.
  explicit ValidationRelay(const sp_context* context) noexcept;
  // Logs the messages since construction as SP_LOG_WARNING. Never throws.
  ~ValidationRelay();
  ValidationRelay(const ValidationRelay&) = delete;
  ValidationRelay& operator=(const ValidationRelay&) = delete;

 private:
  const sp_context* context_ = nullptr;  // null: relays nothing
  std::size_t first_ = 0;
};

}  // namespace sp::capi
