// SoundScene's bookkeeping and argument checks, without a backend: ids and
// slots, capacity, play windows and one-shots as the step plan sees them,
// changes queued for the next step (from another thread too), moving parts
// placed out of the BVH's reach, and every misuse an engine binding could
// make.
#include <atomic>
#include <cfloat>
#include <cmath>
#include <limits>
#include <set>
#include <thread>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "sim/sound_scene_backend.h"
#include "sim/step_plan.h"
#include "sim/world_geometry.h"
#include "soundpaint/simulation.h"
#include "support/scene_builder.h"

namespace sp {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

World room_world(std::size_t sources, bool movable_box = false) {
  Scene scene = test::closed_room();
  scene.sources.clear();
  for (std::size_t i = 0; i < sources; ++i) scene.sources.push_back(test::source_at({0, 1, 0}));
  if (movable_box) {
    const std::size_t first = scene.triangle_count();
    test::add_box(scene, {1, 0, 0}, {1.2f, 2, 1}, "wood");
    scene.instance_names = {"door"};
    scene.triangle_instances.assign(scene.triangle_count(), kStaticInstance);
    for (std::size_t t = first; t < scene.triangle_count(); ++t) scene.triangle_instances[t] = 0;
  }
  Config config;
  config.listener_position = glm::vec3(0, 1.5f, 0);
  config.ray_budget = 90;
  return make_world(scene, config).value();
}

std::vector<std::uint32_t> planned_ids(SoundScene& scene, std::uint64_t step) {
  StepPlan plan;
  detail::SoundSceneBackend::plan(scene, step, plan);
  std::vector<std::uint32_t> ids;
  for (const auto& s : plan.sources) ids.push_back(s.source_id);
  return ids;
}

void expect_invalid(const Result<bool>& r, const char* words) {
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::InvalidArgument);
  EXPECT_NE(r.error().message.find(words), std::string::npos) << r.error().message;
}

TEST(SoundScene, AddedSourcesTakeTheLowestFreeSlot) {
  SoundScene scene(room_world(2));
  EXPECT_EQ(scene.add_source(test::source_at({1, 1, 1})).value(), 2u);
  ASSERT_TRUE(scene.remove_source(0).ok());
  EXPECT_FALSE(scene.has_source(0));
  EXPECT_EQ(scene.add_source(test::source_at({1, 1, 1})).value(), 0u);
  EXPECT_EQ(planned_ids(scene, 0), (std::vector<std::uint32_t>{0, 1, 2}));
}

TEST(SoundScene, RemovedSourcesAreNotPlannedAndSplitNoBudget) {
  SoundScene scene(room_world(3));
  ASSERT_TRUE(scene.remove_source(1).ok());
  StepPlan plan;
  detail::SoundSceneBackend::plan(scene, 0, plan);
  ASSERT_EQ(plan.sources.size(), 2u);
  EXPECT_EQ(plan.sources[0].ray_count, 45u);  // 90 rays over the two left
  EXPECT_EQ(plan.sources[1].source_id, 2u);
}

TEST(SoundScene, CapacityIsEnforcedWithLimitExceeded) {
  SoundScene scene(room_world(0));
  for (std::uint32_t i = 0; i < scene.source_capacity(); ++i)
    ASSERT_TRUE(scene.add_source(test::source_at({0, 1, 0})).ok());
  Result<std::uint32_t> one_more = scene.add_source(test::source_at({0, 1, 0}));
  ASSERT_FALSE(one_more.ok());
  EXPECT_EQ(one_more.error().code, ErrorCode::LimitExceeded);
  ASSERT_TRUE(scene.remove_source(7).ok());
  EXPECT_EQ(scene.emit(test::source_at({0, 1, 0}), 1.0).value(), 7u);
}

TEST(SoundScene, PlayOpensAWindowFromTheNextStep) {
  World world = room_world(1);
  world.sources[0].duration = 0.0;  // silent by pattern
  const double dt = world.config.dt;
  SoundScene scene(std::move(world));
  EXPECT_TRUE(planned_ids(scene, 0).empty());
  ASSERT_TRUE(scene.play(0, 3 * dt - 1e-9).ok());  // steps 1, 2, 3
  EXPECT_EQ(planned_ids(scene, 1).size(), 1u);
  EXPECT_EQ(planned_ids(scene, 2).size(), 1u);
  EXPECT_EQ(planned_ids(scene, 3).size(), 1u);
  EXPECT_TRUE(planned_ids(scene, 4).empty());
}

