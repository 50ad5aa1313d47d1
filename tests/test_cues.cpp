// Cues that reach the player (docs/model.md#cues-for-the-player, issue 34):
// what a spot sends to the listener, derived by hand for single rays; then,
// on both backends, small scenes that show each cause of the old failure
// fixed: the source behind the camera in a closed room, a brief sound in a
// quiet scene, a far source beside a near one, two rooms joined by a door.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "core/glm_interop.h"
#include "draw/display_sources.h"
#include "render/render_target.h"
#include "render/renderer.h"
#include "render/view_camera.h"
#include "sim/cpu_tracer.h"
#include "sp_connect.h"
#include "sp_guide.h"
#include "sp_random.h"
#include "support/gpu_environment.h"
#include "support/run_steps.h"
#include "support/scene_builder.h"
#include "support/single_ray.h"

namespace sp {
namespace {

using test::add_box;
using test::add_closed_room;
using test::source_at;

// ---------------------------------------------------------------- one spot

// A ray from the source at the origin straight down -z onto the front
// (+z) face of a wall whose face is the plane z = -5; the listener at L.
struct OneSpot : test::SingleRay {
  OneSpot() {
    config.air_attenuation = 0.02f;
    config.bounce_energy_loss = 0.2f;
    config.min_energy = 0.05f;
    config.max_bounces = 0;
    config.layers["concrete"] = {0.8f, 2.0f};
    add_box(scene, {-10, -10, -6}, {10, 10, -5}, "concrete");
  }

