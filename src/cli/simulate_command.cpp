#include <chrono>
#include <cstdio>
#include <optional>
#include <vector>

#include "cli/commands.h"
#include "cli/event_options.h"
#include "cli/limit_options.h"
#include "cli/options.h"
#include "cli/world_loading.h"
#include "io/atomic_file.h"
#include "io/output_path.h"
#include "io/output.h"

namespace sp::cli {
namespace {

constexpr const char* kSimulateHelp =
    "usage: soundpaint simulate SCENE [--config FILE] [--backend cpu|gpu|auto] [--steps N]\n"
    "                           [--seed S] [--threads T] [--indicators OUT.csv] [--stats OUT.json]\n"
    "                           [--max-triangles N] [--allow-external-uris] [--memory-budget SIZE]\n"
    "\n"
    "Runs N steps (default 120) of the ray model on SCENE (.gltf or .glb).\n"
    "  --config FILE        JSON configuration (see README: configuration keys)\n"
    "  --backend B          cpu, gpu or auto (default auto: the GPU backend on a hardware\n"
    "                       GPU, else the CPU backend, with a note on stderr; gpu also\n"
    "                       accepts a CPU Vulkan device such as lavapipe)\n"
    "  --steps N            number of steps, each dt seconds (default 120)\n"
    "  --seed S             overrides the config's seed (0..4294967295)\n"
    "  --threads T          CPU backend worker threads (default: all cores)\n"
    "  --indicators FILE    CSV of every indicator created, header first\n"
    "  --stats FILE         JSON with counts, per-layer counters and step timing\n"
    "                       (outputs: a regular file, written through a symbolic link,\n"
    "                       or - for standard output)\n";

}  // namespace

int run_simulate(const std::vector<std::string>& args) {
  ParsedArgs parsed = parse_args(args,
                                 with_options(with_options(with_options({"--config", "--backend", "--steps", "--seed",
                                                                         "--threads", "--indicators", "--stats"},
                                                                        kSceneLimitValueOptions),
                                                           kMemoryLimitValueOptions),
                                              kEventValueOptions),
                                 with_options({"--help"}, kSceneLimitFlagOptions));
  if (printed_help(parsed, {kSimulateHelp, scene_limit_help(), memory_limit_help(), event_help()})) return 0;
  const std::string& scene_path = scene_argument(parsed, "simulate");
  const std::uint64_t steps = parsed.unsigned_value("--steps", 0, 100'000'000).value_or(120);
  const auto seed = parsed.unsigned_value("--seed", 0, 0xFFFFFFFFull);
  const auto threads = parsed.unsigned_value("--threads", 1, 1024);
  const BackendChoice backend = parse_backend(parsed.value("--backend").value_or("auto"));
  const std::optional<std::string> indicators_path = parsed.value("--indicators");
  const std::optional<std::string> stats_path = parsed.value("--stats");
  std::vector<NamedOutput> outputs;
  if (indicators_path) outputs.push_back({"--indicators", *indicators_path});
  if (stats_path) outputs.push_back({"--stats", *stats_path});
  // Refused outputs fail before the scene is even read.
  for (const NamedOutput& output : outputs) (void)resolve_output(output.path);
  check_distinct_outputs(outputs);
  // With an output on standard output, the summary line goes to stderr.
  const bool stdout_taken =
      (indicators_path && names_stdout(*indicators_path)) || (stats_path && names_stdout(*stats_path));
  std::FILE* const report = stdout_taken ? stderr : stdout;
  std::optional<events::TraceReplay> replay = load_event_replay(parsed);

  LoadedWorld loaded = load_scene_and_world(scene_path, parsed.value("--config"), seed, scene_load_options(parsed));
  (void)warn_if_penetration_fails(loaded.scene, loaded.world);
  std::unique_ptr<Simulator> simulator = create_simulator(
      std::move(loaded.world), backend, static_cast<unsigned>(threads.value_or(0)), memory_budget(parsed));

  // Open outputs before the run so an unwritable path fails fast; both only
  // appear under their names once complete.
  std::unique_ptr<IndicatorCsvWriter> csv;
  if (indicators_path) csv = IndicatorCsvWriter::open(*indicators_path).value();
  std::optional<AtomicFile> stats_file;
  if (stats_path) stats_file.emplace(*stats_path);

  StepTimings timings;
  const double dt = simulator->world().config.dt;
  for (std::uint64_t n = 0; n < steps; ++n) {
    if (replay) replay->advance(simulator->scene(), static_cast<double>(n) * dt);
    auto start = std::chrono::steady_clock::now();
    simulator->step().value();
    auto end = std::chrono::steady_clock::now();
    timings.wall_ms.push_back(std::chrono::duration<double, std::milli>(end - start).count());
    if (auto gpu_ms = simulator->last_gpu_ms()) timings.gpu_ms.push_back(*gpu_ms);
    if (csv) csv->write(simulator->last_step_indicators().value()).value();
  }

  SimulationStats stats = simulator->stats().value();
  if (stats_file)
    stats_file->write(stats_json(simulator->world(), stats, backend_name(simulator->backend()),
                                 simulator->device_description(), timings));
  if (csv) csv->commit().value();
  if (stats_file) stats_file->commit();
  std::fprintf(report, "%llu steps on %s: %llu rays, %llu casts, %llu indicators, %.3f ms/step median\n",
               static_cast<unsigned long long>(stats.steps), backend_name(simulator->backend()),
               static_cast<unsigned long long>(stats.rays_emitted), static_cast<unsigned long long>(stats.casts),
               static_cast<unsigned long long>(stats.indicators), median(timings.wall_ms));
  return 0;
}

}  // namespace sp::cli