TEST(SoundScene, EmittedOneShotIgnoresItsPatternAndFreesItsSlot) {
  SoundScene scene(room_world(0));
  SourceDesc pattern = test::source_at({0, 1, 0});
  pattern.phase = 100.0;  // would never play by pattern
  const double dt = scene.world().config.dt;
  const std::uint32_t id = scene.emit(pattern, 2 * dt - 1e-9).value();
  EXPECT_EQ(planned_ids(scene, 0), std::vector<std::uint32_t>{id});
  EXPECT_EQ(planned_ids(scene, 1), std::vector<std::uint32_t>{id});
  EXPECT_TRUE(planned_ids(scene, 2).empty());
  EXPECT_FALSE(scene.has_source(id));
}

TEST(SoundScene, MisuseIsAnErrorNamingTheProblem) {
  SoundScene scene(room_world(1, true));
  expect_invalid(scene.set_listener({kNaN, 0, 0}), "finite");
  expect_invalid(scene.move_source(0, {0, kNaN, 0}), "finite");
  expect_invalid(scene.move_source(5, {0, 0, 0}), "unknown source id 5");
  expect_invalid(scene.play(0, -1.0), "duration");
  expect_invalid(scene.play(0, std::nan("")), "duration");
  SourceDesc bad = test::source_at({0, 0, 0});
  bad.interval = 0.0;
  EXPECT_FALSE(scene.add_source(bad).ok());
  expect_invalid(scene.update_source(0, bad), "interval");
  bad = test::source_at({0, 0, kNaN});
  EXPECT_FALSE(scene.emit(bad, 1.0).ok());
  ASSERT_TRUE(scene.remove_source(0).ok());
  expect_invalid(scene.remove_source(0), "was removed");
  expect_invalid(scene.play(0, 1.0), "was removed");
  glm::mat4 nan_matrix(1.0f);
  nan_matrix[3][1] = kNaN;
  expect_invalid(scene.set_instance_transform(0, nan_matrix), "finite");
  expect_invalid(scene.set_instance_transform(1, glm::mat4(1.0f)), "unknown instance 1");
  EXPECT_FALSE(scene.geometry_pending());
}

TEST(SoundScene, InstanceTransformsMoveOnlyTheirTrianglesAtTheNextUpdate) {
  SoundScene scene(room_world(0, true));
  const float door_top_before = scene.world().geometry->bvh.nodes[0].bmax.y;
  ASSERT_TRUE(scene.set_instance_transform(0, glm::translate(glm::mat4(1.0f), {0, 5, 0})).ok());
  EXPECT_TRUE(scene.geometry_pending());
  EXPECT_EQ(scene.world().geometry->bvh.nodes[0].bmax.y, door_top_before);  // nothing moves before the step
  const BvhChanges changes = detail::SoundSceneBackend::update_geometry(scene);
  EXPECT_FALSE(changes.triangles.empty());
  // The door's top, 2 m, moved to 7 m; the room's own top is 3.3 m.
  EXPECT_FLOAT_EQ(scene.world().geometry->bvh.nodes[0].bmax.y, 7.0f);
  std::size_t moved = 0;
  for (const BvhTriangle& t : scene.world().geometry->bvh.triangles) moved += t.v0.y >= 5.0f ? 1 : 0;
  EXPECT_EQ(moved, 12u);
  EXPECT_TRUE(detail::SoundSceneBackend::update_geometry(scene).triangles.empty());  // nothing pending
}

