#include "bench_common.h"

#include "bvh/wide_bvh.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <thread>

#include <glm/glm.hpp>

#include "generated_level.h"
#include "io/output.h"

namespace spbench {

void select_cpu_walk(const CommandLine& cli, const std::string& name) {
  if (name == "best") return;
  sp::WideWalk walk = sp::WideWalk::Baseline;
  if (name == "avx512") {
    walk = sp::WideWalk::Avx512;
  } else if (name == "avx512-8wide") {
    walk = sp::WideWalk::Avx512Wide8;
  } else if (name != "baseline") {
    cli.fail("--cpu-walk must be best, baseline, avx512 or avx512-8wide, not " + name);
  }
  if (!sp::select_wide_walk(walk)) cli.fail("--cpu-walk " + name + ": this build or this CPU does not have it");
}

const char* cpu_walk_name() { return sp::wide_walk_name(sp::selected_wide_walk()); }

// ---------------------------------------------------------------------------
// Command line

void CommandLine::fail(const std::string& problem) const {
  std::fprintf(stderr, "%s: %s\n%s", program_.c_str(), problem.c_str(), usage_.c_str());
  std::exit(2);
}

void CommandLine::parse(int argc, char** argv,
                        const std::function<bool(const std::string&, const std::string&)>& handle) const {
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag == "--help" || flag == "-h") {
      std::printf("%s", usage_.c_str());
      std::exit(0);
    }
    if (i + 1 >= argc) fail("missing value for " + flag);
    const std::string value = argv[++i];
    if (!handle(flag, value)) fail("unknown flag " + flag);
  }
}

std::uint32_t CommandLine::to_uint(const std::string& text, const std::string& flag) const {
  try {
    std::size_t used = 0;
    const unsigned long long value = std::stoull(text, &used);
    if (used == text.size() && value <= 0xFFFFFFFFull && text.find('-') == std::string::npos)
      return static_cast<std::uint32_t>(value);
  } catch (const std::exception&) {
  }
  fail("bad value for " + flag + ": " + text);
}

double CommandLine::to_double(const std::string& text, const std::string& flag) const {
  try {
    std::size_t used = 0;
    const double value = std::stod(text, &used);
    if (used == text.size() && std::isfinite(value) && value >= 0.0) return value;
  } catch (const std::exception&) {
  }
  fail("bad value for " + flag + ": " + text);
}

std::vector<std::uint32_t> CommandLine::to_uint_list(const std::string& text, const std::string& flag) const {
  std::vector<std::uint32_t> values;
  for (const std::string& item : split(text)) values.push_back(to_uint(item, flag));
  return values;
}

std::vector<std::string> CommandLine::split(const std::string& list) {
  std::vector<std::string> items;
  std::stringstream stream(list);
  for (std::string item; std::getline(stream, item, ',');)
    if (!item.empty()) items.push_back(item);
  return items;
}

int guarded_main(const CommandLine& cli, const std::function<int()>& body) {
  try {
    return body();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", cli.program().c_str(), e.what());
    return 1;
  }
}

unsigned resolve_threads(unsigned requested) {
  return requested ? requested : std::max(1u, std::thread::hardware_concurrency());
}

std::string host_description() {
  std::string model = "unknown CPU";
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);) {
    if (line.rfind("model name", 0) == 0 && line.find(':') != std::string::npos) {
      model = line.substr(line.find(':') + 2);
      break;
    }
  }
  return model + ", " + std::to_string(std::thread::hardware_concurrency()) + " hardware threads";
}

// ---------------------------------------------------------------------------
// Scenes

sp::Scene load_scene_or_exit(const CommandLine& cli, const std::string& spec) {
  if (spec.rfind("gen:", 0) == 0) return generate_level(cli.to_uint(spec.substr(4), "--scene gen:N"));
  auto scene = sp::load_scene(spec);
  if (!scene) {
    std::fprintf(stderr, "%s: %s\n", cli.program().c_str(), scene.error().message.c_str());
    std::exit(1);
  }
  return std::move(scene).value();
}

Pattern parse_pattern(const CommandLine& cli, const std::string& name) {
  if (name == "scene") return Pattern::Scene;
  if (name == "paper") return Pattern::Paper;
  if (name == "burst") return Pattern::Burst;
  cli.fail("unknown pattern " + name);
}

