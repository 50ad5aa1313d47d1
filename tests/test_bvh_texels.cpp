// The walks' two ways of reading the tree on a GPU: uniform texel buffers
// where the device's limit allows, its storage buffers otherwise
// (gpu::bvh_texels_usable). When each is used, and that the two give the
// same bytes through all three walks: closest hits, the matter query of
// penetrating rays and the casts to the listener.
#include <algorithm>
#include <cstdint>
#include <limits>
#include <memory>

#include <glm/vec3.hpp>
#include <gtest/gtest.h>

#include "gpu/gpu_resources.h"
#include "gpu/gpu_simulator.h"
#include "sim/world_geometry.h"
#include "support/gpu_environment.h"
#include "support/run_steps.h"
#include "support/scene_builder.h"
#include "vk/context.h"

namespace sp {
namespace {

class BvhTexels : public test::GpuTest {};

// A context on the tests' device whose walks may put at most `max_texels`
// texels in one buffer (0: the device's limit).
std::unique_ptr<vk::Context> context_with_texel_limit(std::uint32_t max_texels) {
  vk::ContextSettings settings;
  settings.validation = true;
  settings.device_name = test::GpuEnvironment::context()->properties().deviceName;
  settings.kernels.max_texel_buffer_elements = max_texels;
  return vk::Context::create(settings).value();
}

TEST_F(BvhTexels, UsedExactlyWhileNodesAndTrianglesEachFitTheLimit) {
  // Two RGBA32UI texels a node (32 bytes), four a triangle (64 bytes).
  const std::unique_ptr<vk::Context> context = context_with_texel_limit(4000);
  EXPECT_TRUE(gpu::bvh_texels_usable(*context, 2000, 1000));
  EXPECT_FALSE(gpu::bvh_texels_usable(*context, 2001, 1000));
  EXPECT_FALSE(gpu::bvh_texels_usable(*context, 2000, 1001));
  EXPECT_EQ(context->validation_message_count(), 0u);
}

TEST_F(BvhTexels, TheDevicesOwnLimitAppliesWithoutARequest) {
  // Capped where a texel index would no longer fit texelFetch's int.
  const vk::Context& context = *test::GpuEnvironment::context();
  const std::size_t limit = std::min<std::size_t>(context.properties().limits.maxTexelBufferElements,
                                                  std::numeric_limits<std::int32_t>::max());
  EXPECT_TRUE(gpu::bvh_texels_usable(context, limit / 2, limit / 4));
  EXPECT_FALSE(gpu::bvh_texels_usable(context, limit / 2 + 1, 1));
  EXPECT_FALSE(gpu::bvh_texels_usable(context, 1, limit / 4 + 1));
}

// The closed room, whose 0.3 m concrete walls let about half the rays
// through (matter queries), with the listener inside (casts to it).
World room_world() {
  Config config;
  config.listener_position = glm::vec3(-1.5f, 1.5f, 1.0f);
  config.ray_budget = 300;
  config.min_energy = 0.001f;
  config.layers["concrete"] = {0.5f, 1.0f};
  return make_world(test::closed_room(), config).value();
}

// Six steps of room_world(), the indicators in a fixed order.
test::Recorded run_room(vk::Context& context) {
  auto sim = gpu::create_simulator(room_world(), context).value();
  test::Recorded out = test::run_steps(*sim, 6);
  test::sort_indicators(out.indicators);
  return out;
}

TEST_F(BvhTexels, StorageReadsGiveTheSameIndicatorsAsTexelReads) {
  const World room = room_world();
  const std::size_t nodes = room.geometry->bvh.nodes.size();
  const std::size_t triangles = room.geometry->bvh.triangles.size();
  const std::unique_ptr<vk::Context> texels = context_with_texel_limit(0);
  const std::unique_ptr<vk::Context> storage = context_with_texel_limit(1);
  ASSERT_TRUE(gpu::bvh_texels_usable(*texels, nodes, triangles));
  ASSERT_FALSE(gpu::bvh_texels_usable(*storage, nodes, triangles));

  const test::Recorded reference = run_room(*texels);
  // All three walks ran.
  ASSERT_GT(reference.indicators.size(), 100u);
  std::uint64_t penetrations = 0;
  for (const LayerCounters& layer : reference.stats.layers) penetrations += layer.penetrations;
  EXPECT_GT(penetrations, 100u);
  EXPECT_GT(reference.stats.connections, 100u);

  const test::Recorded other = run_room(*storage);
  test::expect_same_bytes(other.indicators, reference.indicators);
  test::expect_same_bytes(other.live, reference.live);
  EXPECT_EQ(other.stats.casts, reference.stats.casts);
  EXPECT_EQ(other.stats.connections, reference.stats.connections);
  EXPECT_EQ(texels->validation_message_count(), 0u);
  EXPECT_EQ(storage->validation_message_count(), 0u);
}

}  // namespace
}  // namespace sp
