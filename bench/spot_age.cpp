// How long drawn spots actually live (issue 11): runs a scene for N steps
// on the CPU backend and reports, for the live indicators the display would
// draw after the last step, their ages against the lifetime, how many steps
// of the last lifetime are represented, and how many spots each step keeps.
// Not a timing: a measure of the ring's behaviour at a given budget.
//
//   spot_age --scene ../shared/levels/oa_dm1-brushes.glb --steps 120 --capacities 4000,20000 --rays 500
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "sim/indicator_ring.h"
#include "soundpaint/simulation.h"
#include "sp_types.h"

namespace {

struct Options {
  std::string scene = SP_DEFAULT_SCENE;
  std::uint32_t steps = 120;
  std::uint32_t rays = 500;
  std::vector<std::uint32_t> capacities = {4000, 20000};
};

[[noreturn]] void usage(const std::string& problem) {
  std::fprintf(stderr, "spot_age: %s\nusage: spot_age [--scene FILE] [--steps N] [--rays R] [--capacities A,B,...]\n",
               problem.c_str());
  std::exit(2);
}

std::uint32_t to_uint(const std::string& text, const std::string& flag) {
  char* end = nullptr;
  const unsigned long value = std::strtoul(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || value == 0 || value > 100000000ul) usage("bad value for " + flag + ": " + text);
  return static_cast<std::uint32_t>(value);
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (i + 1 >= argc) usage(flag + " needs a value");
    const std::string value = argv[++i];
    if (flag == "--scene") {
      o.scene = value;
    } else if (flag == "--steps") {
      o.steps = to_uint(value, flag);
    } else if (flag == "--rays") {
      o.rays = to_uint(value, flag);
    } else if (flag == "--capacities") {
      o.capacities.clear();
      std::stringstream list(value);
      for (std::string item; std::getline(list, item, ',');) o.capacities.push_back(to_uint(item, flag));
    } else {
      usage("unknown option " + flag);
    }
  }
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = parse(argc, argv);
  auto scene = sp::load_scene(options.scene);
  if (!scene) {
    std::fprintf(stderr, "spot_age: %s\n", scene.error().message.c_str());
    return 1;
  }
  std::printf("scene %s, %u rays a step, %u steps\n", options.scene.c_str(), options.rays, options.steps);
  std::printf("%10s %8s %10s %10s %10s %10s %14s %12s\n", "capacity", "quota", "created", "live", "max age s",
              "median s", "steps shown", "min per step");
  for (std::uint32_t capacity : options.capacities) {
    sp::Config config;
    config.ray_budget = options.rays;
    config.max_indicators = capacity;
    auto world = sp::make_world(*scene, config);
    if (!world) {
      std::fprintf(stderr, "spot_age: %s\n", world.error().message.c_str());
      return 1;
    }
    auto sim = sp::create_cpu_simulator(std::move(*world)).value();
    for (std::uint32_t n = 0; n < options.steps; ++n) sim->step().value();
    const std::vector<sp::Indicator> live = sim->live_indicators().value();
    const std::uint32_t now = options.steps - 1;
    std::vector<double> ages;
    std::map<std::uint32_t, std::size_t> per_step;
    for (const sp::Indicator& ind : live) {
      ages.push_back(double(now - ind.step) * config.dt);
      per_step[ind.step] += 1;
    }
    std::sort(ages.begin(), ages.end());
    std::size_t fewest = live.empty() ? 0 : live.size();
    for (const auto& [step, count] : per_step) fewest = std::min(fewest, count);
    const auto lifetime_steps = static_cast<std::uint32_t>(sp::display_lifetime(config) / config.dt);
    std::printf("%10u %8u %10llu %10zu %10.3f %10.3f %8zu of %3u %12zu\n", capacity, sp::ring_quota(config),
                static_cast<unsigned long long>(sim->stats().value().indicators), live.size(),
                ages.empty() ? 0.0 : ages.back(), ages.empty() ? 0.0 : ages[ages.size() / 2], per_step.size(),
                lifetime_steps, fewest);
  }
  return 0;
}
