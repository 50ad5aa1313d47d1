// The C API driven as a game drives it: a render thread steps a simulation
// and reads its indicators while an audio thread (the middleware's
// callback) plays, emits, moves sources and moves the listener. The audio
// calls are queued to the next step, so neither thread sees the other's
// half-done work: every call succeeds, every indicator names a source that
// existed, and every one-shot sounds and then ends. Run under
// ThreadSanitizer by scripts/test.sh (build-tsan/), where a data race fails
// the test even when the results happen to come out right.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "soundpaint/soundpaint.h"

namespace {

std::string last_error() { return sp_last_error_message(); }

// A 20 m quad on the plane z = 1 facing the origin: every source sits at
// the origin, so its rays that head for +z paint indicators on it.
constexpr float kHalf = 10.0f;
const float kQuad[] = {
    -kHalf, -kHalf, 1.0f, -kHalf, kHalf, 1.0f, kHalf, kHalf,  1.0f,  //
    -kHalf, -kHalf, 1.0f, kHalf,  kHalf, 1.0f, kHalf, -kHalf, 1.0f,  //
};
const std::uint32_t kQuadLayers[] = {0, 0};
const char* const kLayerNames[] = {"concrete"};

// Source 0 is silent by its pattern (duration 0): it sounds only when played.
const char* const kConfig = R"({
  "ray_budget": 32, "max_bounces": 0, "air_attenuation": 0, "seed": 5,
  "listener": { "position": [0, 0, 0] },
  "sources": [ { "position": [0, 0, 0], "duration": 0 } ]
})";
constexpr double kDt = 1.0 / 60.0;  // the config's default dt

// Iterations, not time: both loops end whatever the scheduler does.
constexpr int kAudioCalls = 200;
constexpr int kRenderSteps = 200;
// One-shots last two steps; these steps after both threads are done end
// every one of them.
constexpr int kFlushSteps = 4;

struct Simulation {
  sp_scene* scene = nullptr;
  sp_simulation* sim = nullptr;
  sp_sound_scene* sound = nullptr;
  ~Simulation() {
    sp_simulation_destroy(sim);
    sp_scene_destroy(scene);
  }
};

std::vector<sp_indicator> live_indicators(sp_simulation* sim) {
  std::uint32_t count = 0;
  if (sp_simulation_live_indicators(sim, nullptr, 0, &count) != SP_OK) return {};
  std::vector<sp_indicator> out(count);
  if (sp_simulation_live_indicators(sim, out.data(), count, &count) != SP_OK) return {};
  out.resize(count);
  return out;
}

