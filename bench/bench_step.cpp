// Step benchmark: ms per step (wall and GPU timestamps) and casts per second
// for each backend and ray budget, on one scene. Before timing it checks that
// the backends agree (same indicator and cast counts over a few steps); then
// it warms up and reports the median over several runs.
//
//   bench_step --scene scenes/level.gltf --backends cpu,gpu --budgets 100,500,2500 --steps 300 --runs 5
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "soundpaint/output.h"
#include "soundpaint/simulation.h"

namespace {

struct Options {
  std::string scene = SP_DEFAULT_SCENE;
  std::vector<std::string> backends = {"cpu", "gpu"};
  std::vector<std::uint32_t> budgets = {100, 500, 2500};
  std::uint32_t steps = 300;
  std::uint32_t warmup = 30;
  std::uint32_t runs = 5;
  std::uint32_t bounces = 4;
  unsigned threads = 0;
};

[[noreturn]] void usage(const std::string& problem) {
  std::fprintf(stderr,
               "bench_step: %s\nusage: bench_step [--scene FILE] [--backends cpu,gpu] [--budgets A,B,...]\n"
               "                  [--steps N] [--warmup N] [--runs R] [--bounces B] [--threads T]\n",
               problem.c_str());
  std::exit(2);
}

std::uint32_t to_uint(const std::string& text, const std::string& flag) {
  try {
    std::size_t used = 0;
    unsigned long value = std::stoul(text, &used);
    if (used != text.size() || value > 0xFFFFFFFFul) throw std::invalid_argument(text);
    return static_cast<std::uint32_t>(value);
  } catch (const std::exception&) {
    usage("bad value for " + flag + ": " + text);
  }
}

std::vector<std::string> split(const std::string& list) {
  std::vector<std::string> items;
  std::stringstream stream(list);
  for (std::string item; std::getline(stream, item, ',');) items.push_back(item);
  return items;
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    std::string flag = argv[i];
    if (i + 1 >= argc) usage("missing value for " + flag);
    std::string value = argv[++i];
    if (flag == "--scene") o.scene = value;
    else if (flag == "--backends") o.backends = split(value);
    else if (flag == "--budgets") {
      o.budgets.clear();
      for (const auto& item : split(value)) o.budgets.push_back(to_uint(item, flag));
    } else if (flag == "--steps") o.steps = to_uint(value, flag);
    else if (flag == "--warmup") o.warmup = to_uint(value, flag);
    else if (flag == "--runs") o.runs = to_uint(value, flag);
    else if (flag == "--bounces") o.bounces = to_uint(value, flag);
    else if (flag == "--threads") o.threads = to_uint(value, flag);
    else usage("unknown flag " + flag);
  }
  if (o.steps == 0 || o.runs == 0) usage("--steps and --runs must be > 0");
  for (const auto& b : o.backends)
    if (b != "cpu" && b != "gpu") usage("unknown backend " + b);
  return o;
}

std::unique_ptr<sp::Simulator> make(const sp::Scene& scene, const Options& o, const std::string& backend,
                                    std::uint32_t budget) {
  sp::Config config;
  config.ray_budget = budget;
  config.max_bounces = o.bounces;
  sp::World world = sp::make_world(scene, config).value();
  if (backend == "gpu") return std::move(sp::create_gpu_simulator(std::move(world)).value());
  return std::move(sp::create_cpu_simulator(std::move(world), sp::CpuSettings{o.threads}).value());
}

// The backends must agree before their speeds mean anything.
bool validate(const sp::Scene& scene, const Options& o, std::uint32_t budget) {
  if (o.backends.size() < 2) return true;
  std::uint64_t indicators[2] = {}, casts[2] = {};
  for (int b = 0; b < 2; ++b) {
    auto sim = make(scene, o, o.backends[static_cast<std::size_t>(b)], budget);
    for (int n = 0; n < 10; ++n) sim->step().value();
    auto stats = sim->stats().value();
    indicators[b] = stats.indicators;
    casts[b] = stats.casts;
  }
  auto close = [](std::uint64_t a, std::uint64_t b) {
    return double(a > b ? a - b : b - a) <= 0.001 * double(std::max(a, b)) + 1.0;
  };
  if (close(indicators[0], indicators[1]) && close(casts[0], casts[1])) return true;
  std::fprintf(stderr, "bench_step: backends disagree at budget %u: indicators %llu vs %llu, casts %llu vs %llu\n",
               budget, (unsigned long long)indicators[0], (unsigned long long)indicators[1],
               (unsigned long long)casts[0], (unsigned long long)casts[1]);
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  Options options = parse(argc, argv);
  auto scene = sp::load_scene(options.scene);
  if (!scene) {
    std::fprintf(stderr, "bench_step: %s\n", scene.error().message.c_str());
    return 1;
  }
  unsigned threads = options.threads ? options.threads : std::max(1u, std::thread::hardware_concurrency());
  std::printf("scene %s: %zu triangles, %zu sources; %u bounces; CPU backend on %u threads\n", options.scene.c_str(),
              scene->triangle_count(), scene->sources.size(), options.bounces, threads);
  for (const std::string& backend : options.backends)
    std::printf("%s backend: %s\n", backend.c_str(), make(*scene, options, backend, 1)->device_description().c_str());
  std::printf("%-4s %8s %12s %12s %12s %12s %14s\n", "back", "budget", "ms/step med", "ms/step p99", "gpu ms med",
              "casts/step", "Mcasts/s");
  for (std::uint32_t budget : options.budgets) {
    if (!validate(*scene, options, budget)) return 1;
    for (const std::string& backend : options.backends) {
      std::vector<double> medians, p99s, gpu_medians, rates, casts_per_step;
      for (std::uint32_t run = 0; run < options.runs; ++run) {
        auto sim = make(*scene, options, backend, budget);
        for (std::uint32_t n = 0; n < options.warmup; ++n) sim->step().value();
        std::vector<double> wall, gpu;
        std::uint64_t casts = 0;
        for (std::uint32_t n = 0; n < options.steps; ++n) {
          auto start = std::chrono::steady_clock::now();
          sim->step().value();
          wall.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
          if (auto g = sim->last_gpu_ms()) gpu.push_back(*g);
          casts += sim->last_step_casts();
        }
        double total_ms = 0.0;
        for (double ms : wall) total_ms += ms;
        medians.push_back(sp::median(wall));
        p99s.push_back(sp::percentile(wall, 99.0));
        if (!gpu.empty()) gpu_medians.push_back(sp::median(gpu));
        casts_per_step.push_back(double(casts) / options.steps);
        rates.push_back(total_ms > 0.0 ? double(casts) / total_ms * 1e-3 : 0.0);
      }
      char gpu_text[32] = "-";
      if (!gpu_medians.empty()) std::snprintf(gpu_text, sizeof gpu_text, "%.4f", sp::median(gpu_medians));
      std::printf("%-4s %8u %12.4f %12.4f %12s %12.0f %14.2f\n", backend.c_str(), budget, sp::median(medians),
                  sp::median(p99s), gpu_text, sp::median(casts_per_step), sp::median(rates));
      std::fflush(stdout);
    }
  }
  return 0;
}
