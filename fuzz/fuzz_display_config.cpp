// Fuzz target: the config's `display` and `diffraction` objects, as far as
// they reach (configs come from players). Any input must give a Config or a
// one-line error. A config that parses is then used: a world of a small
// fixed level with the config's sources, its table of sources as the draw
// sees it (whose hidden and shape flags must follow the display settings),
// and one CPU step with diffraction as configured, at a small ray budget.
// A slow input is a finding too: the display's lists and the sources must
// cost their sum, not their product (issue 38).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "draw/display_frame.h"
#include "draw/display_sources.h"
#include "soundpaint/config.h"
#include "soundpaint/scene.h"
#include "soundpaint/simulation.h"
#include "sp_draw_types.h"

namespace {

// Bounds on the work one input buys, well above what a test needs: a step
// costs in rays times bounces, and the ring in indicators.
constexpr std::uint32_t kMaxRays = 256;
constexpr std::uint32_t kMaxBounces = 8;
constexpr std::uint32_t kMaxIndicators = 4096;

void one_line(const sp::Error& error) {
  if (error.message.find('\n') != std::string::npos) __builtin_trap();
}

void add_box(sp::Scene& scene, sp::Vec3 lo, sp::Vec3 hi) {
  const sp::Vec3 c[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z},
                         {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
  static constexpr int kFaces[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                                        {3, 6, 2}, {3, 7, 6}, {0, 4, 7}, {0, 7, 3}, {1, 2, 6}, {1, 6, 5}};
  for (const auto& face : kFaces) {
    for (const int corner : face) scene.vertices.push_back(c[corner]);
    scene.triangle_layers.push_back(0);
  }
}

// A floor with a pillar standing on it and a free panel: convex edges, free
// edges and edges buried in the floor, for diffraction to find.
sp::Scene small_level() {
  sp::Scene scene;
  scene.layer_names = {"concrete"};
  add_box(scene, {-10, -0.3f, -10}, {10, 0, 10});
  add_box(scene, {-0.5f, 0, -0.5f}, {0.5f, 3, 0.5f});
  for (const sp::Vec3& v : {sp::Vec3{2, 0.5f, -2}, sp::Vec3{4, 0.5f, -2}, sp::Vec3{4, 2.5f, -2}, sp::Vec3{2, 0.5f, -2},
                            sp::Vec3{4, 2.5f, -2}, sp::Vec3{2, 2.5f, -2}})
    scene.vertices.push_back(v);
  scene.triangle_layers.insert(scene.triangle_layers.end(), 2, 0);
  scene.sources.push_back(sp::SourceDesc{});
  scene.sources.back().position = {3, 1, 3};
  scene.sources.back().category = "footsteps";
  return scene;
}

// The draw's table must hide exactly the sources whose category the
// display hides, and give every source a shape.
void check_display_sources(const sp::World& world) {
  const sp::DisplaySettings& display = world.config.display;
  const std::set<std::string, std::less<>> hidden(display.hide_categories.begin(), display.hide_categories.end());
  const std::vector<sp::shader::DisplaySource> table = sp::draw::make_display_sources(world, display);
  if (table.size() != world.sources.size()) __builtin_trap();
  for (std::size_t id = 0; id < table.size(); ++id) {
    const std::uint32_t flags = table[id].shape_flags;
    if (((flags & SP_SOURCE_HIDDEN) != 0) != hidden.contains(world.sources[id].category)) __builtin_trap();
    if ((flags & ~(SP_SOURCE_HIDDEN | SP_SOURCE_PRESENT)) >= sp::kShapeCount) __builtin_trap();
  }
  const sp::draw::DisplayFrame frame = sp::draw::DisplayFrame::from(world, 1, display, true);
  if (frame.source_count != table.size()) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  sp::Result<sp::Config> parsed = sp::parse_config(text, "fuzz.json");
  if (!parsed.ok()) {
    one_line(parsed.error());
    return 0;
  }
  sp::Config config = *parsed;
  config.ray_budget = std::min(config.ray_budget, kMaxRays);
  config.max_bounces = std::min(config.max_bounces, kMaxBounces);
  config.max_indicators = std::min(config.max_indicators, kMaxIndicators);
  config.listener_position = sp::Vec3{0, 1.5f, 3};  // in the small level, whatever the config says
  // Embree is a build option; the built-in traversal is in every build.
  config.cpu_traversal = sp::CpuTraversal::Soundpaint;
  sp::BvhBuildSettings build;
  build.threads = 1;
  sp::Result<sp::World> world = sp::make_world(small_level(), config, build);
  if (!world.ok()) {
    one_line(world.error());
    return 0;
  }
  check_display_sources(*world);
  sp::CpuSettings cpu;
  cpu.threads = 1;
  auto simulator = sp::create_cpu_simulator(std::move(*world), cpu);
  if (!simulator.ok()) {
    one_line(simulator.error());
    return 0;
  }
  const sp::Result<bool> stepped = (*simulator)->step();
  if (!stepped.ok()) one_line(stepped.error());
  return 0;
}
