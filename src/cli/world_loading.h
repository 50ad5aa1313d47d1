// Shared steps of the subcommands: scene + config -> World -> Simulator.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "soundpaint/check.h"
#include "soundpaint/scene.h"
#include "soundpaint/simulation.h"

namespace sp::vk {
class Context;
}

namespace sp::cli {

// A World with the Scene it was built from (render needs the scene's camera).
struct LoadedWorld {
  Scene scene;
  World world;
};

// Loads the scene (as `scene_options` allow) and optional config, applies a
// --seed override, builds the World; returns both. Throws sp::Exception
// naming the file and problem.
LoadedWorld load_scene_and_world(const std::string& scene_path, const std::optional<std::string>& config_path,
                                 std::optional<std::uint64_t> seed_override,
                                 const SceneLoadOptions& scene_options = {});

// Runs the penetration probe (include/soundpaint/check.h) at the config's
// W_max on the world's own geometry and prints its one-line warnings on
// stderr: when most penetrations find no way out of matter, and when casts
// reached the per-cast work bound. Such a level looks like any other
// otherwise. The probe, or nothing when it failed.
std::optional<PenetrationProbe> warn_if_penetration_fails(const Scene& scene, const World& world);

// "cpu", "gpu" or "auto"; throws naming --backend otherwise.
BackendChoice parse_backend(const std::string& name);

const char* backend_name(Backend backend);

// Auto tries the GPU and falls back to the CPU, saying so on stderr. A
// config whose rays and indicators could need more than `memory_budget`
// bytes fails (--memory-budget).
std::unique_ptr<Simulator> create_simulator(World world, BackendChoice backend, unsigned cpu_threads,
                                            std::uint64_t memory_budget = kDefaultMemoryBudgetBytes);

// The same choice, with the GPU backend on `context` (which must outlive the
// simulator) so that a draw pass on that context can use its buffers.
std::unique_ptr<Simulator> create_simulator_on(vk::Context& context, World world, BackendChoice backend,
                                               unsigned cpu_threads,
                                               std::uint64_t memory_budget = kDefaultMemoryBudgetBytes);

}  // namespace sp::cli
