// The memory a config may make a simulator allocate, estimated before it
// does (README "Security"), and the budget that refuses it at creation.
#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include <glm/glm.hpp>

#include "sim/memory_estimate.h"
#include "soundpaint/simulation.h"
#include "sp_types.h"
#include "support/scene_builder.h"

namespace {

constexpr std::uint64_t kIndicator = sizeof(sp::Indicator);

sp::World room_world(const sp::Config& base) {
  sp::Config config = base;
  config.listener_position = glm::vec3(0.0f, 1.5f, 0.0f);
  return sp::make_world(sp::test::closed_room(), config).value();
}

// Defaults: 500 rays, 4 bounces, a ring of 4,000. A step makes at most
// 500 * (2 * 4 + 2) = 5,000 indicators, held 4 times on the CPU and twice
// on the GPU (plus what 500 rays take there); the ring is counted twice.
TEST(MemoryEstimate, FollowsTheDocumentedWorstCase) {
  const sp::Config config;
  const sp::MemoryEstimate cpu = sp::estimate_memory(config, sp::Backend::Cpu);
  EXPECT_EQ(cpu.ring_bytes, 2 * 4000 * kIndicator);
  EXPECT_EQ(cpu.step_bytes, 4 * 5000 * kIndicator);
  const sp::MemoryEstimate gpu = sp::estimate_memory(config, sp::Backend::Gpu);
  EXPECT_EQ(gpu.ring_bytes, cpu.ring_bytes);
  // Per GPU ray: a state, a cast result counted as large, two queue slots.
  EXPECT_EQ(gpu.step_bytes, 2 * 5000 * kIndicator + 500 * (2 * sizeof(sp::shader::RayState) + 8));
}

// The README's maxima (ray_budget and max_indicators 2^24, max_bounces 64)
// need hundreds of gigabytes at worst; the estimate must not wrap around.
TEST(MemoryEstimate, SaturatesInsteadOfWrapping) {
  sp::Config config;
  config.ray_budget = sp::kMaxRayBudget;
  config.max_indicators = sp::kMaxIndicatorsLimit;
  config.max_bounces = sp::kMaxBouncesLimit;
  const std::uint64_t expected_step = 4ull * (1ull << 24) * 130 * kIndicator;
  EXPECT_EQ(sp::estimate_memory(config, sp::Backend::Cpu).step_bytes, expected_step);
  EXPECT_GT(sp::estimate_memory(config, sp::Backend::Cpu).total(), std::uint64_t{600} << 30);
}

TEST(MemoryBudget, RefusesTheMaximalConfigAtCreationNamingTheKnobs) {
  sp::Config config;
  config.ray_budget = sp::kMaxRayBudget;
  config.max_indicators = sp::kMaxIndicatorsLimit;
  config.max_bounces = sp::kMaxBouncesLimit;
  const auto start = std::chrono::steady_clock::now();
  const auto simulator = sp::create_cpu_simulator(room_world(config));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_FALSE(simulator.ok());
  EXPECT_EQ(simulator.error().code, sp::ErrorCode::LimitExceeded);
  const std::string& message = simulator.error().message;
  for (const char* named : {"ray_budget 16777216", "max_bounces 64", "max_indicators 16777216",
                            "memory budget of 2.0 GiB", "--memory-budget", "memory_budget_bytes"}) {
    EXPECT_NE(message.find(named), std::string::npos) << named << " in: " << message;
  }
  EXPECT_EQ(message.find('\n'), std::string::npos);
  EXPECT_LT(seconds, 5.0) << "refused only after allocating";
}

TEST(MemoryBudget, IsConfigurable) {
  const sp::Config config;
  const std::uint64_t needed = sp::estimate_memory(config, sp::Backend::Cpu).total();
  sp::CpuSettings settings;
  settings.memory_budget_bytes = needed;
  EXPECT_TRUE(sp::create_cpu_simulator(room_world(config), settings).ok());
  settings.memory_budget_bytes = needed - 1;
  const auto refused = sp::create_cpu_simulator(room_world(config), settings);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().code, sp::ErrorCode::LimitExceeded);
}

TEST(MemoryBudget, DescribesSizesForPeople) {
  EXPECT_EQ(sp::describe_bytes(512), "512 bytes");
  EXPECT_EQ(sp::describe_bytes(1536), "1.5 KiB");
  EXPECT_EQ(sp::describe_bytes(std::uint64_t{2} << 30), "2.0 GiB");
}

}  // namespace