const char* pattern_name(Pattern pattern) {
  switch (pattern) {
    case Pattern::Scene:
      return "scene";
    case Pattern::Paper:
      return "paper";
    case Pattern::Burst:
      return "burst";
  }
  return "?";
}

void apply_pattern(sp::Scene& scene, Pattern pattern, double dt) {
  if (pattern == Pattern::Scene) return;
  const double count = static_cast<double>(scene.sources.size());
  for (std::size_t i = 0; i < scene.sources.size(); ++i) {
    sp::SourceDesc& source = scene.sources[i];
    source.interval = 0.25;
    source.duration = pattern == Pattern::Paper ? 0.1 : dt;
    source.phase = 0.25 * static_cast<double>(i) / count;
  }
}

// ---------------------------------------------------------------------------
// Simulators and the frame loop

sp::Result<std::unique_ptr<sp::Simulator>> make_simulator(const sp::World& world, const std::string& backend,
                                                          unsigned threads) {
  if (backend == "gpu") return sp::create_gpu_simulator(world);
  return sp::create_cpu_simulator(world, sp::CpuSettings{threads});
}

std::vector<BackendInfo> usable_backends(const sp::World& world, const std::vector<std::string>& backends,
                                         unsigned threads) {
  std::vector<BackendInfo> usable;
  for (const std::string& backend : backends) {
    auto sim = make_simulator(world, backend, threads);
    if (sim) {
      usable.push_back({backend, (*sim)->device_description()});
      std::printf("%s backend: %s\n", backend.c_str(), usable.back().device.c_str());
    } else {
      std::printf("%s backend: not available (%s)\n", backend.c_str(), sim.error().message.c_str());
    }
  }
  return usable;
}

std::vector<std::string> names(const std::vector<BackendInfo>& backends) {
  std::vector<std::string> result;
  for (const BackendInfo& backend : backends) result.push_back(backend.name);
  return result;
}

glm::vec3 player_position(glm::vec3 centre, std::uint64_t frame, double dt) {
  const double angle = 2.0 * std::numbers::pi * static_cast<double>(frame) * dt / 10.0;
  return centre + glm::vec3(static_cast<float>(std::cos(angle)), 0.0f, static_cast<float>(std::sin(angle)));
}

void run_frame(sp::Simulator& sim, glm::vec3 centre) {
  sim.set_listener(player_position(centre, sim.steps_run(), sim.world().config.dt)).value();
  sim.step().value();
}

std::string backends_disagree(const sp::World& world, const std::vector<std::string>& backends, unsigned threads,
                              std::uint32_t steps) {
  if (backends.size() < 2 || steps == 0) return {};
  std::vector<sp::SimulationStats> totals;
  for (const std::string& backend : backends) {
    auto sim = make_simulator(world, backend, threads).value();
    for (std::uint32_t n = 0; n < steps; ++n) run_frame(*sim, world.listener);
    totals.push_back(sim->stats().value());
  }
  auto close = [](std::uint64_t a, std::uint64_t b) {
    return static_cast<double>(a > b ? a - b : b - a) <= 0.001 * static_cast<double>(std::max(a, b)) + 1.0;
  };
  std::string problems;
  for (std::size_t b = 1; b < backends.size(); ++b) {
    const sp::SimulationStats &x = totals[0], &y = totals[b];
    auto compare = [&](const char* what, std::uint64_t u, std::uint64_t v) {
      if (!close(u, v))
        problems += std::string(problems.empty() ? "" : "; ") + what + " " + backends[0] + " " + std::to_string(u) +
                    " vs " + backends[b] + " " + std::to_string(v);
    };
    compare("indicators", x.indicators, y.indicators);
    compare("casts", x.casts, y.casts);
    compare("rays emitted", x.rays_emitted, y.rays_emitted);
  }
  return problems;
}

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Keeps the baseline loop's work from being optimised away.
volatile float g_sink = 0.0f;

}  // namespace

