// Does a level suit the ray model? What `soundpaint check` reports: the
// geometry facts that decide whether sound can pass through walls
// (docs/model.md#what-the-level-needs-and-soundpaint-check), and a short probe
// simulation that counts how often a ray that penetrates a surface finds no way
// out of matter.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "soundpaint/config.h"
#include "soundpaint/result.h"
#include "soundpaint/scene.h"
#include "soundpaint/simulation.h"
#include "soundpaint/export.h"

// Exported from a shared libsoundpaint (export.h).
SP_CPP_API_BEGIN

namespace sp {

// A layer a finding concerns, and how many of the finding's edges, triangles
// or probe events are on it. `name` is the layer's name exactly as the scene
// gives it (Scene::layer_names), not escaped: it is data, for tools.
struct CheckLayerCount {
  std::string name;
  std::uint64_t count = 0;
};

// One finding: advice, not an error. Codes (stable, for tools):
//   open_edges            edges with surface on one side only: the mesh is not closed
//   inconsistent_winding  edges two neighbouring triangles run the same way
//   degenerate_triangles  triangles of zero area
//   scale                 the bounds suggest units other than metres
//   penetration_misses    in the probe, more than a quarter of penetrations
//                         found no way out of matter within probe_reach
//   wall_thickness        in the probe at the config's max_wall_thickness,
//                         more than half did, though ways out exist
//   back_faces            in the probe, rays in air struck the backs of faces
//   memory_budget         the config's rays and indicators may need more
//                         memory than memory_budget_bytes, so simulators
//                         created with that budget refuse the config
struct CheckFinding {
  std::string code;
  // Edges, triangles, probe events; for scale, the level's largest extent
  // (rounded, at most 2^53, the largest count every JSON reader holds
  // exactly); for memory_budget, the bytes the config may need.
  std::uint64_t count = 0;
  // One line: what was found and what to do about it. The layer names in it
  // are escaped (README "Security": control characters as \u{1b}, bytes
  // that are not UTF-8 as \xff), so it holds no control character, no line
  // break and no invalid UTF-8, whatever the scene calls its layers.
  std::string message;
  // For open_edges, inconsistent_winding, penetration_misses and
  // wall_thickness: every layer concerned, the most first (the message
  // names at most four). Empty for the other codes.
  std::vector<CheckLayerCount> layers;
};

struct PenetrationProbe {
  std::uint64_t penetrations = 0;  // decisions to penetrate a solid (sheets excluded)
  std::uint64_t no_way_out = 0;    // of those, found no way out within the probe's reach
  std::uint64_t hits = 0;
  std::uint64_t back_face_hits = 0;
  std::uint64_t casts_cut_short = 0;  // casts that reached the per-cast work bound (SimulationStats)
  // Per layer id (Scene::layer_names): penetrations and those without a way out.
  std::vector<std::uint64_t> layer_penetrations;
  std::vector<std::uint64_t> layer_no_way_out;

  // no_way_out / penetrations, 0 without penetrations.
  double miss_share() const { return penetrations ? double(no_way_out) / double(penetrations) : 0.0; }
};

struct CheckReport {
  std::uint64_t triangles = 0;
  PenetrationProbe probe;            // reaching probe_reach (or W_max if larger): is there a way out at all?
  PenetrationProbe probe_at_config;  // reaching the config's W_max: what a simulation will see
  std::vector<CheckFinding> findings;
};

struct CheckSettings {
  // The probe: every scene source (or, with none, the listener or the
  // bounds' centre) casts probe_rays_per_step rays for probe_steps steps on
  // the CPU backend, every layer reflecting half the time so that each gets
  // penetrations. Matter is searched up to probe_reach metres from the
  // entry point (or the config's W_max if larger; 0: W_max): the probe asks
  // whether a way out exists at all, not whether a wall is thinner than
  // W_max. Walls of real levels are rarely more than a few metres thick.
  std::uint32_t probe_steps = 20;
  std::uint32_t probe_rays_per_step = 2000;
  float probe_reach = 4.0f;
  unsigned threads = 0;  // CPU threads of the probe; 0: all cores
  // The budget a simulation of this config will be created with
  // (CpuSettings / GpuSettings::memory_budget_bytes, `--memory-budget`):
  // a config whose estimate exceeds it is reported (memory_budget). The
  // probe itself runs on small ray and indicator counts of its own, so a
  // config over budget is advice, never a failure of the check.
  std::uint64_t memory_budget_bytes = kDefaultMemoryBudgetBytes;
};

// Checks `scene` with `config`'s layers (their sheet_thickness decides which
// faces are sheets). Errors: InvalidScene / InvalidConfig as make_world.
Result<CheckReport> check_scene(const Scene& scene, const Config& config, const CheckSettings& settings = {});

// The probe alone; `info` and `simulate` run it with probe_reach 0 to warn
// when penetration mostly fails.
Result<PenetrationProbe> probe_penetration(const Scene& scene, const Config& config,
                                           const CheckSettings& settings = {});
// The same on `geometry`, built from `scene` (build_geometry, or a World's),
// which it shares: no weld or BVH build of its own.
Result<PenetrationProbe> probe_penetration(const Scene& scene, const Config& config, const CheckSettings& settings,
                                           const WorldGeometryHandle& geometry);

// The one-line warning `info` and `simulate` print, or "" when at most half
// the probe's penetrations found no way out.
std::string penetration_warning(const PenetrationProbe& probe);

// The one-line warning `info` and `simulate` print when some of the probe's
// casts reached the per-cast work bound (docs/model.md#work-bounds), or "".
std::string work_bound_warning(const PenetrationProbe& probe);

}  // namespace sp

SP_CPP_API_END
