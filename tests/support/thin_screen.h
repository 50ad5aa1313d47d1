// A level where only diffraction at a thin solid's free edge can reach a
// place (issue 38: a glass pane or a thin door, 1 or 2 cm thick, closed like
// any brush): a screen standing on a floor brush, a back wall behind it, a
// source in front. Every face swallows what enters it, so no straight or
// reflected ray reaches the screen's shadow on the back wall; the window
// below gets cues only from rays turned round the screen's free edge.
// Hand-derived; shared by the edge, backend and parity tests.
#pragma once

#include <cmath>

#include <glm/vec3.hpp>

#include "soundpaint/config.h"
#include "soundpaint/scene.h"
#include "soundpaint/simulation.h"
#include "support/scene_builder.h"

namespace sp::test {

// Y up. The screen: x in [-2, 0], y in [0, 2.5], z in [-t/2, t/2]; its
// free upright edges run at x = 0 and x = -2. Brushes, 12 triangles each,
// in scene order: the floor (top at y = 0), the screen, the back wall (its
// front at z = 1.5). They touch but share no edge, so each is a solid of
// its own, as brushes exported from a level editor are.
inline constexpr float kScreenWidth = 2.0f;
inline constexpr float kScreenHeight = 2.5f;
inline constexpr float kBackWallZ = 1.5f;
inline constexpr glm::vec3 kScreenSource(-0.5f, 1.25f, -0.5f);

inline Scene thin_screen_level(float thickness) {
  Scene scene;
  add_box(scene, {-6, -0.2f, -6}, {6, 0, 6}, "floor");
  add_box(scene, {-kScreenWidth, 0, -0.5f * thickness}, {0, kScreenHeight, 0.5f * thickness}, "screen");
  add_box(scene, {-6, 0, kBackWallZ}, {6, 4, kBackWallZ + 0.2f}, "wall");
  scene.sources.push_back(source_at(kScreenSource));
  return scene;
}

// Nothing reflects (rho = 0) and matter costs 1000 per metre, so a ray that
// enters a face, even the 1 cm screen's, dies inside it.
inline Config thin_screen_config(bool diffraction) {
  Config config;
  for (const char* layer : {"floor", "screen", "wall"}) config.layers[layer] = {0.0f, 1000.0f};
  config.listener_position = glm::vec3(0.5f, 1.25f, 1.0f);  // behind the screen, in its shadow
  config.ray_budget = 3000;
  config.max_bounces = 2;
  config.diffraction.enabled = diffraction;
  return config;
}

// Whether `ind` is a hit on the back wall's front in the window x in
// (0.05, 1.2), y in (0.05, 2.4). The source sees none of it: the line from
// the source to a point there crosses the screen's front (z = -t/2) at the
// fraction s = (0.5 - t/2) / 2 <= 0.2475 of its length, at x <= -0.5 +
// 0.2475 * 1.7 = -0.079 and y in [0.95, 1.54], inside the face, 8 cm from
// its free edge. The shadow's boundary on the wall is at x = -0.5 + 0.5 / s,
// 1.52 (1 cm) or 1.54 (2 cm). A ray struck on the front near its free edge
// x = 0 heads less to the right than the line from the source through the
// edge (it struck left of the edge) and turns further left, into the
// shadow, while a turn past the screen's end face (x = 0) is absorbed: it
// lands between x = 0 and the boundary, in this window when low enough.
// One turned at the top edge keeps rising (lands above y = 2.5), one at the
// far edge x = -2 lands left of it.
inline bool in_free_edge_shadow(const Indicator& ind) {
  const Vec3 p = ind.position;
  return ind.kind == kIndicatorHit && std::abs(p.z - kBackWallZ) < 1e-3f && p.x > 0.05f && p.x < 1.2f && p.y > 0.05f &&
         p.y < 2.4f;
}

// Whether `ind` is a hit on the back wall the source sees directly, right
// of the shadow's boundary (x > 1.54): cues there with diffraction on or off.
inline bool in_direct_sight(const Indicator& ind) {
  const Vec3 p = ind.position;
  return ind.kind == kIndicatorHit && std::abs(p.z - kBackWallZ) < 1e-3f && p.x > 1.8f && p.y > 0.05f && p.y < 2.4f;
}

}  // namespace sp::test