  // The spot the ray makes, heard at `listener`, its source at `source`.
  shader::Indicator spot(glm::vec3 listener, glm::vec3 source = glm::vec3(0.0f)) {
    world.listener = Vec3{listener.x, listener.y, listener.z};
    sources[0].position = source;
    TraceCounters counters;
    std::vector<shader::Indicator> made = trace(source, {0, 0, -1}, counters);
    EXPECT_EQ(made.size(), 1u);
    if (made.empty()) return {};
    TraceContext context{&world.geometry->bvh, layers, sources, make_sim_params(config, 0, listener)};
    connect_indicators(context, made, counters);
    return made[0];
  }
};

TEST(CueSpot, AHitFacingTheListenerIsHeardWithWhatTheModelReflectsLessTheAir) {
  OneSpot f;
  f.finish();
  const glm::vec3 listener(3.0f, 0.0f, -1.0f);
  const shader::Indicator ind = f.spot(listener);
  // Hit at (0, 0, -5) after 5 m of air: E = 1 - 0.02 * 5 = 0.9. It sends
  // rho_ref (1 - e_loss) E = 0.8 * 0.8 * 0.9 = 0.576 towards the listener,
  // from 0.1 mm off the face: sqrt(3^2 + 3.9999^2) m away, losing 0.02 a metre.
  const double distance = std::sqrt(3.0 * 3.0 + 3.9999 * 3.9999);
  EXPECT_NEAR(ind.energy, 0.9f, 1e-6f);
  EXPECT_NEAR(ind.heard, 0.576 - 0.02 * distance, 1e-5);
  // The sound arrives from the spot: the unit way from the listener to it.
  const glm::vec3 arrival = glm::normalize(glm::vec3(-3.0f, 0.0f, -4.0f));
  EXPECT_NEAR(glm::distance(ind.arrival, arrival), 0.0f, 1e-6f);
  // The source, at the origin, lies at 90 - atan(4 / 3)... from the
  // listener it is along (-3, 0, 1): 71.57 - 18.43 = ... the angle between
  // (-3, 0, -4) and (-3, 0, 1) is acos(5 / (5 * sqrt(10))) = 71.57 degrees,
  // outside the default 30-degree lobe.
  EXPECT_EQ(ind.toward, 0.0f);
  EXPECT_GT(ind.heard, 0.0f);
}

TEST(CueSpot, TowardFallsLinearlyInTheCosineToTheLobesEdge) {
  OneSpot f;
  f.config.cues.toward_angle = 60.0f;
  f.finish();
  // The source 2 m behind the spot's line: from the listener at (0, 0, 3)
  // the spot (0, 0, -5) and the source (0, 0, 0) are both straight ahead.
  shader::Indicator ind = f.spot({0.0f, 0.0f, 3.0f});
  EXPECT_NEAR(ind.toward, 1.0f, 1e-6f);
  // Listener at (4, 0, 0): spot along (-4, 0, -5), source along (-1, 0, 0):
  // cos = 4 / sqrt(41); with cos 60 = 0.5 the lobe gives (c - 0.5) / 0.5.
  ind = f.spot({4.0f, 0.0f, 0.0f});
  const double c = 4.0 / std::sqrt(41.0);
  EXPECT_NEAR(ind.toward, (c - 0.5) / 0.5, 1e-5);
}

TEST(CueSpot, ABlockedWayAFaceTurnedAwayOrTooLittleEnergyIsNotHeard) {
  {  // a pillar between the spot and the listener
    OneSpot f;
    add_box(f.scene, {1.0f, -1.0f, -3.5f}, {2.0f, 1.0f, -2.5f}, "concrete");
    f.finish();
    const shader::Indicator ind = f.spot({3.0f, 0.0f, -1.0f});
    EXPECT_EQ(ind.heard, 0.0f);
    EXPECT_EQ(ind.toward, 0.0f);
  }
  {  // the listener behind the wall: its face turns away from them
    OneSpot f;
    f.finish();
    TraceCounters counters;
    f.world.listener = Vec3{0.0f, 0.0f, -8.0f};
    std::vector<shader::Indicator> made = f.trace({0, 0, 0}, {0, 0, -1}, counters);
    ASSERT_EQ(made.size(), 1u);
    TraceContext context{&f.world.geometry->bvh, f.layers, f.sources,
                         make_sim_params(f.config, 0, glm::vec3(0.0f, 0.0f, -8.0f))};
    connect_indicators(context, made, counters);
    EXPECT_EQ(made[0].heard, 0.0f);
    EXPECT_EQ(counters.connections, 0u) << "a face turned away is not cast";
  }
  {  // 0.576 sent, and the listener 40 m away: 0.576 - 0.8 < tau_min
    OneSpot f;
    f.finish();
    EXPECT_EQ(f.spot({0.0f, 0.0f, 35.0f}).heard, 0.0f);
  }
  {  // listening off: the earlier model, nothing heard
    OneSpot f;
    f.config.cues.listen = false;
    f.finish();
    EXPECT_EQ(f.spot({3.0f, 0.0f, -1.0f}).heard, 0.0f);
  }
}

TEST(CueSpot, AnExitSendsOnWhatLeftTheWall) {
  // A 0.1 m glass sheet across the ray: hit, then the exit on its far side.
  test::SingleRay f;
  f.config.air_attenuation = 0.02f;
  f.config.max_bounces = 1;
  f.config.min_energy = 0.01f;
  f.config.layers["glass"] = {0.0f, 3.0f, 0.1f};  // never reflects
  test::add_quad(f.scene, {-5, -5, -5}, {5, -5, -5}, {5, 5, -5}, {-5, 5, -5}, "glass");
  f.finish();
  TraceCounters counters;
  const glm::vec3 listener(0.0f, 2.0f, -9.0f);  // beyond the glass
  f.world.listener = Vec3{listener.x, listener.y, listener.z};
  std::vector<shader::Indicator> made = f.trace({0, 0, 0}, {0, 0, -1}, counters);
  ASSERT_GE(made.size(), 2u);
  TraceContext context{&f.world.geometry->bvh, f.layers, f.sources, make_sim_params(f.config, 0, listener)};
  connect_indicators(context, made, counters);
  const shader::Indicator& hit = made[0];
  const shader::Indicator& exit = made[1];
  ASSERT_EQ(exit.kind, SP_INDICATOR_EXIT);
  EXPECT_EQ(hit.heard, 0.0f) << "the hit's face turns away from a listener beyond the glass";
  // E = 1 - 0.02 * 5 - 3 * 0.1 = 0.6 leaves; the exit is 0.1 mm off the
  // glass towards the listener, sqrt(2^2 + 3.9999^2) m from them.
  const double distance = std::sqrt(4.0 + 3.9999 * 3.9999);
  EXPECT_NEAR(exit.energy, 0.6f, 1e-6f);
  EXPECT_NEAR(exit.heard, 0.6 - 0.02 * distance, 1e-5);
}

// ---------------------------------------------------------------- the guide

TEST(CueGuide, CellsTileTheSphereAndADirectionDrawnInACellLiesInIt) {
  std::set<std::uint32_t> seen;
  for (std::uint32_t i = 0; i < 20000; ++i) seen.insert(shader::sp_guide_cell(shader::sp_emission_direction(1, 2, i)));
  EXPECT_EQ(seen.size(), SP_GUIDE_CELLS) << "uniform directions reach every cell";
  for (std::uint32_t cell = 0; cell < SP_GUIDE_CELLS; ++cell) {
    for (float f : {0.1f, 0.5f, 0.9f}) {
      const glm::vec3 d = shader::sp_guide_cell_direction(cell, f, 1.0f - f);
      EXPECT_NEAR(glm::length(d), 1.0f, 1e-6f);
      EXPECT_EQ(shader::sp_guide_cell(d), cell) << cell << " " << f;
    }
  }
}

TEST(CueGuide, AFoldDecaysAddsAndSumsAndAPickFollowsTheWeights) {
  std::vector<std::uint32_t> guide(SP_GUIDE_STRIDE, 0u);
  guide[SP_GUIDE_WEIGHTS + 3] = 1600;  // decays by 1600 / 16 = 100
  guide[SP_GUIDE_PENDING + 3] = 50;
  guide[SP_GUIDE_PENDING + 7] = 250;
  shader::sp_guide_fold(guide.data(), 0);
  EXPECT_EQ(guide[SP_GUIDE_WEIGHTS + 3], 1550u);
  EXPECT_EQ(guide[SP_GUIDE_WEIGHTS + 7], 250u);
  EXPECT_EQ(guide[SP_GUIDE_PENDING + 3], 0u);
  EXPECT_EQ(shader::sp_guide_total(guide.data(), 0), 1800u);
  EXPECT_EQ(shader::sp_guide_pick(guide.data(), 0, 0), 3u);
  EXPECT_EQ(shader::sp_guide_pick(guide.data(), 0, 1549), 3u);
  EXPECT_EQ(shader::sp_guide_pick(guide.data(), 0, 1550), 7u);
  EXPECT_EQ(shader::sp_guide_pick(guide.data(), 0, 1799), 7u);
  // Half of a source's rays (guide_share 0.5) are guided, the first ones.
  shader::StepSource source{};
  source.first_ray = 10;
  source.ray_count = 9;
  shader::SimParams p{};
  p.cues = SP_CUES_LISTEN | SP_CUES_GUIDE;
  p.guide_share = 0.5f;
  std::map<std::uint32_t, int> cells;
  for (std::uint32_t ray = 10; ray < 19; ++ray) {
    std::uint32_t cell = 0;
    const glm::vec3 d = shader::sp_source_emission(guide.data(), source, ray, p, cell);
    if (ray < 14) {
      EXPECT_TRUE(cell == 3u || cell == 7u) << ray;
      EXPECT_EQ(shader::sp_guide_cell(d), cell);
    } else {
      EXPECT_EQ(d, shader::sp_emission_direction(p.seed, p.step, ray)) << "the rest go out uniformly";
    }
  }
}

// ---------------------------------------------------------------- scenes, both backends

class Cues : public test::GpuTest, public ::testing::WithParamInterface<Backend> {
 protected:
  std::unique_ptr<Simulator> simulator(const Scene& scene, const Config& config) {
    return make_simulator(make_world(scene, config).value(), GetParam());
  }
};

// The room: 10 x 4 x 8 m, closed, the player at z = 1 looking
// towards -z, the source 4 m behind them. The old ring kept the strongest
// spots, by the source, out of view: the wall in front of the player
// showed none after 10 steps.
Scene room_with_source_behind() {
  Scene scene;
  add_closed_room(scene, {-5, 0, -4}, {5, 4, 4}, 0.3f, "concrete");
  scene.sources.push_back(source_at({0.0f, 1.6f, 3.0f}));
  return scene;
}

Config room_config(std::uint32_t seed) {
  Config config;
  config.listener_position = glm::vec3(0.0f, 1.6f, -1.0f);
  config.seed = seed;
  return config;
}

TEST_P(Cues, TheWallInFrontOfThePlayerCarriesSpotsWhenTheSourceIsBehind) {
  auto sim = simulator(room_with_source_behind(), room_config(1));
  const test::Recorded out = test::run_steps(*sim, 10);
  std::size_t front = 0;  // on the wall at z = -4, facing the player
  for (const Indicator& ind : out.live) front += ind.position.z < -3.99f && ind.normal.z > 0.99f;
  EXPECT_GT(front, 50u) << out.live.size() << " live";
  std::size_t heard = 0;
  for (const Indicator& ind : out.live) heard += ind.heard_energy > 0.0f;
  EXPECT_GT(heard, 0u);
}

TEST_P(Cues, AnotherSeedPaintsAnotherPicture) {
  const Scene scene = room_with_source_behind();
  draw::RenderSettings settings;
  settings.width = 160;
  settings.height = 120;
  draw::CameraOverrides look;
  look.position = glm::vec3(0.0f, 1.6f, -1.0f);
  look.look_at = glm::vec3(0.0f, 1.6f, -4.0f);
  std::vector<draw::RgbaImage> pictures;
  for (std::uint32_t seed : {1u, 2u}) {
    auto sim = simulator(scene, room_config(seed));
    for (int n = 0; n < 10; ++n) ASSERT_TRUE(sim->step().ok());
    draw::Renderer renderer(*test::GpuEnvironment::context(), sim->world(), settings);
    pictures.push_back(renderer.render(
        draw::make_view_camera(std::nullopt, sim->world(), look, settings.width, settings.height), *sim));
  }
  ASSERT_EQ(pictures[0].pixels.size(), pictures[1].pixels.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < pictures[0].pixels.size(); ++i) differ += pictures[0].pixels[i] != pictures[1].pixels[i];
  EXPECT_GT(differ, 200u) << "seeds 1 and 2 drew the same picture";
}

// Nothing else sounds, the spots live 100 s: the one step a source plays
// fills the ring's room at once, not a quota of capacity * dt / lifetime.
TEST_P(Cues, ABriefSoundInAQuietSceneFillsTheRoomTheRingHas) {
  Scene scene = room_with_source_behind();
  scene.sources[0].duration = 1.0 / 120.0;  // one step of 1/60 s
  scene.sources[0].interval = 1000.0;
  Config config = room_config(1);
  config.indicator_lifetime = 100.0f;
  config.max_indicators = 1500;
  config.ray_budget = 300;
  auto sim = simulator(scene, config);
  const test::Recorded out = test::run_steps(*sim, 5);
  ASSERT_GT(out.indicators.size(), 300u);
  EXPECT_EQ(out.live.size(), std::min<std::size_t>(out.indicators.size(), 1500u));
  // The old quota: ceil(1500 / (100 * 60)) = 1 spot.
}

// A long hall, both sources in sight: a near one 2 m from the player and a
// far one 16 m away. Every audible source has a floor: the step's budget
// is shared evenly between the sources' heard spots as far as each has
// them, so the far one's are not crowded out.
TEST_P(Cues, AFarSourceKeepsItsFloorBesideANearOne) {
  Scene scene;
  add_closed_room(scene, {-2, 0, -20}, {2, 3, 2}, 0.3f, "concrete");
  scene.sources.push_back(source_at({0.5f, 1.0f, -1.0f}, 40.0f));
  scene.sources.push_back(source_at({0.0f, 1.0f, -17.0f}, 40.0f));
  Config config;
  config.listener_position = glm::vec3(0.0f, 1.6f, 1.0f);
  config.max_indicators = 600;  // quota 10 a step
  auto sim = simulator(scene, config);
  const test::Recorded out = test::run_steps(*sim, 60);
  std::size_t toward[2] = {0, 0};
  for (const Indicator& ind : out.live)
    if (ind.toward > 0.0f && ind.step >= 2) toward[ind.source_id] += 1;  // after the free room's first fill
  EXPECT_GT(toward[1], 100u);
  EXPECT_NEAR(double(toward[1]), double(toward[0]), 0.1 * double(toward[0]) + 5) << toward[0] << " " << toward[1];
}

// Two 6 x 3 x 6 m rooms side by side, joined by a door at one end of the
// shared wall: the source in one, the player in the other, out of its
// sight. A guided source sends more of its rays through the door, and more
// of its spots reach the player.
TEST_P(Cues, AGuidedSourceFindsTheDoorToThePlayer) {
  Scene scene;
  add_closed_room(scene, {-6, 0, -3}, {6, 3, 3}, 0.3f, "concrete");
  add_box(scene, {-0.15f, 0.0f, -3.0f}, {0.15f, 3.0f, 1.8f}, "concrete");  // the wall, a door from z = 1.8 to 3
  scene.sources.push_back(source_at({-4.0f, 1.5f, -2.0f}));
  auto heard = [&](float share) {
    Config config;
    config.listener_position = glm::vec3(4.0f, 1.6f, -2.0f);
    config.cues.guide_share = share;
    config.ray_budget = 200;
    config.layers["concrete"] = {0.9f, 50.0f};  // no sound through the 0.3 m wall
    auto sim = simulator(scene, config);
    const test::Recorded out = test::run_steps(*sim, 40);
    std::size_t n = 0;
    for (const Indicator& ind : out.indicators) n += ind.heard_energy > 0.0f;
    return n;
  };
  const std::size_t uniform = heard(0.0f);
  const std::size_t guided = heard(0.75f);
  EXPECT_GT(uniform, 20u) << "some rays find the door by chance";
  EXPECT_GT(guided, 2 * uniform) << uniform << " heard unguided";
}

// One liveness rule on both backends: a spot of 0.3 s is live (and drawn)
// for the display's 1/3 s, then neither. At dt = 1/16 s: ages 0 to 5/16 s.
TEST_P(Cues, ASpotIsLiveForTheDisplaysLifetimeThenNot) {
  Scene scene = room_with_source_behind();
  scene.sources[0].duration = 1.0 / 32.0;  // the first step only
  scene.sources[0].interval = 1000.0;
  Config config = room_config(1);
  config.dt = 1.0 / 16.0;
  config.indicator_lifetime = 0.3f;
  config.ray_budget = 100;
  auto sim = simulator(scene, config);
  for (int n = 0; n <= 5; ++n) ASSERT_TRUE(sim->step().ok());
  EXPECT_FALSE(sim->live_indicators()->empty()) << "5/16 s old: under 1/3 s";
  ASSERT_TRUE(sim->step().ok());
  EXPECT_TRUE(sim->live_indicators()->empty()) << "6/16 s old: past the display's lifetime";
}

INSTANTIATE_TEST_SUITE_P(Backends, Cues, ::testing::Values(Backend::Cpu, Backend::Gpu),
                         [](const auto& c) { return c.param == Backend::Gpu ? "Gpu" : "Cpu"; });

// ---------------------------------------------------------------- hidden sources

TEST(CueArrows, ASourceBehindAWallFromTheListenerIsOccludedAndOneInSightIsNot) {
  Scene scene;
  add_box(scene, {-1, 0, -5}, {1, 3, -4}, "concrete");      // a wall 4 m ahead
  scene.sources.push_back(source_at({0.0f, 1.5f, -8.0f}));  // behind it
  scene.sources.push_back(source_at({3.0f, 1.5f, -8.0f}));  // beside it, in sight
  scene.sources.push_back(source_at({0.0f, 0.0f, -4.0f}));  // on the wall's face: not hidden by it
  Config config;
  config.listener_position = glm::vec3(0.0f, 1.5f, 0.0f);
  const World world = make_world(scene, config).value();
  const std::vector<std::uint32_t> cues = draw::make_source_cues(world);
  ASSERT_EQ(cues.size(), 3u);
  EXPECT_EQ(cues[0], SP_SOURCE_CUE_OCCLUDED);
  EXPECT_EQ(cues[1], 0u);
  EXPECT_EQ(cues[2], 0u);
}

}  // namespace
}  // namespace sp