// FLT_MAX is finite, but a door scaled by it has vertices at FLT_MAX and
// +-inf, which the refit refuses (and the step with it, for good): checked at the call, the transform is
// refused with the reason, nothing is queued, and the steps go on from the
// previous transform.
TEST(SoundScene, ExtremeInstanceTransformIsRefusedAndThePreviousOneStays) {
  SoundScene scene(room_world(0, true));
  ASSERT_TRUE(scene.set_instance_transform(0, glm::translate(glm::mat4(1.0f), {0, 5, 0})).ok());
  (void)detail::SoundSceneBackend::update_geometry(scene);
  ASSERT_FLOAT_EQ(scene.world().geometry->bvh.nodes[0].bmax.y, 7.0f);

  const glm::mat4 huge_scale = glm::scale(glm::mat4(1.0f), glm::vec3(FLT_MAX));
  Result<bool> refused = scene.set_instance_transform(0, huge_scale);
  expect_invalid(refused, "instance 0 (\"door\")");
  expect_invalid(refused, "coordinate bound");  // the door's first vertex, x = 1, lands on FLT_MAX
  expect_invalid(refused, "previous transform stays");
  expect_invalid(scene.set_instance_transform(0, glm::translate(glm::mat4(1.0f), glm::vec3(FLT_MAX)) * huge_scale),
                 "not finite");
  // Finite everywhere, but 1e11 m away: beyond the bound (1e10 m).
  expect_invalid(scene.set_instance_transform(0, glm::translate(glm::mat4(1.0f), {0, 1e11f, 0})), "coordinate bound");
  EXPECT_FALSE(scene.geometry_pending());
  EXPECT_TRUE(detail::SoundSceneBackend::update_geometry(scene).triangles.empty());
  EXPECT_FLOAT_EQ(scene.world().geometry->bvh.nodes[0].bmax.y, 7.0f);

  // Large but within the bound is placed: the door's top (2 m) at 2e9 m.
  ASSERT_TRUE(scene.set_instance_transform(0, glm::scale(glm::mat4(1.0f), glm::vec3(1e9f))).ok());
  EXPECT_FALSE(detail::SoundSceneBackend::update_geometry(scene).triangles.empty());
  EXPECT_FLOAT_EQ(scene.world().geometry->bvh.nodes[0].bmax.y, 2e9f);
}

// What a call changes waits in the queue: the ids, has_source and
// listener() answer for it at once, the World the steps read only from the
// next step on, and in the order the calls were made.
TEST(SoundScene, ChangesWaitForTheNextStepAndApplyInCallOrder) {
  SoundScene scene(room_world(2));
  const std::uint32_t added = scene.add_source(test::source_at({1, 1, 1})).value();
  EXPECT_EQ(added, 2u);
  EXPECT_TRUE(scene.has_source(added));
  EXPECT_EQ(scene.world().sources.size(), 2u);  // not yet
  ASSERT_TRUE(scene.set_listener({0, 2, 0}).ok());
  EXPECT_EQ(scene.listener(), Vec3(0, 2, 0));
  EXPECT_EQ(scene.world().listener, Vec3(0, 1.5f, 0));  // not yet
  // Removing frees the id at once; the add that takes it and the move that
  // follows apply after the removal.
  ASSERT_TRUE(scene.remove_source(0).ok());
  EXPECT_FALSE(scene.has_source(0));
  EXPECT_EQ(scene.add_source(test::source_at({-1, 1, -1})).value(), 0u);
  ASSERT_TRUE(scene.move_source(0, {-2, 1, -2}).ok());

  EXPECT_EQ(planned_ids(scene, 0), (std::vector<std::uint32_t>{0, 1, 2}));
  ASSERT_EQ(scene.world().sources.size(), 3u);
  EXPECT_EQ(scene.world().sources[0].position, Vec3(-2, 1, -2));
  EXPECT_EQ(scene.world().sources[2].position, Vec3(1, 1, 1));
  EXPECT_EQ(scene.world().listener, Vec3(0, 2, 0));
}

