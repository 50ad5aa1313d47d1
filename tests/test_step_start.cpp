// What the host writes into the control block before a step's first kernel
// (gpu::step_start_control): the kernels read these as the step's starting
// counts and dispatch arguments, none of them resetting anything first.
#include <gtest/gtest.h>

#include "gpu/step_recorder.h"

namespace sp {
namespace {

void expect_groups(const shader::QueueArgs& q, std::uint32_t active, std::uint32_t groups) {
  EXPECT_EQ(q.active_count, active);
  EXPECT_EQ(q.resolving_count, 0u);
  // resolve runs over every entry, trace over the Active ones, the matter
  // query over none: no ray resolves a penetration yet.
  EXPECT_EQ(q.group_count_x, groups);
  EXPECT_EQ(q.active_groups_x, groups);
  EXPECT_EQ(q.resolving_groups_x, 0u);
  for (std::uint32_t other : {q.group_count_y, q.group_count_z, q.active_groups_y, q.active_groups_z,
                              q.resolving_groups_y, q.resolving_groups_z})
    EXPECT_EQ(other, 1u);
}

TEST(StepStart, QueueZeroHoldsTheStepsRaysInGroupsOfTheKernelsWidth) {
  // 100 rays in groups of 8: 12 full groups and one of 4.
  const shader::Control start = gpu::step_start_control(100, 8);
  expect_groups(start.queues[0], 100, 13);
  expect_groups(start.queues[1], 0, 0);
  expect_groups(gpu::step_start_control(64, 64).queues[0], 64, 1);
  expect_groups(gpu::step_start_control(65, 64).queues[0], 65, 2);
  expect_groups(gpu::step_start_control(0, 8).queues[0], 0, 0);
}

TEST(StepStart, EveryCountStartsAtZeroAndTheConnectPassRunsOneGroup) {
  const shader::Control start = gpu::step_start_control(100, 8);
  for (std::uint32_t count : {start.step_indicators, start.step_casts, start.step_cut_short, start.step_connections,
                              start.connect_count, start.admit_count, start.tiebreak_count, start.resolve_done,
                              start.connect_done, start.tiebreak_done, start.copy_done})
    EXPECT_EQ(count, 0u);
  // The connect pass always runs a group: its last subgroup keeps the
  // totals and plans the admission, even in a step without rays.
  EXPECT_EQ(start.connect_group_count_x, 1u);
  EXPECT_EQ(start.connect_group_count_y, 1u);
  EXPECT_EQ(start.connect_group_count_z, 1u);
  // The admission's passes run over no indicator until resolve lists some.
  EXPECT_EQ(start.admit_group_count_x, 0u);
  EXPECT_EQ(start.admit_group_count_y, 1u);
  EXPECT_EQ(start.admit_group_count_z, 1u);
}

}  // namespace
}  // namespace sp