LoopRun run_frame_loop(sp::Simulator& sim, const LoopSettings& settings) {
  const glm::vec3 centre = sim.world().listener;
  const double dt = sim.world().config.dt;
  const double limit_ms = settings.max_seconds * 1000.0;

  const auto warmup_start = Clock::now();
  for (std::uint32_t n = 0; n < settings.warmup; ++n) {
    run_frame(sim, centre);
    if (limit_ms > 0.0 && ms_since(warmup_start) > limit_ms / 5.0) break;
  }

  LoopRun run;
  const sp::SimulationStats before = sim.stats().value();
  const auto measure_start = Clock::now();
  for (std::uint32_t n = 0; n < settings.steps; ++n) {
    const auto start = Clock::now();
    run_frame(sim, centre);
    run.wall_ms.push_back(ms_since(start));
    if (auto gpu = sim.last_gpu_ms()) run.gpu_ms.push_back(*gpu);
    run.casts += sim.last_step_casts();
    if (limit_ms > 0.0 && ms_since(measure_start) > limit_ms) break;
  }
  const sp::SimulationStats after = sim.stats().value();
  run.rays_emitted = after.rays_emitted - before.rays_emitted;
  run.indicators = after.indicators - before.indicators;

  // The same frame loop without soundpaint: the host's own bookkeeping.
  for (std::uint64_t frame = 0; frame < run.wall_ms.size(); ++frame) {
    const auto start = Clock::now();
    g_sink = g_sink + player_position(centre, frame, dt).x;
    run.baseline_ms.push_back(ms_since(start));
  }
  return run;
}

LoopSummary summarize(const std::vector<LoopRun>& runs) {
  LoopSummary s;
  s.runs = runs.size();
  std::vector<double> medians, p99s, gpu_medians, gpu_p99s, baselines, casts_per_step, rates, rays, indicators;
  for (const LoopRun& run : runs) {
    if (run.wall_ms.empty()) continue;
    const double steps = static_cast<double>(run.wall_ms.size());
    s.steps += run.wall_ms.size();
    medians.push_back(sp::median(run.wall_ms));
    p99s.push_back(sp::percentile(run.wall_ms, 99.0));
    if (!run.gpu_ms.empty()) {
      gpu_medians.push_back(sp::median(run.gpu_ms));
      gpu_p99s.push_back(sp::percentile(run.gpu_ms, 99.0));
    }
    baselines.push_back(sp::median(run.baseline_ms));
    double total_ms = 0.0;
    for (double ms : run.wall_ms) total_ms += ms;
    rates.push_back(total_ms > 0.0 ? static_cast<double>(run.casts) / total_ms * 1e3 : 0.0);
    casts_per_step.push_back(static_cast<double>(run.casts) / steps);
    rays.push_back(static_cast<double>(run.rays_emitted) / steps);
    indicators.push_back(static_cast<double>(run.indicators) / steps);
  }
  if (medians.empty()) return s;
  s.ms_median = sp::median(medians);
  s.ms_p99 = sp::median(p99s);
  if (!gpu_medians.empty()) {
    s.gpu_ms_median = sp::median(gpu_medians);
    s.gpu_ms_p99 = sp::median(gpu_p99s);
  }
  s.baseline_ms_median = sp::median(baselines);
  s.overhead_ms = s.ms_median - s.baseline_ms_median;
  s.casts_per_step = sp::median(casts_per_step);
  s.casts_per_second = sp::median(rates);
  s.rays_per_step = sp::median(rays);
  s.indicators_per_step = sp::median(indicators);
  return s;
}

Json to_json(const LoopSummary& s) {
  auto optional_number = [](std::optional<double> value) { return value ? Json(*value) : Json(nullptr); };
  return Json{{"runs", s.runs},
              {"steps_measured", s.steps},
              {"ms_per_step_median", s.ms_median},
              {"ms_per_step_p99", s.ms_p99},
              {"gpu_ms_per_step_median", optional_number(s.gpu_ms_median)},
              {"gpu_ms_per_step_p99", optional_number(s.gpu_ms_p99)},
              {"baseline_ms_median", s.baseline_ms_median},
              {"overhead_ms", s.overhead_ms},
              {"casts_per_step", s.casts_per_step},
              {"casts_per_second", s.casts_per_second},
              {"rays_per_step", s.rays_per_step},
              {"indicators_per_step", s.indicators_per_step}};
}

// ---------------------------------------------------------------------------
// Output

void write_json(const CommandLine& cli, const std::string& path, const Json& json) {
  try {
    const std::filesystem::path target(path);
    if (target.has_parent_path()) std::filesystem::create_directories(target.parent_path());
    sp::write_file_atomically(target, json.dump(2) + "\n").value();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: cannot write %s: %s\n", cli.program().c_str(), path.c_str(), e.what());
    std::exit(1);
  }
}

}  // namespace spbench
