// Run-time changes on both backends, with hand-derived expectations: a wall
// moved away lets rays through, sources added, moved, recoloured, removed
// and emitted behave as their descriptions say.
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "core/glm_interop.h"
#include "support/backend_cases.h"
#include "support/gpu_environment.h"
#include "support/run_steps.h"
#include "support/scene_builder.h"

namespace sp {
namespace {

class LiveScene : public test::GpuTest, public ::testing::WithParamInterface<test::BackendCase> {
 protected:
  std::unique_ptr<Simulator> simulator(const Scene& scene, const Config& config) {
    return make_simulator(make_world(scene, test::with_traversal(config, GetParam())).value(), GetParam().backend);
  }
};

// A mirror room (every ray reflects, none penetrates) and listener.
Config mirror_config() {
  Config c;
  c.listener_position = glm::vec3(-2, 1.5f, 0);
  c.ray_budget = 200;
  c.max_bounces = 3;
  c.min_energy = 0.0f;
  c.layers["concrete"] = {1.0f, 5.0f};
  c.layers["door"] = {1.0f, 5.0f};
  return c;
}

using test::room_with_movable_wall;

std::size_t count_beyond(const std::vector<Indicator>& indicators, float x) {
  std::size_t n = 0;
  for (const Indicator& ind : indicators) n += ind.position.x > x ? 1 : 0;
  return n;
}

std::vector<Indicator> run(Simulator& sim, int steps) {
  return test::run_steps(sim, static_cast<std::uint64_t>(steps)).indicators;
}

TEST_P(LiveScene, WallMovedAwayLetsRaysReachTheFarSideAndBackBlocksThem) {
  auto sim = simulator(room_with_movable_wall(), mirror_config());
  // Closed: a mirror wall across the whole room; nothing gets behind it.
  std::vector<Indicator> closed = run(*sim, 2);
  ASSERT_FALSE(closed.empty());
  EXPECT_EQ(count_beyond(closed, 0.9f + 1e-4f), 0u);

  // Slid 10 m up, above the ceiling: rays cross x = 1 and hit the +x wall's
  // inner face at x = 3.
  ASSERT_TRUE(sim->scene().set_instance_transform(0, glm::translate(glm::mat4(1.0f), {0, 10, 0})).ok());
  std::vector<Indicator> open = run(*sim, 2);
  EXPECT_GT(count_beyond(open, 1.1f), 20u);
  std::size_t on_far_wall = 0;
  for (const Indicator& ind : open) on_far_wall += std::abs(ind.position.x - 3.0f) < 1e-3f ? 1 : 0;
  EXPECT_GT(on_far_wall, 10u);

  // Back in place: blocked again, bit for bit the rest pose's geometry.
  ASSERT_TRUE(sim->scene().set_instance_transform(0, glm::mat4(1.0f)).ok());
  EXPECT_EQ(count_beyond(run(*sim, 2), 0.9f + 1e-4f), 0u);
}

TEST_P(LiveScene, WallMovedBeyondTheRoomIsHitWhereItWent) {
  // Slid 1.5 m towards +x: its -x face now stands at x = 2.4, so hits on it
  // lie on that plane and none lie between 2.4 and 3.
  auto sim = simulator(room_with_movable_wall(), mirror_config());
  ASSERT_TRUE(sim->scene().set_instance_transform(0, glm::translate(glm::mat4(1.0f), {1.5f, 0, 0})).ok());
  std::vector<Indicator> out = run(*sim, 2);
  std::size_t on_face = 0;
  for (const Indicator& ind : out) {
    on_face += std::abs(ind.position.x - 2.4f) < 1e-3f ? 1 : 0;
    EXPECT_LE(ind.position.x, 2.4f + 1e-3f);
  }
  EXPECT_GT(on_face, 20u);
}

Config open_config() {
  Config c = mirror_config();
  c.listener_position = glm::vec3(0, 1.5f, 0);
  return c;
}

Scene empty_room() {
  Scene scene = test::closed_room();
  scene.sources.clear();
  return scene;
}

TEST_P(LiveScene, AddedSourceEmitsWithItsIdAndColourFromItsPosition) {
  auto sim = simulator(empty_room(), open_config());
  EXPECT_TRUE(run(*sim, 1).empty());
  SourceDesc green = test::source_at({1.0f, 1.5f, 0.5f});
  green.color = {0.0f, 1.0f, 0.0f};
  const std::uint32_t id = sim->scene().add_source(green).value();
  std::vector<Indicator> out = run(*sim, 1);
  ASSERT_FALSE(out.empty());
  for (const Indicator& ind : out) {
    EXPECT_EQ(ind.source_id, id);
    EXPECT_EQ(ind.color, green.color);
    // A first hit lies straight from the source: its path is the distance.
    if (ind.bounces == 0 && ind.penetrations == 0) {
      EXPECT_NEAR(ind.path_length, glm::distance(sp::to_glm(ind.position), sp::to_glm(green.position)), 1e-4f);
    }
  }
}

TEST_P(LiveScene, MovedSourceCastsFromItsNewPosition) {
  Scene scene = empty_room();
  scene.sources = {test::source_at({1.0f, 1.5f, 0.5f})};
  auto sim = simulator(scene, open_config());
  const glm::vec3 moved{-2.0f, 1.0f, -1.5f};
  ASSERT_TRUE(sim->scene().move_source(0, moved).ok());
  std::size_t first_hits = 0;
  for (const Indicator& ind : run(*sim, 1)) {
    if (ind.bounces != 0) continue;
    first_hits += 1;
    EXPECT_NEAR(ind.path_length, glm::distance(sp::to_glm(ind.position), moved), 1e-4f);
  }
  EXPECT_GT(first_hits, 100u);
}

TEST_P(LiveScene, UpdatedColourAppliesFromTheNextStep) {
  Scene scene = empty_room();
  scene.sources = {test::source_at({1.0f, 1.5f, 0.5f})};
  auto sim = simulator(scene, open_config());
  SourceDesc blue = scene.sources[0];
  blue.color = {0.0f, 0.0f, 1.0f};
  ASSERT_TRUE(sim->scene().update_source(0, blue).ok());
  std::vector<Indicator> out = run(*sim, 1);
  ASSERT_FALSE(out.empty());
  for (const Indicator& ind : out) EXPECT_EQ(ind.color, blue.color);
}

TEST_P(LiveScene, RemovedSourceFallsSilentAndItsSlotIsReused) {
  Scene scene = empty_room();
  scene.sources = {test::source_at({1.0f, 1.5f, 0.5f}), test::source_at({-1.0f, 1.5f, 0.5f})};
  auto sim = simulator(scene, open_config());
  ASSERT_TRUE(sim->scene().remove_source(0).ok());
  for (const Indicator& ind : run(*sim, 2)) EXPECT_EQ(ind.source_id, 1u);
  EXPECT_EQ(sim->scene().add_source(test::source_at({0, 1, 0})).value(), 0u);
}

TEST_P(LiveScene, EmittedSoundPlaysForItsDurationThenEnds) {
  Config config = open_config();
  auto sim = simulator(empty_room(), config);
  // Two steps' worth of sound: steps 0 and 1 emit, step 2 does not.
  const std::uint32_t id = sim->scene().emit(test::source_at({0.5f, 1.0f, 0.0f}), 2.0 * config.dt - 1e-9).value();
  EXPECT_FALSE(run(*sim, 1).empty());
  EXPECT_FALSE(run(*sim, 1).empty());
  EXPECT_TRUE(run(*sim, 1).empty());
  EXPECT_FALSE(sim->scene().has_source(id));
  EXPECT_EQ(sim->stats().value().rays_emitted, 2u * config.ray_budget);
}

INSTANTIATE_TEST_SUITE_P(Backends, LiveScene, ::testing::ValuesIn(test::backend_cases()), test::backend_case_name);

}  // namespace
}  // namespace sp