// An audio thread plays, emits, moves sources and the listener and swings
// the door while this thread plans and refits step after step. Run under
// ThreadSanitizer too (scripts/test.sh): any unsynchronised access fails.
TEST(SoundScene, AnotherThreadChangesTheSceneWhileStepsRun) {
  SoundScene scene(room_world(1, true));
  const double dt = scene.world().config.dt;
  constexpr int kCalls = 300;
  constexpr int kSteps = 300;
  std::atomic<int> steps_done{0};
  std::vector<std::uint32_t> emitted;
  int errors = 0;
  std::thread audio([&] {
    for (int i = 0; i < kCalls; ++i) {
      while (steps_done.load() < i / 2) std::this_thread::yield();  // keeps pace; the steps always get there
      const float angle = 0.01f * static_cast<float>(i);
      errors += scene.set_listener({0, 1.5f, angle}).ok() ? 0 : 1;
      errors += scene.move_source(0, {angle, 1, 0}).ok() ? 0 : 1;
      errors += scene.play(0, dt).ok() ? 0 : 1;
      errors += scene.set_instance_transform(0, glm::rotate(glm::mat4(1.0f), angle, {0, 1, 0})).ok() ? 0 : 1;
      Result<std::uint32_t> id = scene.emit(test::source_at({0, 1, 0.5f}), 2 * dt - 1e-9);
      if (id) emitted.push_back(*id);
      errors += id ? 0 : 1;
      errors += scene.has_source(0) ? 0 : 1;
    }
  });
  std::set<std::uint32_t> planned;
  for (int step = 0; step < kSteps; ++step) {
    (void)detail::SoundSceneBackend::update_geometry(scene);
    for (std::uint32_t id : planned_ids(scene, std::uint64_t(step))) planned.insert(id);
    steps_done.fetch_add(1);
  }
  audio.join();
  for (int step = kSteps; step < kSteps + 3; ++step)
    for (std::uint32_t id : planned_ids(scene, std::uint64_t(step))) planned.insert(id);

  EXPECT_EQ(errors, 0);
  ASSERT_EQ(emitted.size(), std::size_t{kCalls});
  // Every one-shot was planned (each is alone in no step, but every
  // playing source within reach is planned) and has ended since.
  for (std::uint32_t id : std::set<std::uint32_t>(emitted.begin(), emitted.end())) {
    EXPECT_TRUE(planned.contains(id)) << "one-shot " << id << " never planned";
    EXPECT_FALSE(scene.has_source(id)) << "one-shot " << id << " still live";
  }
  EXPECT_TRUE(scene.has_source(0));
  EXPECT_EQ(scene.world().sources[0].position, Vec3(0.01f * (kCalls - 1), 1, 0));
}

#ifndef NDEBUG
// Debug builds only (the check is compiled out with NDEBUG): world() from
// a thread that does not step aborts with a message saying so.
TEST(SoundSceneDeathTest, WorldFromAnotherThreadAbortsInDebugBuilds) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_DEATH(
      {
        SoundScene scene(room_world(1));
        (void)planned_ids(scene, 0);
        std::thread other([&] { (void)scene.world(); });
        other.join();
      },
      "world\\(\\) called on a thread other than the one that steps");
}
#endif

TEST(SoundScene, SceneInstanceTablesAreChecked) {
  Scene scene = test::closed_room();
  scene.instance_names = {"door"};
  scene.triangle_instances.assign(scene.triangle_count(), 3);
  Config config;
  config.listener_position = glm::vec3(0, 1, 0);
  Result<World> world = make_world(scene, config);
  ASSERT_FALSE(world.ok());
  EXPECT_EQ(world.error().code, ErrorCode::InvalidScene);
  EXPECT_NE(world.error().message.find("instance 3"), std::string::npos);
  scene.triangle_instances.resize(5);
  EXPECT_FALSE(make_world(scene, config).ok());
}

}  // namespace
}  // namespace sp

namespace sp {
namespace {

// A World edited by hand so that its tables disagree is refused, naming
// them, where it used to be repaired behind the host's back.
TEST(SoundScene, AWorldWhoseTablesDisagreeIsRefusedNotRepaired) {
  World extra_source = room_world(1, false);
  extra_source.sources.push_back(extra_source.sources[0]);  // no source_active, no colour for it
  auto refused = create_cpu_simulator(std::move(extra_source));
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().code, ErrorCode::InvalidArgument);
  EXPECT_NE(refused.error().message.find("2 sources but 1 source_active and 1 source_colors"), std::string::npos)
      << refused.error().message;

  World lost_transforms = room_world(1, true);
  lost_transforms.instance_transforms.clear();
  auto also_refused = create_cpu_simulator(std::move(lost_transforms));
  ASSERT_FALSE(also_refused.ok());
  EXPECT_NE(also_refused.error().message.find("1 instances but 0 instance_transforms"), std::string::npos)
      << also_refused.error().message;

  EXPECT_TRUE(create_cpu_simulator(room_world(1, true)).ok()) << "make_world's World is refused";
}

}  // namespace
}  // namespace sp
