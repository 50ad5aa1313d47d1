// Helpers shared by the benchmark programs (bench_step, bench_rays): flags,
// scenes (glTF files or generated levels), simulators, the check that the
// backends agree, the timed frame loop and its summary, and JSON output.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "soundpaint/simulation.h"

namespace spbench {

using Json = nlohmann::ordered_json;

// ---------------------------------------------------------------------------
// Command line: every option is "--flag value"; --help prints the usage.

class CommandLine {
 public:
  CommandLine(std::string program, std::string usage) : program_(std::move(program)), usage_(std::move(usage)) {}

  const std::string& program() const { return program_; }

  // Prints the problem and the usage to stderr, exits with status 2.
  [[noreturn]] void fail(const std::string& problem) const;

  // Calls handle(flag, value) for every pair; handle returns false for a
  // flag it does not know.
  void parse(int argc, char** argv, const std::function<bool(const std::string&, const std::string&)>& handle) const;

  std::uint32_t to_uint(const std::string& text, const std::string& flag) const;
  double to_double(const std::string& text, const std::string& flag) const;  // finite, >= 0
  std::vector<std::uint32_t> to_uint_list(const std::string& text, const std::string& flag) const;
  static std::vector<std::string> split(const std::string& list);  // on commas, empty items dropped

 private:
  std::string program_;
  std::string usage_;
};

// A benchmark's main: parses the flags, runs the body; an exception (a
// device failure, say) becomes a message on stderr and exit status 1.
int guarded_main(const CommandLine& cli, const std::function<int()>& body);
template <class Options>
int bench_main(int argc, char** argv, const char* program, const char* usage,
               Options (*parse)(const CommandLine&, int, char**), int (*run)(const CommandLine&, const Options&)) {
  const CommandLine cli(program, usage);
  const Options options = parse(cli, argc, argv);
  return guarded_main(cli, [&] { return run(cli, options); });
}

// `requested`, or the hardware's thread count for 0.
unsigned resolve_threads(unsigned requested);

// The CPU's model name (from /proc/cpuinfo) and thread count.
std::string host_description();

// --cpu-walk: which compiled copy of soundpaint's CPU traversal runs
// (src/bvh/wide_bvh.h): "best" (the default: the fastest this CPU runs),
// "baseline" or "avx512". Fails, naming the problem, on an unknown name or a
// walk this build or CPU lacks.
void select_cpu_walk(const CommandLine& cli, const std::string& name);
// The walk in use, by name.
const char* cpu_walk_name();

// ---------------------------------------------------------------------------
// Scenes

// `spec` is a glTF file, or "gen:N" for generate_level(N). Prints the error
// and exits with status 1 when the file cannot be loaded.
sp::Scene load_scene_or_exit(const CommandLine& cli, const std::string& spec);

// How the sources emit during a benchmark.
//  scene: as the scene file says;
//  paper: every 0.25 s for 0.1 s, phases 0.25 s * i / n (the paper's
//         benchmark; scenes/level.gltf is authored this way);
//  burst: every 0.25 s for one step (dt), phases as above.
enum class Pattern { Scene, Paper, Burst };
Pattern parse_pattern(const CommandLine& cli, const std::string& name);  // fails on an unknown name
const char* pattern_name(Pattern pattern);
void apply_pattern(sp::Scene& scene, Pattern pattern, double dt);

// ---------------------------------------------------------------------------
// Simulators and the frame loop

// The backend "cpu" or "gpu" on a copy of `world`.
sp::Result<std::unique_ptr<sp::Simulator>> make_simulator(const sp::World& world, const std::string& backend,
                                                          unsigned threads);

struct BackendInfo {
  std::string name;    // "cpu" or "gpu"
  std::string device;  // Simulator::device_description()
};

// The backends of `backends` that can be created on this machine; prints
// each one's device string, and why the others are left out, to stdout.
std::vector<BackendInfo> usable_backends(const sp::World& world, const std::vector<std::string>& backends,
                                         unsigned threads);
std::vector<std::string> names(const std::vector<BackendInfo>& backends);

// One frame of the host loop: the player walks a 1 m circle around the
// scene's listener (one lap per 10 s); the frame moves the listener there
// and runs the step.
glm::vec3 player_position(glm::vec3 centre, std::uint64_t frame, double dt);
void run_frame(sp::Simulator& sim, glm::vec3 centre);

// Runs `steps` frames of every backend from a fresh start and compares the
// totals (indicators, casts, rays emitted): they must agree within 0.1 % + 1.
// Returns an empty string when they do, else what differs.
std::string backends_disagree(const sp::World& world, const std::vector<std::string>& backends, unsigned threads,
                              std::uint32_t steps);

struct LoopSettings {
  std::uint32_t warmup = 30;  // frames run before measuring
  std::uint32_t steps = 300;  // frames measured
  double max_seconds = 0.0;   // > 0: stop measuring after this much wall time (at least one frame),
                              // and warming up after a fifth of it
};

// One measured run of the frame loop.
struct LoopRun {
  std::vector<double> wall_ms;      // per frame: player update + set_listener + step
  std::vector<double> gpu_ms;       // per frame, GPU timestamps; empty for the CPU backend
  std::vector<double> baseline_ms;  // per frame of the same loop without soundpaint: player update only
  std::uint64_t casts = 0;
  std::uint64_t rays_emitted = 0;
  std::uint64_t indicators = 0;
};

// Warms up, then measures `settings.steps` frames, then the same number of
// baseline frames.
LoopRun run_frame_loop(sp::Simulator& sim, const LoopSettings& settings);

// Several runs of one backend and budget, reduced: medians of the per-run
// statistics (rule 30: median of N runs).
struct LoopSummary {
  std::size_t runs = 0;
  std::size_t steps = 0;   // frames measured, all runs together
  double ms_median = 0.0;  // wall time of a frame
  double ms_p99 = 0.0;
  std::optional<double> gpu_ms_median;  // GPU timestamps
  std::optional<double> gpu_ms_p99;
  double baseline_ms_median = 0.0;  // the loop without soundpaint
  double overhead_ms = 0.0;         // ms_median - baseline_ms_median
  double casts_per_step = 0.0;
  double casts_per_second = 0.0;  // casts / wall time of the frames
  double rays_per_step = 0.0;
  double indicators_per_step = 0.0;
};
LoopSummary summarize(const std::vector<LoopRun>& runs);
Json to_json(const LoopSummary& summary);

// ---------------------------------------------------------------------------
// Output

// Writes `json` (indented) to `path` atomically; exits with status 1 on failure.
void write_json(const CommandLine& cli, const std::string& path, const Json& json);

}  // namespace spbench
