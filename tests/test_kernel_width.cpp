// The width of the simulation's kernels (GpuSettings::workgroup_size):
// what a device gets by default, what is refused, and results that do not
// depend on it.
#include <algorithm>
#include <limits>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>
#include <gtest/gtest.h>

#include "gpu/gpu_resources.h"
#include "support/gpu_environment.h"
#include "support/run_steps.h"
#include "support/scene_builder.h"
#include "vk/context.h"

namespace sp {
namespace {

using test::expect_same_bytes;

class KernelWidth : public test::GpuTest {};

Config room_config(std::uint32_t budget) {
  Config config;
  config.listener_position = glm::vec3(0, 1.5f, 0);
  config.ray_budget = budget;
  config.min_energy = 0.001f;
  return config;
}

struct WidthRun {
  std::vector<Indicator> indicators;  // sorted by (step, iteration, ray, kind)
  std::vector<std::size_t> per_step;  // indicators each step made
  std::vector<Indicator> live;        // the ring's, in its order
  SimulationStats stats;
};

// Four steps at 8 rays (a few dozen spots a step) then four at 300
// (hundreds): on a GPU the connect pass's last subgroup admits the first,
// the admit dispatches the others; on a CPU device the connect pass admits
// them all (gpu::inline_admission_max).
WidthRun run_steps(Simulator& sim) {
  WidthRun out;
  for (int n = 0; n < 8; ++n) {
    if (n == 4) {
      EXPECT_TRUE(sim.set_config(room_config(300)).ok());
    }
    EXPECT_TRUE(sim.step().ok());
    const std::vector<Indicator> step = sim.last_step_indicators().value();
    out.per_step.push_back(step.size());
    out.indicators.insert(out.indicators.end(), step.begin(), step.end());
  }
  test::sort_indicators(out.indicators);
  out.live = sim.live_indicators().value();
  out.stats = sim.stats().value();
  return out;
}

WidthRun run_with_width(std::uint32_t workgroup_size) {
  GpuSettings settings;
  settings.workgroup_size = workgroup_size;
  auto sim = create_gpu_simulator(make_world(test::closed_room(), room_config(8)).value(), settings).value();
  return run_steps(*sim);
}

// The same steps on a context of the shared one's device whose kernels
// are set up as `kernels` asks.
WidthRun run_with_kernels(const vk::KernelSettings& kernels) {
  vk::ContextSettings settings;
  settings.validation = true;
  settings.device_name = test::GpuEnvironment::context()->properties().deviceName;
  settings.kernels = kernels;
  std::unique_ptr<vk::Context> context = vk::Context::create(settings).value();
  auto sim = gpu::create_simulator(make_world(test::closed_room(), room_config(8)).value(), *context).value();
  WidthRun out = run_steps(*sim);
  EXPECT_EQ(context->validation_message_count(), 0u);
  return out;
}

// The same steps with the other way of admitting the steps of more than 64
// spots: the two admit dispatches where the device's choice is the connect
// pass (a CPU device), the connect pass where it is the dispatches.
WidthRun run_with_the_other_admission() {
  vk::KernelSettings kernels;
  kernels.workgroup_size = SP_WORKGROUP_SIZE;
  const bool dispatches_by_default = gpu::inline_admission_max(*test::GpuEnvironment::context()) == 64u;
  kernels.inline_admission_max = dispatches_by_default ? std::numeric_limits<std::uint32_t>::max() : 64u;
  return run_with_kernels(kernels);
}

TEST_F(KernelWidth, ACpuDeviceGetsItsSubgroupWidthWiderOnlyForABudgetThatNeedsIt) {
  const vk::Context& context = *test::GpuEnvironment::context();
  const std::uint32_t subgroup = context.subgroup_size();
  if (context.properties().deviceType != VK_PHYSICAL_DEVICE_TYPE_CPU || subgroup >= SP_WORKGROUP_SIZE) {
    EXPECT_EQ(gpu::kernel_workgroup_size(context, 300), std::uint32_t{SP_WORKGROUP_SIZE});
    return;
  }
  EXPECT_EQ(gpu::kernel_workgroup_size(context, 300), subgroup);
  const std::uint32_t groups = context.properties().limits.maxComputeWorkGroupCount[0];
  EXPECT_EQ(gpu::kernel_workgroup_size(context, subgroup * groups), subgroup);
  EXPECT_EQ(gpu::kernel_workgroup_size(context, subgroup * groups + 1), 2 * subgroup);
}

TEST_F(KernelWidth, TheSameIndicatorsAndTotalsWhateverTheWidth) {
  const std::uint32_t subgroup = test::GpuEnvironment::context()->subgroup_size();
  const WidthRun reference = run_with_width(0);
  // Both ways of admitting ran: steps of at most 64 spots and steps of more.
  EXPECT_TRUE(std::any_of(reference.per_step.begin(), reference.per_step.end(),
                          [](std::size_t n) { return n > 0 && n <= 64; }));
  EXPECT_TRUE(std::any_of(reference.per_step.begin(), reference.per_step.end(), [](std::size_t n) { return n > 64; }));
  for (std::uint32_t width : {2 * subgroup, std::uint32_t{SP_WORKGROUP_SIZE}}) {
    SCOPED_TRACE(width);
    const WidthRun other = run_with_width(width);
    EXPECT_EQ(other.per_step, reference.per_step);
    expect_same_bytes(other.indicators, reference.indicators);
    expect_same_bytes(other.live, reference.live);
    EXPECT_EQ(other.stats.casts, reference.stats.casts);
    EXPECT_EQ(other.stats.connections, reference.stats.connections);
    EXPECT_EQ(other.stats.indicators, reference.stats.indicators);
  }
}

TEST_F(KernelWidth, TheAdmitDispatchesAdmitWhatTheConnectPassAdmits) {
  const WidthRun reference = run_with_width(0);
  ASSERT_TRUE(std::any_of(reference.per_step.begin(), reference.per_step.end(), [](std::size_t n) { return n > 64; }));
  const WidthRun other = run_with_the_other_admission();
  EXPECT_EQ(other.per_step, reference.per_step);
  expect_same_bytes(other.indicators, reference.indicators);
  expect_same_bytes(other.live, reference.live);
  EXPECT_EQ(other.stats.indicators, reference.stats.indicators);
}

// The connect pass over hundreds of spots a step in one workgroup (each
// lane casting for many spots in turn), in three, and in a lane a spot.
TEST_F(KernelWidth, TheSameSpotsHeardWhateverTheConnectPassesWorkgroups) {
  const WidthRun reference = run_with_width(0);
  const std::uint32_t width = gpu::kernel_workgroup_size(*test::GpuEnvironment::context(), 300);
  // Over its four steps of 300 rays, each of three workgroups' lanes casts
  // for several spots in turn.
  ASSERT_GT(reference.stats.connections, 4u * 3u * width * 4u);
  for (std::uint32_t most : {1u, 3u, std::numeric_limits<std::uint32_t>::max()}) {
    SCOPED_TRACE(most);
    vk::KernelSettings kernels;
    kernels.connect_groups_max = most;
    const WidthRun other = run_with_kernels(kernels);
    EXPECT_EQ(other.per_step, reference.per_step);
    expect_same_bytes(other.indicators, reference.indicators);
    expect_same_bytes(other.live, reference.live);
    EXPECT_EQ(other.stats.connections, reference.stats.connections);
  }
}

TEST_F(KernelWidth, AWidthThatIsNoMultipleOfTheSubgroupOrBeyondTheLimitIsRefusedNamingIt) {
  const vk::Context& context = *test::GpuEnvironment::context();
  const std::uint32_t subgroup = context.subgroup_size();
  std::vector<std::uint32_t> bad = {context.properties().limits.maxComputeWorkGroupInvocations * 2};
  if (subgroup > 1) bad.push_back(subgroup + 1);
  for (std::uint32_t width : bad) {
    GpuSettings settings;
    settings.workgroup_size = width;
    auto sim = create_gpu_simulator(make_world(test::closed_room(), room_config(8)).value(), settings);
    ASSERT_FALSE(sim.ok()) << width;
    EXPECT_EQ(sim.error().code, ErrorCode::InvalidArgument);
    EXPECT_NE(sim.error().message.find("workgroup_size"), std::string::npos) << sim.error().message;
  }
}

}  // namespace
}  // namespace sp
