// Shared steps of the subcommands: scene + config -> World -> Simulator.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

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

// load_world() that also returns the scene.
LoadedWorld load_scene_and_world(const std::string& scene_path, const std::optional<std::string>& config_path,
                                 std::optional<std::uint64_t> seed_override);

// Loads the scene and optional config, applies a --seed override, builds the
// World. Throws sp::Exception naming the file and problem.
World load_world(const std::string& scene_path, const std::optional<std::string>& config_path,
                 std::optional<std::uint64_t> seed_override);


// "cpu", "gpu" or "auto"; throws naming --backend otherwise.
BackendChoice parse_backend(const std::string& name);

const char* backend_name(Backend backend);

// Auto tries the GPU and falls back to the CPU, saying so on stderr.
std::unique_ptr<Simulator> create_simulator(World world, BackendChoice backend, unsigned cpu_threads);

// The same choice, with the GPU backend on `context` (which must outlive the
// simulator) so that a draw pass on that context can use its buffers.
std::unique_ptr<Simulator> create_simulator_on(vk::Context& context, World world, BackendChoice backend,
                                               unsigned cpu_threads);

}  // namespace sp::cli