TEST(CapiThreads, AudioThreadCallsWhileTheRenderThreadSteps) {
  Simulation s;
  ASSERT_EQ(sp_scene_create(kQuad, 2, kQuadLayers, kLayerNames, 1, &s.scene), SP_OK) << last_error();
  ASSERT_EQ(sp_simulation_create(s.scene, kConfig, SP_BACKEND_CPU, &s.sim), SP_OK) << last_error();
  ASSERT_EQ(sp_simulation_scene(s.sim, &s.sound), SP_OK) << last_error();

  // Both threads start together, and the audio thread keeps pace with the
  // steps (call i after step i / 2), so that its calls fall between and
  // during all of them rather than all inside the first.
  std::atomic<int> ready{0};
  std::atomic<int> steps_done{0};
  auto start_together = [&] {
    ready.fetch_add(1);
    while (ready.load() < 2) std::this_thread::yield();
  };

  std::vector<std::uint32_t> emitted;     // audio thread's, read after join
  std::vector<std::string> audio_errors;  // likewise
  std::thread audio([&] {
    sp_source_desc shot;
    sp_source_desc_init(&shot);
    start_together();
    for (int i = 0; i < kAudioCalls; ++i) {
      while (steps_done.load() < i / 2) std::this_thread::yield();  // the render loop always gets there
      const float wobble = 0.001f * static_cast<float>(i % 10);
      auto check = [&](sp_result r, const char* call) {
        if (r != SP_OK) audio_errors.push_back(std::string(call) + ": " + last_error());
      };
      check(sp_sound_scene_set_listener(s.sound, wobble, 0.0f, 0.0f), "set_listener");
      check(sp_simulation_set_listener(s.sim, 0.0f, wobble, 0.0f), "simulation_set_listener");
      check(sp_sound_scene_move_source(s.sound, 0, 0.0f, wobble, 0.0f), "move_source");
      check(sp_sound_scene_play(s.sound, 0, kDt), "play");
      check(sp_simulation_play(s.sim, 0, kDt), "simulation_play");
      std::uint32_t id = 0;
      const sp_result r = sp_sound_scene_emit(s.sound, &shot, 2 * kDt - 1e-9, &id);
      check(r, "emit");
      if (r == SP_OK) emitted.push_back(id);
      int live = 0;
      check(sp_sound_scene_has_source(s.sound, 0, &live), "has_source");
      if (live != 1) audio_errors.push_back("source 0 is not live");
    }
  });

  std::set<std::uint32_t> painted;  // source ids seen in indicators
  std::vector<std::string> render_errors;
  auto render_step = [&] {
    if (sp_simulation_step(s.sim) != SP_OK) {
      render_errors.push_back("step: " + last_error());
      return;
    }
    for (const sp_indicator& ind : live_indicators(s.sim)) painted.insert(ind.source_id);
  };
  start_together();
  for (int i = 0; i < kRenderSteps; ++i) {
    render_step();
    steps_done.fetch_add(1);
  }
  audio.join();
  for (int i = 0; i < kFlushSteps; ++i) render_step();

  EXPECT_TRUE(audio_errors.empty()) << audio_errors.size() << " errors, first: " << audio_errors.front();
  EXPECT_TRUE(render_errors.empty()) << render_errors.size() << " errors, first: " << render_errors.front();
  ASSERT_EQ(emitted.size(), std::size_t{kAudioCalls});

  // Every indicator came from source 0 or from an emitted one-shot, and
  // the one-shots did paint.
  const std::set<std::uint32_t> emitted_ids(emitted.begin(), emitted.end());
  bool one_shot_painted = false;
  for (std::uint32_t id : painted) {
    EXPECT_TRUE(id == 0 || emitted_ids.contains(id)) << "indicator of source " << id << ", never added";
    one_shot_painted = one_shot_painted || emitted_ids.contains(id);
  }
  EXPECT_TRUE(one_shot_painted);

  // Every one-shot has ended and freed its slot; source 0 stays.
  for (std::uint32_t id : emitted_ids) {
    int live = 1;
    ASSERT_EQ(sp_sound_scene_has_source(s.sound, id, &live), SP_OK) << last_error();
    EXPECT_EQ(live, id == 0 ? 1 : 0) << "one-shot " << id << " still live";
  }
  int source0 = 0;
  ASSERT_EQ(sp_sound_scene_has_source(s.sound, 0, &source0), SP_OK);
  EXPECT_EQ(source0, 1);

  sp_stats stats{};
  ASSERT_EQ(sp_simulation_stats(s.sim, &stats), SP_OK) << last_error();
  EXPECT_EQ(stats.steps, std::uint64_t{kRenderSteps + kFlushSteps});

  // Quiet again, one more one-shot sounds alone: the next step gives it
  // every ray, and some reach the quad.
  sp_source_desc shot;
  sp_source_desc_init(&shot);
  std::uint32_t last = 0;
  ASSERT_EQ(sp_sound_scene_emit(s.sound, &shot, kDt / 2, &last), SP_OK) << last_error();
  ASSERT_EQ(sp_simulation_step(s.sim), SP_OK) << last_error();
  std::size_t of_last = 0;
  for (const sp_indicator& ind : live_indicators(s.sim))
    of_last += (ind.source_id == last && ind.step == kRenderSteps + kFlushSteps) ? 1 : 0;
  EXPECT_GT(of_last, 0u);
}

