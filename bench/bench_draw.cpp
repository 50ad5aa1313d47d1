// Indicator-pass benchmark: GPU time of the indicator pass alone, for rings
// of N synthetic indicators lying on the level's surfaces in front of the
// scene camera. Two measures, both from timestamp queries: around the pass's
// one vkCmdDrawIndirect ("pass"), and the whole frame's GPU time minus that
// of a frame with an empty ring ("frame - empty"). They agree on GPUs that
// finish a draw before the next timestamp; lavapipe bins draws and
// rasterises them later, so there only the second is the pass's cost.
// Before timing it checks that the indicators change the picture; then it
// warms up and reports medians over several frames.
//
//   bench_draw --scene scenes/level.gltf --counts 20000,200000 --width 1280 --height 720 --runs 9
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <glm/geometric.hpp>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "render/host_indicators.h"
#include "render/renderer.h"
#include "render/view_camera.h"
#include "io/output.h"
#include "sim/world_geometry.h"
#include "soundpaint/simulation.h"
#include "sp_types.h"
#include "vk/context.h"

namespace {

struct Options {
  std::string scene = SP_DEFAULT_SCENE;
  std::vector<std::uint32_t> counts = {20000, 200000};
  std::uint32_t width = 1280;
  std::uint32_t height = 720;
  std::uint32_t warmup = 3;
  std::uint32_t runs = 9;
  float radius = 15.0f;  // metres around the camera where indicators are placed
  std::uint32_t seed = 1;
};

[[noreturn]] void usage(const std::string& problem) {
  std::fprintf(stderr,
               "bench_draw: %s\nusage: bench_draw [--scene FILE] [--counts A,B,...] [--width W] [--height H]\n"
               "                  [--warmup N] [--runs R] [--radius METRES] [--seed S]\n",
               problem.c_str());
  std::exit(2);
}

std::uint32_t to_uint(const std::string& text, const std::string& flag) {
  try {
    std::size_t used = 0;
    const unsigned long value = std::stoul(text, &used);
    if (used != text.size() || value > 0xFFFFFFFFul) throw std::invalid_argument(text);
    return static_cast<std::uint32_t>(value);
  } catch (const std::exception&) {
    usage("bad value for " + flag + ": " + text);
  }
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (i + 1 >= argc) usage("missing value for " + flag);
    const std::string value = argv[++i];
    if (flag == "--scene") {
      o.scene = value;
    } else if (flag == "--counts") {
      o.counts.clear();
      std::stringstream list(value);
      for (std::string item; std::getline(list, item, ',');) o.counts.push_back(to_uint(item, flag));
    } else if (flag == "--width") {
      o.width = to_uint(value, flag);
    } else if (flag == "--height") {
      o.height = to_uint(value, flag);
    } else if (flag == "--warmup") {
      o.warmup = to_uint(value, flag);
    } else if (flag == "--runs") {
      o.runs = to_uint(value, flag);
    } else if (flag == "--radius") {
      o.radius = static_cast<float>(to_uint(value, flag));
    } else if (flag == "--seed") {
      o.seed = to_uint(value, flag);
    } else {
      usage("unknown flag " + flag);
    }
  }
  if (o.runs == 0 || o.width == 0 || o.height == 0 || o.counts.empty())
    usage("--runs, --width, --height, --counts must be > 0");
  return o;
}

// Indicators as the simulation would leave them: on surfaces (area-weighted
// over triangles near and in front of the camera), facing the camera's
// side, energies and intensities spread out, spread over the level's
// sources (their shapes) in 15 colours, all born at step 0 (drawn 6 steps
// later: faded in, not yet faded out).
std::vector<sp::shader::Indicator> synthetic_indicators(const sp::World& world, const sp::draw::ViewCamera& camera,
                                                        std::uint32_t count, float radius, std::uint32_t seed) {
  std::vector<const sp::BvhTriangle*> candidates;
  std::vector<double> areas;
  for (const sp::BvhTriangle& t : world.geometry->bvh.triangles) {
    const glm::vec3 centre = (t.v0 + t.v1 + t.v2) / 3.0f;
    const glm::vec3 to = centre - camera.eye;
    if (glm::length(to) > radius || glm::dot(to, camera.forward) <= 0.0f) continue;
    candidates.push_back(&t);
    areas.push_back(0.5 * double(glm::length(glm::cross(t.v1 - t.v0, t.v2 - t.v0))));
  }
  if (candidates.empty()) usage("no surface within --radius in front of the camera");
  std::mt19937 rng(seed);
  std::discrete_distribution<std::size_t> pick(areas.begin(), areas.end());
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<sp::shader::Indicator> indicators(count);
  for (std::uint32_t i = 0; i < count; ++i) {
    const sp::BvhTriangle& t = *candidates[pick(rng)];
    float a = unit(rng), b = unit(rng);
    if (a + b > 1.0f) a = 1.0f - a, b = 1.0f - b;
    sp::shader::Indicator& ind = indicators[i];
    ind.position = t.v0 + a * (t.v1 - t.v0) + b * (t.v2 - t.v0);
    ind.normal = glm::dot(t.normal, camera.eye - ind.position) >= 0.0f ? t.normal : -t.normal;
    ind.energy = 0.2f + 0.8f * unit(rng);
    ind.size = world.config.indicator_size * ind.energy;
    ind.intensity = 0.3f + 0.7f * unit(rng);
    const std::uint32_t source = i % std::max<std::uint32_t>(1, std::uint32_t(world.sources.size()));
    const float hue = float(i % 15) / 15.0f * 6.0f;
    ind.color = glm::clamp(
        glm::vec3(std::abs(hue - 3.0f) - 1.0f, 2.0f - std::abs(hue - 2.0f), 2.0f - std::abs(hue - 4.0f)), 0.0f, 1.0f);
    ind.source_id = source;
    ind.kind = SP_INDICATOR_HIT;
    ind.bounces = i % 3;  // a third of them direct sound, drawn larger
    ind.step = 0;
    // Travelling into the surface at an angle: a comet's tail on every spot.
    const glm::vec3 along = glm::cross(ind.normal, glm::vec3(0.3f, 1.0f, 0.2f));
    ind.dir = glm::normalize(glm::length(along) > 1e-3f ? along - ind.normal : -ind.normal);
  }
  return indicators;
}

