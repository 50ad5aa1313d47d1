// One Vulkan context per test binary, with the Khronos validation layer on.
// GPU tests skip (printing why) only when there is truly no Vulkan device;
// every test fixture fails if validation reported anything during it.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "gpu/gpu_simulator.h"
#include "soundpaint/simulation.h"
#include "vk/context.h"

namespace sp::test {

class GpuEnvironment : public ::testing::Environment {
 public:
  static vk::Context* context() { return context_.get(); }
  static const std::string& unavailable_reason() { return reason_; }

  void SetUp() override {
    vk::ContextSettings settings;
    settings.validation = true;
    auto created = vk::Context::create(settings);
    if (created) {
      context_ = std::move(created.value());
      std::printf("[ GPU      ] %s\n", context_->description().c_str());
    } else {
      reason_ = created.error().message;
      std::printf("[ GPU      ] no Vulkan device, GPU tests skip: %s\n", reason_.c_str());
    }
  }
  void TearDown() override { context_.reset(); }

 private:
  static inline std::unique_ptr<vk::Context> context_;
  static inline std::string reason_;
};

// Fixture base: skips without a device; asserts zero validation messages.
class GpuTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!GpuEnvironment::context()) {
      // CI installs lavapipe, so there a missing device is a broken setup,
      // not a reason to skip the GPU half of the suite.
      if (const char* ci = std::getenv("CI"); ci && std::string(ci) == "true")
        FAIL() << "CI=true but no Vulkan device: " << GpuEnvironment::unavailable_reason();
      GTEST_SKIP() << "no Vulkan device: " << GpuEnvironment::unavailable_reason();
    }
    messages_before_ = GpuEnvironment::context()->validation_message_count();
  }
  void TearDown() override {
    vk::Context* context = GpuEnvironment::context();
    if (!context) return;
    auto messages = context->validation_messages();
    EXPECT_EQ(context->validation_message_count(), messages_before_) << "validation messages during the test";
    for (std::size_t k = messages_before_; k < messages.size(); ++k) ADD_FAILURE() << messages[k];
  }

  std::unique_ptr<Simulator> make_simulator(World world, Backend backend) {
    if (backend == Backend::Cpu) return std::move(create_cpu_simulator(std::move(world), CpuSettings{2}).value());
    return std::move(gpu::create_simulator(std::move(world), *GpuEnvironment::context()).value());
  }

 private:
  std::uint32_t messages_before_ = 0;
};

}  // namespace sp::test
