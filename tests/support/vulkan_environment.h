// The one GPU test harness and its skip policy (issue 14, item 5).
//
// - One Vulkan context per test binary, validation layer on, held by
//   GpuEnvironment (registered by support/gpu_main.cpp, or by the binary).
// - Every test on it (VulkanTest, and GpuTest in support/gpu_environment.h)
//   fails if the layer reported anything while it ran, from any context in
//   the process.
// - The environment's teardown destroys the context and fails the binary if
//   that produced messages: the layer reports leaked objects there.
// - No Vulkan device: GPU tests skip, saying why, except on CI (CI=true,
//   which .ci/run sets), where a missing device is a broken setup and fails.
//   Any other reason the context cannot be made (no validation layer, say)
//   fails everywhere. SKIP_WITHOUT_VULKAN applies the same policy to a
//   command run by a test (the CLI, the example host).
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sp_types.h"
#include "vk/context.h"
#include "vk/debug_messenger.h"

namespace sp::test {

// True when CI=true (or CI=1): CI installs lavapipe, so no GPU test may skip.
inline bool ci_requires_vulkan() {
  const char* ci = std::getenv("CI");
  return ci != nullptr && (std::string(ci) == "true" || std::string(ci) == "1");
}

// Whether a Vulkan error message means "this machine has no usable device"
// (soundpaint's own wording, also printed by the CLI and the example host).
inline bool says_no_vulkan_device(const std::string& message) {
  return message.find("no Vulkan device") != std::string::npos;
}

inline std::string join_messages(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& line : lines) text += "\n  " + line;
  return text;
}

}  // namespace sp::test

// Ends the current test for want of a Vulkan device: skips, or fails on CI.
// Only in functions returning void (a test body, SetUp).
#define SP_NO_VULKAN_DEVICE(reason)                                                               \
  do {                                                                                            \
    if (::sp::test::ci_requires_vulkan()) FAIL() << "CI=true but no Vulkan device: " << (reason); \
    GTEST_SKIP() << "no Vulkan device: " << (reason);                                             \
  } while (false)

// For a command run by a test: `result` has .status and .err (stderr). Ends
// the test as SP_NO_VULKAN_DEVICE when the command failed for want of a device.
#define SKIP_WITHOUT_VULKAN(result)                                                                                 \
  do {                                                                                                              \
    if ((result).status != 0 && ::sp::test::says_no_vulkan_device((result).err)) SP_NO_VULKAN_DEVICE((result).err); \
  } while (false)

namespace sp::test {

class GpuEnvironment : public ::testing::Environment {
 public:
  static vk::Context* context() { return state().context.get(); }
  // Why there is no context: no device (tests skip, or fail on CI).
  static const std::string& unavailable_reason() { return state().unavailable; }
  // Why there is no context although there may be a device: tests fail.
  static const std::string& failure_reason() { return state().failure; }

  void SetUp() override {
    vk::ContextSettings settings;
    settings.validation = true;
    auto created = vk::Context::create(settings);
    if (created) {
      state().context = std::move(created.value());
      std::printf("[ GPU      ] %s\n", state().context->description().c_str());
      EXPECT_EQ(vk::process_validation_message_count(), 0u)
          << "validation messages while creating the context:" << join_messages(vk::process_validation_messages());
    } else if (says_no_vulkan_device(created.error().message)) {
      state().unavailable = created.error().message;
      std::printf("[ GPU      ] no Vulkan device, GPU tests %s: %s\n", ci_requires_vulkan() ? "fail (CI=true)" : "skip",
                  state().unavailable.c_str());
    } else {
      state().failure = created.error().message;
      std::printf("[ GPU      ] no Vulkan context, GPU tests fail: %s\n", state().failure.c_str());
    }
  }

  // Leaked objects are reported by vkDestroyDevice/vkDestroyInstance, inside
  // ~Context, so the count is read from the process-wide tally afterwards.
  // Without a context there is nothing to check: what the loader said while
  // failing to find a device is not the tests' doing.
  void TearDown() override {
    if (!state().context) return;
    const std::uint32_t before = vk::process_validation_message_count();
    state().context.reset();
    const std::uint32_t after = vk::process_validation_message_count();
    EXPECT_EQ(after, before) << "validation messages while destroying the context (leaks?):"
                             << join_messages(vk::process_validation_messages(before));
    EXPECT_EQ(after, 0u) << "validation messages in this run:" << join_messages(vk::process_validation_messages());
  }

 private:
  struct State {
    std::unique_ptr<vk::Context> context;
    std::string unavailable;
    std::string failure;
  };
  static State& state() {
    static State s;
    return s;
  }
};

// Fixture base of every test that uses the shared context.
class VulkanTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!GpuEnvironment::failure_reason().empty()) FAIL() << "Vulkan context: " << GpuEnvironment::failure_reason();
    if (!GpuEnvironment::context()) SP_NO_VULKAN_DEVICE(GpuEnvironment::unavailable_reason());
    messages_before_ = vk::process_validation_message_count();
  }
  void TearDown() override {
    if (!GpuEnvironment::context()) return;
    const std::uint32_t now = vk::process_validation_message_count();
    if (now != messages_before_) {
      ADD_FAILURE() << (now - messages_before_) << " validation message(s) during this test:"
                    << join_messages(vk::process_validation_messages(messages_before_));
    }
  }

 private:
  std::uint32_t messages_before_ = 0;
};

}  // namespace sp::test
