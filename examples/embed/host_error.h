// How the example reports failure: one exception type carrying one line,
// printed by main() as "soundpaint_embed_example: <line>" with status 1.
#pragma once

#include <stdexcept>
#include <string>

#include <vulkan/vulkan.h>

struct HostError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

[[noreturn]] inline void fail(const std::string& message) { throw HostError(message); }

// Vulkan failures name the call, so the one line says what went wrong.
inline void check(VkResult result, const char* call) {
  if (result != VK_SUCCESS) fail(std::string(call) + " failed (VkResult " + std::to_string(result) + ")");
}