std::size_t differing_pixels(const sp::draw::RgbaImage& a, const sp::draw::RgbaImage& b) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.pixels.size(); i += 4)
    n += a.pixels[i] != b.pixels[i] || a.pixels[i + 1] != b.pixels[i + 1] || a.pixels[i + 2] != b.pixels[i + 2];
  return n;
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = parse(argc, argv);
  auto scene = sp::load_scene(options.scene);
  if (!scene) {
    std::fprintf(stderr, "bench_draw: %s\n", scene.error().message.c_str());
    return 1;
  }
  auto world = sp::make_world(*scene, sp::Config{});
  auto context = sp::vk::Context::create();
  if (!world || !context) {
    std::fprintf(stderr, "bench_draw: %s\n", (!world ? world.error() : context.error()).message.c_str());
    return 1;
  }
  sp::vk::Context& vk = **context;
  sp::draw::RenderSettings settings;
  settings.width = options.width;
  settings.height = options.height;
  sp::draw::Renderer renderer(vk, *world, settings);
  sp::draw::HostIndicators ring(vk);
  const sp::draw::ViewCamera camera =
      sp::draw::make_view_camera(scene->camera, *world, {}, options.width, options.height);
  // Drawn 6 steps after their birth (0.1 s): faded in, not yet faded out.
  const std::uint64_t steps_run = 7;

  std::printf("scene %s: %zu triangles; %ux%u; indicators within %.0f m in front of the scene camera\n",
              options.scene.c_str(), scene->triangle_count(), options.width, options.height, double(options.radius));
  std::printf("device: %s\n", vk.description().c_str());

  // Medians over `runs` frames of the current ring, after the warm-up.
  struct Sample {
    double indicator_ms, frame_ms, wall_ms;
  };
  auto measure = [&]() {
    for (std::uint32_t n = 0; n < options.warmup; ++n) renderer.render(camera, ring.view(), *world, steps_run);
    std::vector<double> indicator_ms, frame_ms, wall_ms;
    for (std::uint32_t run = 0; run < options.runs; ++run) {
      const auto start = std::chrono::steady_clock::now();
      renderer.render(camera, ring.view(), *world, steps_run);
      wall_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
      if (auto t = renderer.last_timings()) {
        indicator_ms.push_back(t->indicator_ms);
        frame_ms.push_back(t->frame_ms);
      }
    }
    return Sample{sp::median(indicator_ms), sp::median(frame_ms), sp::median(wall_ms)};
  };

  ring.upload({});
  const sp::draw::RgbaImage empty = renderer.render(camera, ring.view(), *world, steps_run);
  if (!renderer.last_timings()) std::printf("(no timestamp queries on this queue: GPU columns are 0)\n");
  const Sample base = measure();
  std::printf("empty ring: frame %.3f ms GPU, %.3f ms wall (median of %u)\n", base.frame_ms, base.wall_ms,
              options.runs);
  std::printf("%10s %16s %16s %16s %14s %14s\n", "indicators", "pass gpu ms", "frame gpu ms", "frame - empty",
              "frame wall ms", "M ind./s");
  for (const std::uint32_t count : options.counts) {
    ring.upload(synthetic_indicators(*world, camera, count, options.radius, options.seed));
    // The indicators must show before their cost means anything.
    const std::size_t changed = differing_pixels(empty, renderer.render(camera, ring.view(), *world, steps_run));
    if (count > 0 && changed == 0) {
      std::fprintf(stderr, "bench_draw: %u indicators left the picture unchanged\n", count);
      return 1;
    }
    const Sample s = measure();
    // What the indicators add to a whole frame: on lavapipe, which rasterises
    // after the pass's timestamps, this is the pass's real cost.
    const double added = s.frame_ms - base.frame_ms;
    std::printf("%10u %16.3f %16.3f %16.3f %14.3f %14.2f\n", count, s.indicator_ms, s.frame_ms, added, s.wall_ms,
                added > 0.0 ? double(count) / added * 1e-3 : 0.0);
    std::fflush(stdout);
  }
  return 0;
}
