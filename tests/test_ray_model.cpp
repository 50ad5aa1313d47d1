// The ray model against hand-derived values, one ray at a time: rays are
// placed by hand and traced by the CPU backend's tracer; and how long the
// indicators they leave are live.
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "sim/indicator_ring.h"
#include "sp_ring.h"
#include "sp_types.h"
#include "support/scene_builder.h"
#include "support/single_ray.h"

namespace sp {
namespace {

using Fixture = test::SingleRay;

// A wall of `thickness` between x = 1 and x = 1 + thickness that always
// lets rays through (rho_ref = 0), in air that costs nothing.
Fixture penetrating_wall(float thickness, float attenuation, float max_wall_thickness) {
  Fixture f;
  test::add_box(f.scene, {1.0f, -50.0f, -50.0f}, {1.0f + thickness, 50.0f, 50.0f}, "wall");
  f.config.layers["wall"] = {0.0f, attenuation};
  f.config.air_attenuation = 0.0f;
  f.config.min_energy = 0.01f;
  f.config.max_wall_thickness = max_wall_thickness;
  f.config.max_bounces = 8;
  return f;
}

TEST(RayModel, SlabAtNormalIncidenceCostsAttenuationTimesThickness) {
  Fixture f = penetrating_wall(0.2f, 2.0f, 0.5f);
  f.finish();
  TraceCounters counters;
  auto indicators = f.trace({0, 0, 0}, {1, 0, 0}, counters);
  ASSERT_EQ(indicators.size(), 2u);
  EXPECT_EQ(indicators[0].kind, SP_INDICATOR_HIT);
  EXPECT_NEAR(indicators[0].position.x, 1.0f, 1e-6f);
  EXPECT_FLOAT_EQ(indicators[0].energy, 1.0f);
  EXPECT_EQ(indicators[1].kind, SP_INDICATOR_EXIT);
  EXPECT_NEAR(indicators[1].position.x, 1.2f, 1e-5f);
  EXPECT_NEAR(indicators[1].energy, 1.0f - 2.0f * 0.2f, 1e-5f);  // E0 - alpha * t
  EXPECT_NEAR(indicators[1].path_length, 1.2f, 1e-5f);
  EXPECT_EQ(indicators[1].penetrations, 1u);
  // hit normal faces the ray's side (-x), exit normal the side it leaves to (+x)
  EXPECT_FLOAT_EQ(indicators[0].normal.x, -1.0f);
  EXPECT_FLOAT_EQ(indicators[1].normal.x, 1.0f);
  EXPECT_EQ(counters.layers[0].hits, 1u);
  EXPECT_EQ(counters.layers[0].penetrations, 1u);
  EXPECT_EQ(counters.casts, 3u);  // closest hit, matter query, closest hit into the void
}

TEST(RayModel, SlabAtObliqueIncidenceCostsThicknessOverCosine) {
  for (float degrees : {30.0f, 45.0f, 60.0f}) {
    Fixture f = penetrating_wall(0.2f, 2.0f, 1.0f);
    f.finish();
    float theta = glm::radians(degrees);
    TraceCounters counters;
    auto indicators = f.trace({0, 0, 0}, {std::cos(theta), std::sin(theta), 0}, counters);
    ASSERT_EQ(indicators.size(), 2u) << degrees;
    float path_in_wall = 0.2f / std::cos(theta);  // 0.2309, 0.2828, 0.4 m
    EXPECT_NEAR(indicators[1].energy, 1.0f - 2.0f * path_in_wall, 1e-5f) << degrees;
    EXPECT_NEAR(indicators[1].position.x, 1.2f, 1e-5f) << degrees;
    EXPECT_NEAR(indicators[1].position.y, 1.2f * std::tan(theta), 1e-5f) << degrees;
  }
}

TEST(RayModel, SlabThickerThanMaxWallThicknessAbsorbs) {
  Fixture f = penetrating_wall(1.0f, 0.1f, 0.5f);
  f.finish();
  TraceCounters counters;
  auto indicators = f.trace({0, 0, 0}, {1, 0, 0}, counters);
  ASSERT_EQ(indicators.size(), 1u);  // the entry hit only; no exit
  EXPECT_EQ(indicators[0].kind, SP_INDICATOR_HIT);
  EXPECT_EQ(counters.layers[0].penetrations, 1u);
  EXPECT_EQ(counters.layers[0].no_way_out, 1u);
  EXPECT_EQ(counters.casts, 2u);
}

TEST(RayModel, ObjectBehindWallWithinReachDoesNotCorruptThickness) {
  // Wall x in [1, 1.2]; a crate at x in [1.5, 1.7], inside W_max = 1 of the
  // entry point. Measuring from the far end (the paper) would find the
  // crate's face at 1.7 and report 0.7 m; the exit face nearest p_in is 1.2.
  Fixture f = penetrating_wall(0.2f, 2.0f, 1.0f);
  test::add_box(f.scene, {1.5f, -1.0f, -1.0f}, {1.7f, 1.0f, 1.0f}, "crate");
  f.config.layers["crate"] = {1.0f, 0.0f};
  f.finish();
  TraceCounters counters;
  auto indicators = f.trace({0, 0, 0}, {1, 0, 0}, counters);
  ASSERT_GE(indicators.size(), 2u);
  EXPECT_EQ(indicators[1].kind, SP_INDICATOR_EXIT);
  EXPECT_NEAR(indicators[1].position.x, 1.2f, 1e-5f);
  EXPECT_NEAR(indicators[1].energy, 1.0f - 2.0f * 0.2f, 1e-5f);
  ASSERT_GE(indicators.size(), 3u);  // then it reaches the crate
  EXPECT_NEAR(indicators[2].position.x, 1.5f, 1e-5f);
}

TEST(RayModel, AirAttenuationAndBounceLossCombine) {
  // Mirror walls at x = +-2 (inner faces), rho_ref = 1: a ray along +x from
  // the centre hits at path 2, 6, 10, ... with E = (E0 - a*path) scaled by
  // (1 - e_loss) per bounce so far.
  Fixture f;
  test::add_box(f.scene, {2.0f, -5, -5}, {2.5f, 5, 5}, "mirror");
  test::add_box(f.scene, {-2.5f, -5, -5}, {-2.0f, 5, 5}, "mirror");
  f.config.layers["mirror"] = {1.0f, 0.0f};
  f.config.air_attenuation = 0.01f;
  f.config.bounce_energy_loss = 0.1f;
  f.config.min_energy = 0.0f;
  f.config.max_bounces = 3;
  f.finish();
  TraceCounters counters;
  auto indicators = f.trace({0, 0, 0}, {1, 0, 0}, counters);
  ASSERT_EQ(indicators.size(), 4u);  // max_bounces + 1 hits
  double energy = 1.0;
  double path = 0.0;
  for (std::size_t k = 0; k < indicators.size(); ++k) {
    double leg = k == 0 ? 2.0 : 4.0;
    path += leg;
    energy -= leg * 0.01;
    EXPECT_NEAR(indicators[k].path_length, path, 1e-3) << k;
    EXPECT_NEAR(indicators[k].energy, energy, 1e-5) << k;
    EXPECT_EQ(indicators[k].bounces, k);
    EXPECT_NEAR(std::abs(indicators[k].position.x), 2.0f, 1e-3f) << k;
    EXPECT_NEAR(indicators[k].size, f.config.indicator_size * energy, 1e-5) << k;
    energy *= 1.0 - 0.1;
  }
}

TEST(RayModel, MaxDistanceEndsTheRay) {
  Fixture f = penetrating_wall(0.2f, 0.0f, 0.5f);
  f.finish();
  f.sources[0].max_distance = 0.9f;  // the wall at 1 m is out of reach
  TraceCounters counters;
  EXPECT_TRUE(f.trace({0, 0, 0}, {1, 0, 0}, counters).empty());
  EXPECT_EQ(counters.casts, 1u);
}

TEST(RayModel, EnergyThresholdBoundsTheCast) {
  // E0 = 1, tau_min = 0.5, alpha_air = 1: reach 0.5 m, wall at 1 m.
  Fixture f = penetrating_wall(0.2f, 0.0f, 0.5f);
  f.config.air_attenuation = 1.0f;
  f.config.min_energy = 0.5f;
  f.finish();
  TraceCounters counters;
  EXPECT_TRUE(f.trace({0, 0, 0}, {1, 0, 0}, counters).empty());
  EXPECT_EQ(counters.layers[0].hits, 0u);
}

TEST(RayModel, HitBelowThresholdLeavesNoIndicator) {
  // Reaching the wall 1 m away leaves E = 1 - 0.5 = 0.5 == tau_min (all exact
  // in float): the reach formula lets the cast reach the wall, which counts as
  // a hit, but E <= tau_min kills the ray before any indicator.
  Fixture f = penetrating_wall(0.2f, 0.0f, 0.5f);
  f.config.air_attenuation = 0.5f;
  f.config.min_energy = 0.5f;
  f.finish();
  TraceCounters counters;
  auto indicators = f.trace({0, 0, 0}, {1, 0, 0}, counters);
  EXPECT_TRUE(indicators.empty());  // E == tau_min at the wall: dead, no indicator
  EXPECT_EQ(counters.layers[0].hits, 1u);
}

// The liveness rule, by hand: live while the age, whole steps times dt,
// is below max(indicator_lifetime, 1/3 s); the same answer whether it is
// given indicator_lifetime (live_indicators) or the display's lifetime
// (the draw). In steps of 1/16 s (exact in binary), a 0.3 s spot lives 6
// steps (ages 0 to 5/16 = 0.3125 s), not 5 as its own lifetime would have it.
TEST(Liveness, OneRuleForLiveAndDrawn) {
  EXPECT_EQ(shader::sp_display_lifetime(0.3f), 1.0f / 3.0f);
  EXPECT_EQ(shader::sp_display_lifetime(1.0f / 3.0f), 1.0f / 3.0f);
  EXPECT_EQ(shader::sp_display_lifetime(1.0f), 1.0f);
  const float dt = 1.0f / 16.0f;
  for (float lifetime : {0.3f, shader::sp_display_lifetime(0.3f)}) {
    EXPECT_TRUE(shader::sp_indicator_live(100u, 100u, dt, lifetime));
    EXPECT_TRUE(shader::sp_indicator_live(105u, 100u, dt, lifetime));   // 0.3125 s
    EXPECT_FALSE(shader::sp_indicator_live(106u, 100u, dt, lifetime));  // 0.375 s
  }
  // Above the minimum, indicator_lifetime itself; an age equal to it is over.
  EXPECT_TRUE(shader::sp_indicator_live(15u, 0u, dt, 1.0f));   // 0.9375 s
  EXPECT_FALSE(shader::sp_indicator_live(16u, 0u, dt, 1.0f));  // 1 s
  // At 60 steps a second, 20 steps: 20 * float(1/60) rounds to float(1/3).
  EXPECT_TRUE(shader::sp_indicator_live(19u, 0u, 1.0f / 60.0f, 0.1f));
  EXPECT_FALSE(shader::sp_indicator_live(20u, 0u, 1.0f / 60.0f, 0.1f));
  // The host's form: after `steps_run` steps, the last one is shown.
  Config config;
  config.dt = 1.0 / 16.0;
  config.indicator_lifetime = 0.3f;
  EXPECT_FALSE(is_live(0u, 0u, config));  // nothing before the first step
  EXPECT_TRUE(is_live(0u, 6u, config));
  EXPECT_FALSE(is_live(0u, 7u, config));
}

}  // namespace
}  // namespace sp
