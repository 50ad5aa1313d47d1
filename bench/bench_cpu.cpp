// CPU backend benchmark: ms per step and casts per second on a scene for a
// list of ray budgets. Scenarios come from flags; results are medians over
// several runs after a warm-up, printed as a table and optionally as JSON.
//
//   bench_cpu --scene scenes/level.gltf --budgets 100,500,2500 --steps 300 --runs 5
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstdio>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "soundpaint/output.h"
#include "soundpaint/simulation.h"

namespace {

struct Options {
  std::string scene = SP_DEFAULT_SCENE;
  std::vector<std::uint32_t> budgets = {100, 500, 2500};
  std::uint32_t steps = 300;
  std::uint32_t warmup = 30;
  std::uint32_t runs = 5;
  std::uint32_t bounces = 4;
  unsigned threads = 0;
};

[[noreturn]] void usage(const char* problem) {
  std::fprintf(stderr,
               "bench_cpu: %s\nusage: bench_cpu [--scene FILE] [--budgets A,B,...] [--steps N] [--warmup N]\n"
               "                 [--runs R] [--bounces B] [--threads T]\n",
               problem);
  std::exit(2);
}

std::uint32_t to_uint(const std::string& text, const char* flag) {
  try {
    std::size_t used = 0;
    unsigned long value = std::stoul(text, &used);
    if (used != text.size() || value > 0xFFFFFFFFul) throw std::invalid_argument(text);
    return static_cast<std::uint32_t>(value);
  } catch (const std::exception&) {
    usage((std::string("bad value for ") + flag + ": " + text).c_str());
  }
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    std::string flag = argv[i];
    if (i + 1 >= argc) usage(("missing value for " + flag).c_str());
    std::string value = argv[++i];
    if (flag == "--scene") {
      o.scene = value;
    } else if (flag == "--budgets") {
      o.budgets.clear();
      std::stringstream list(value);
      for (std::string item; std::getline(list, item, ',');) o.budgets.push_back(to_uint(item, "--budgets"));
    } else if (flag == "--steps") {
      o.steps = to_uint(value, "--steps");
    } else if (flag == "--warmup") {
      o.warmup = to_uint(value, "--warmup");
    } else if (flag == "--runs") {
      o.runs = to_uint(value, "--runs");
    } else if (flag == "--bounces") {
      o.bounces = to_uint(value, "--bounces");
    } else if (flag == "--threads") {
      o.threads = to_uint(value, "--threads");
    } else {
      usage(("unknown flag " + flag).c_str());
    }
  }
  if (o.steps == 0 || o.runs == 0) usage("--steps and --runs must be > 0");
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  Options options = parse(argc, argv);
  auto scene = sp::load_scene(options.scene);
  if (!scene) {
    std::fprintf(stderr, "bench_cpu: %s\n", scene.error().message.c_str());
    return 1;
  }
  unsigned threads = options.threads ? options.threads : std::max(1u, std::thread::hardware_concurrency());
  std::printf("scene %s: %zu triangles, %zu sources; CPU backend, %u threads, %u bounces\n", options.scene.c_str(),
              scene->triangle_count(), scene->sources.size(), threads, options.bounces);
  std::printf("%8s %14s %14s %14s %16s\n", "budget", "ms/step med", "ms/step p99", "casts/step", "Mcasts/s med");
  for (std::uint32_t budget : options.budgets) {
    std::vector<double> run_medians, run_p99s, run_rates, run_casts;
    for (std::uint32_t run = 0; run < options.runs; ++run) {
      sp::Config config;
      config.ray_budget = budget;
      config.max_bounces = options.bounces;
      auto world = sp::make_world(*scene, config);
      if (!world) {
        std::fprintf(stderr, "bench_cpu: %s\n", world.error().message.c_str());
        return 1;
      }
      auto sim = sp::create_cpu_simulator(std::move(*world), sp::CpuSettings{threads}).value();
      for (std::uint32_t n = 0; n < options.warmup; ++n) sim->step().value();
      std::vector<double> ms;
      std::uint64_t casts = 0;
      double total_ms = 0.0;
      for (std::uint32_t n = 0; n < options.steps; ++n) {
        auto start = std::chrono::steady_clock::now();
        sim->step().value();
        double elapsed = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        ms.push_back(elapsed);
        total_ms += elapsed;
        casts += sim->last_step_casts();
      }
      run_medians.push_back(sp::median(ms));
      run_p99s.push_back(sp::percentile(ms, 99.0));
      run_casts.push_back(double(casts) / options.steps);
      run_rates.push_back(total_ms > 0.0 ? double(casts) / total_ms * 1e-3 : 0.0);
    }
    std::printf("%8u %14.4f %14.4f %14.0f %16.2f\n", budget, sp::median(run_medians), sp::median(run_p99s),
                sp::median(run_casts), sp::median(run_rates));
  }
  return 0;
}
