// Step benchmark, the paper's Figure 6 workload by default (section 5.2;
// docs/model.md#the-paper): ms per step (median and p99 of wall time, and GPU
// timestamps), casts per second, indicators per step and the overhead over the
// same frame loop without soundpaint, for each backend and ray budget on one
// scene.
//
// The frame loop (bench_common.h): each frame moves the listener along a
// slow circle (set_listener) and runs one step. The baseline is the same
// loop without soundpaint, i.e. the host's bookkeeping alone (computing the
// player position and reading the clock), timed the same way; the overhead
// is median(frame) - median(baseline). The paper's Unity figures (1.04 /
// 1.34 / 2.23 ms at 100 / 500 / 2500 rays) are frame time with the
// visualization minus without, rendering of the indicators included; this
// loop renders nothing.
//
// Before timing, the backends must agree (indicator, cast and ray totals over
// a few steps); each run then warms up and measures; the table shows medians
// over the runs.
//
//   bench_step --scene scenes/level.gltf --backends cpu,gpu --budgets 100,500,2500 --steps 2000 --runs 3
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "bench_common.h"
#include "gpu/gpu_simulator.h"
#include "io/output.h"
#include "sp_types.h"

namespace {

using spbench::CommandLine;

constexpr const char* kUsage =
    "usage: bench_step [--scene FILE|gen:TRIANGLES] [--backends cpu,gpu] [--budgets A,B,...]\n"
    "                  [--steps N] [--warmup N] [--runs R] [--max-seconds S] [--pattern paper|burst|scene]\n"
    "                  [--bounces B] [--threads T] [--validate-steps N] [--json OUT.json] [--diffraction 0|1]\n"
    "                  [--cpu-traversal soundpaint|embree] [--cpu-walk best|baseline|avx512|avx512-8wide]\n"
    "                  [--kernels N]\n"
    "  --scene        glTF level, or gen:N for a generated level of about N triangles (default: scenes/level.gltf)\n"
    "  --budgets      rays per step (default 100,500,2500: the paper's)\n"
    "  --steps        frames measured per run (default 2000, as the paper); --warmup frames before (default 60)\n"
    "  --runs         fresh simulators per backend and budget; the table shows medians over runs (default 3)\n"
    "  --max-seconds  stop a run's measuring after S seconds, its warm-up after S/5 (default 0: no limit)\n"
    "  --pattern      paper: every source plays every 0.25 s for 0.1 s, phases staggered (default);\n"
    "                 burst: every 0.25 s for one step; scene: as the scene file says\n"
    "  --validate-steps  frames each backend runs for the agreement check (default 10; 0 skips it)\n"
    "  --diffraction  1: diffraction on, its other keys at their defaults (default 0)\n"
    "  --cpu-traversal  the config's cpu_traversal for the CPU backend (default soundpaint;\n"
    "                 embree needs a build with -DSOUNDPAINT_EMBREE=ON)\n"
    "  --cpu-walk     soundpaint's CPU traversal: best (default: the fastest this CPU runs), baseline, avx512\n"
    "                (4-wide), avx512-8wide\n"
    "  --kernels      after each budget's GPU runs, N more steps with a timestamp after each kernel: per step\n"
    "                 the dispatches and barriers recorded and the median GPU ms of each kernel (default 0;\n"
    "                 emit's time includes the first iteration's casts, which it makes)\n";

struct Options {
  std::string scene = SP_DEFAULT_SCENE;
  std::vector<std::string> backends = {"cpu", "gpu"};
  std::vector<std::uint32_t> budgets = {100, 500, 2500};
  spbench::LoopSettings loop{60, 2000, 0.0};
  std::uint32_t runs = 3;
  std::uint32_t bounces = 4;
  unsigned threads = 0;
  spbench::Pattern pattern = spbench::Pattern::Paper;
  std::uint32_t validate_steps = 10;
  std::string json;
  bool diffraction = false;
  sp::CpuTraversal cpu_traversal = sp::CpuTraversal::Soundpaint;
  std::string cpu_walk = "best";
  std::uint32_t kernel_steps = 0;
};

Options parse(const CommandLine& cli, int argc, char** argv) {
  Options o;
  cli.parse(argc, argv, [&](const std::string& flag, const std::string& value) {
    if (flag == "--scene") o.scene = value;
    else if (flag == "--backends") o.backends = CommandLine::split(value);
    else if (flag == "--budgets") o.budgets = cli.to_uint_list(value, flag);
    else if (flag == "--steps") o.loop.steps = cli.to_uint(value, flag);
    else if (flag == "--warmup") o.loop.warmup = cli.to_uint(value, flag);
    else if (flag == "--max-seconds") o.loop.max_seconds = cli.to_double(value, flag);
    else if (flag == "--runs") o.runs = cli.to_uint(value, flag);
    else if (flag == "--bounces") o.bounces = cli.to_uint(value, flag);
    else if (flag == "--threads") o.threads = cli.to_uint(value, flag);
    else if (flag == "--validate-steps") o.validate_steps = cli.to_uint(value, flag);
    else if (flag == "--json") o.json = value;
    else if (flag == "--diffraction") o.diffraction = cli.to_uint(value, flag) != 0;
    else if (flag == "--pattern") o.pattern = spbench::parse_pattern(cli, value);
    else if (flag == "--cpu-walk") o.cpu_walk = value;
    else if (flag == "--kernels") o.kernel_steps = cli.to_uint(value, flag);
    else if (flag == "--cpu-traversal") {
      if (value != "soundpaint" && value != "embree") cli.fail("--cpu-traversal must be soundpaint or embree");
      o.cpu_traversal = value == "embree" ? sp::CpuTraversal::Embree : sp::CpuTraversal::Soundpaint;
    } else return false;
    return true;
  });
  if (o.loop.steps == 0 || o.runs == 0) cli.fail("--steps and --runs must be > 0");
  if (o.backends.empty() || o.budgets.empty()) cli.fail("--backends and --budgets must not be empty");
  for (const auto& b : o.backends)
    if (b != "cpu" && b != "gpu") cli.fail("unknown backend " + b);
  return o;
}

// The paper's Unity overhead per frame (ms) at its three budgets.
const std::map<std::uint32_t, double> kPaperOverheadMs = {{100, 1.04}, {500, 1.34}, {2500, 2.23}};

std::string format(const char* format_string, double value) {
  char text[32];
  std::snprintf(text, sizeof text, format_string, value);
  return text;
}

// Where a GPU step's time goes: the dispatches and barriers one step
// records, and the median GPU ms of each kind of kernel over
// options.kernel_steps steps with timestamps around them (after the same
// warm-up as the timed runs, which run without them). Printed as one line.
spbench::Json profile_kernels(const sp::World& world, unsigned threads, const Options& options) {
  auto sim = spbench::make_simulator(world, "gpu", threads).value();
  if (!sp::gpu::enable_step_profile(*sim)) {
    std::printf("     kernels: no timestamps on this device\n");
    return nullptr;
  }
  for (std::uint32_t n = 0; n < options.loop.warmup; ++n) spbench::run_frame(*sim, world.listener);
  constexpr const char* kNames[sp::gpu::kStageKernelCount] = {"start",   "emit",    "trace", "resolve",
                                                              "prepare", "connect", "admit"};
  std::vector<std::vector<double>> ms(sp::gpu::kStageKernelCount);
  std::vector<double> totals;
  sp::gpu::RecordCounts counts;
  for (std::uint32_t n = 0; n < options.kernel_steps; ++n) {
    spbench::run_frame(*sim, world.listener);
    const std::optional<sp::gpu::StepProfile> profile = sp::gpu::last_step_profile(*sim);
    if (!profile || !profile->measured) continue;
    counts = profile->counts;  // the same every step
    double total = 0.0;
    for (std::size_t k = 1; k < sp::gpu::kStageKernelCount; ++k) {
      ms[k].push_back(profile->kernel_ms[k]);
      total += profile->kernel_ms[k];
    }
    totals.push_back(total);
  }
  if (totals.empty()) return nullptr;
  spbench::Json json = {{"dispatches", counts.dispatches}, {"barriers", counts.barriers}, {"steps", totals.size()}};
  std::printf("     kernels: %u dispatches, %u barriers a step; median GPU ms:", counts.dispatches, counts.barriers);
  for (std::size_t k = 1; k < sp::gpu::kStageKernelCount; ++k) {
    const double median = sp::median(ms[k]);
    json[std::string(kNames[k]) + "_ms"] = median;
    std::printf(" %s %.4f", kNames[k], median);
  }
  json["total_ms"] = sp::median(totals);
  std::printf(" (sum %.4f)\n", sp::median(totals));
  std::fflush(stdout);
  return json;
}

int run(const CommandLine& cli, const Options& options) {
  sp::Scene scene = spbench::load_scene_or_exit(cli, options.scene);
  sp::Config config;
  config.max_bounces = options.bounces;
  config.diffraction.enabled = options.diffraction;  // its other keys at their defaults
  config.cpu_traversal = options.cpu_traversal;
  spbench::apply_pattern(scene, options.pattern, config.dt);
  const unsigned threads = spbench::resolve_threads(options.threads);

  std::printf("scene %s: %zu triangles, %zu sources; pattern %s; %u bounces; CPU backend on %u threads\n",
              options.scene.c_str(), scene.triangle_count(), scene.sources.size(),
              spbench::pattern_name(options.pattern), options.bounces, threads);
  std::printf("host: %s\n", spbench::host_description().c_str());
  spbench::select_cpu_walk(cli, options.cpu_walk);
  std::printf("diffraction: %s; CPU traversal: %s (walk: %s)\n", options.diffraction ? "on" : "off",
              options.cpu_traversal == sp::CpuTraversal::Embree ? "embree" : "soundpaint", spbench::cpu_walk_name());
  config.ray_budget = 1;
  auto probe_world = sp::make_world(scene, config);
  if (!probe_world) {
    std::fprintf(stderr, "bench_step: %s\n", probe_world.error().message.c_str());
    return 1;
  }
  const auto backends = spbench::usable_backends(*probe_world, options.backends, threads);
  if (backends.empty()) {
    std::fprintf(stderr, "bench_step: no backend can run here\n");
    return 1;
  }

  spbench::Json results = spbench::Json::array();
  std::printf("%-4s %7s %6s %9s %9s %9s %9s %8s %9s %11s %9s %9s %6s\n", "back", "budget", "steps", "ms med", "ms p99",
              "gpu med", "gpu p99", "base ms", "overhead", "casts/step", "Mcasts/s", "ind/step", "paper");
  for (std::uint32_t budget : options.budgets) {
    config.ray_budget = budget;
    const sp::World world = sp::make_world(scene, config).value();
    const std::string disagreement =
        spbench::backends_disagree(world, spbench::names(backends), threads, options.validate_steps);
    if (!disagreement.empty()) {
      std::fprintf(stderr, "bench_step: backends disagree at budget %u: %s\n", budget, disagreement.c_str());
      return 1;
    }
    for (const spbench::BackendInfo& backend : backends) {
      std::vector<spbench::LoopRun> runs;
      for (std::uint32_t run = 0; run < options.runs; ++run) {
        auto sim = spbench::make_simulator(world, backend.name, threads).value();
        runs.push_back(spbench::run_frame_loop(*sim, options.loop));
      }
      const spbench::LoopSummary s = spbench::summarize(runs);
      const auto paper = kPaperOverheadMs.find(budget);
      std::printf("%-4s %7u %6zu %9.4f %9.4f %9s %9s %8.5f %9.4f %11.0f %9.3f %9.1f %6s\n", backend.name.c_str(),
                  budget, s.steps, s.ms_median, s.ms_p99,
                  s.gpu_ms_median ? format("%.4f", *s.gpu_ms_median).c_str() : "-",
                  s.gpu_ms_p99 ? format("%.4f", *s.gpu_ms_p99).c_str() : "-", s.baseline_ms_median, s.overhead_ms,
                  s.casts_per_step, s.casts_per_second * 1e-6, s.indicators_per_step,
                  paper != kPaperOverheadMs.end() ? format("%.2f", paper->second).c_str() : "-");
      std::fflush(stdout);
      spbench::Json row = {{"backend", backend.name}, {"device", backend.device}, {"budget", budget}};
      row.update(spbench::to_json(s));
      row["paper_unity_overhead_ms"] =
          paper != kPaperOverheadMs.end() ? spbench::Json(paper->second) : spbench::Json(nullptr);
      if (backend.name == "gpu" && options.kernel_steps > 0) {
        const spbench::Json kernels = profile_kernels(world, threads, options);
        if (!kernels.is_null()) row["kernels"] = kernels;
      }
      results.push_back(row);
    }
  }

  if (!options.json.empty()) {
    spbench::Json paper_points = spbench::Json::object();
    for (const auto& [budget, ms] : kPaperOverheadMs) paper_points[std::to_string(budget)] = ms;
    spbench::Json document = {
        {"benchmark", "bench_step"},
        {"scene", {{"spec", options.scene}, {"triangles", scene.triangle_count()}, {"sources", scene.sources.size()}}},
        {"host", spbench::host_description()},
        {"cpu_walk", spbench::cpu_walk_name()},
        {"settings",
         {{"pattern", spbench::pattern_name(options.pattern)},
          {"bounces", options.bounces},
          {"cpu_threads", threads},
          {"steps", options.loop.steps},
          {"warmup", options.loop.warmup},
          {"runs", options.runs},
          {"max_seconds", options.loop.max_seconds},
          {"validate_steps", options.validate_steps}}},
        {"baseline", "the frame loop without soundpaint: player position update and clock reads only"},
        {"paper_unity_overhead_ms", paper_points},
        {"results", results}};
    spbench::write_json(cli, options.json, document);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return spbench::bench_main(argc, argv, "bench_step", kUsage, parse, run); }