// The render thread's calls may move from thread to thread between them
// (soundpaint.h, Thread-safety): stepping here, then reading and stepping
// on another thread, is allowed, and SoundScene's debug thread check
// (assertions are on under ThreadSanitizer) follows the hand-over rather
// than aborting.
TEST(CapiThreads, RenderCallsMayMoveToAnotherThreadBetweenCalls) {
  Simulation s;
  ASSERT_EQ(sp_scene_create(kQuad, 2, kQuadLayers, kLayerNames, 1, &s.scene), SP_OK) << last_error();
  ASSERT_EQ(sp_simulation_create(s.scene, kConfig, SP_BACKEND_CPU, &s.sim), SP_OK) << last_error();
  ASSERT_EQ(sp_simulation_step(s.sim), SP_OK) << last_error();
  sp_result stats_result = SP_ERROR_INVALID_ARGUMENT;
  sp_result step_result = SP_ERROR_INVALID_ARGUMENT;
  sp_stats stats{};
  std::thread other([&] {
    stats_result = sp_simulation_stats(s.sim, &stats);
    (void)live_indicators(s.sim);
    step_result = sp_simulation_step(s.sim);
  });
  other.join();
  EXPECT_EQ(stats_result, SP_OK);
  EXPECT_EQ(step_result, SP_OK);
  EXPECT_EQ(stats.steps, 1u);
  ASSERT_EQ(sp_simulation_step(s.sim), SP_OK) << last_error();  // and back again
  ASSERT_EQ(sp_simulation_stats(s.sim, &stats), SP_OK) << last_error();
  EXPECT_EQ(stats.steps, 3u);
}

// Stepping and reading are the render thread's, one call at a time. A host
// that breaks the rule from two threads gets an error naming it from the
// call that overlapped, never a race: every call either runs alone or is
// refused, and the steps counted are the steps that returned SP_OK.
TEST(CapiThreads, OverlappingRenderThreadCallsAreRefusedNotRaced) {
  Simulation s;
  ASSERT_EQ(sp_scene_create(kQuad, 2, kQuadLayers, kLayerNames, 1, &s.scene), SP_OK) << last_error();
  ASSERT_EQ(sp_simulation_create(s.scene, kConfig, SP_BACKEND_CPU, &s.sim), SP_OK) << last_error();
  constexpr int kCalls = 100;
  // A refusal must say why; anything else is a failure.
  auto refused = [](sp_result r, const std::string& message) {
    return r == SP_ERROR_INVALID_ARGUMENT && message.find("another thread is inside") != std::string::npos;
  };
  std::atomic<int> ready{0};
  auto start_together = [&] {
    ready.fetch_add(1);
    while (ready.load() < 2) std::this_thread::yield();
  };
  int reader_other = 0;  // results neither SP_OK nor a refusal
  std::thread reader([&] {
    start_together();
    for (int i = 0; i < kCalls; ++i) {
      sp_stats stats{};
      std::uint32_t count = 0;
      const sp_result a = sp_simulation_stats(s.sim, &stats);
      if (a != SP_OK && !refused(a, last_error())) ++reader_other;
      const sp_result b = sp_simulation_live_indicators(s.sim, nullptr, 0, &count);
      if (b != SP_OK && !refused(b, last_error())) ++reader_other;
    }
  });
  std::uint64_t stepped = 0;
  int stepper_other = 0;
  start_together();
  for (int i = 0; i < kCalls; ++i) {
    const sp_result r = sp_simulation_step(s.sim);
    if (r == SP_OK) ++stepped;
    else if (!refused(r, last_error())) ++stepper_other;
  }
  reader.join();
  EXPECT_EQ(reader_other, 0);
  EXPECT_EQ(stepper_other, 0);
  sp_stats stats{};
  ASSERT_EQ(sp_simulation_stats(s.sim, &stats), SP_OK) << last_error();
  EXPECT_EQ(stats.steps, stepped);
}

}  // namespace
