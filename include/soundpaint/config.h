// Simulation configuration (contract: README.md, "Configuration (JSON)") and
// acoustic layer presets. Units: metres, seconds; energies are in units of a
// source's loudness E0.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>


#include "soundpaint/display.h"
#include "soundpaint/math.h"
#include "soundpaint/result.h"
#include "soundpaint/export.h"

// Exported from a shared libsoundpaint (export.h).
SP_CPP_API_BEGIN

namespace sp {

class Signal;  // soundpaint/signal.h

// Acoustic properties of a collision layer (docs/model.md's symbols: rho_ref,
// alpha_layer).
struct LayerProperties {
  float reflect_probability = 0.8f;  // rho_ref in [0, 1]: chance a hit reflects rather than penetrates
  float attenuation = 2.0f;          // alpha_layer >= 0: energy lost per metre travelled inside the material
  // t >= 0, metres. 0: the layer's triangles bound closed solids. > 0: each
  // triangle is a thin sheet of this thickness (a pane, a cloth, a door made
  // of one quad), two-sided, crossed on the spot (docs/model.md#sheets).
  float sheet_thickness = 0.0f;
};

// A sound source (docs/model.md#registry). It plays at time t when t >= phase
// and fmod(t - phase, interval) < duration; the defaults make it play always.
struct SourceDesc {
  std::string name;  // node name for scene sources, "" otherwise
  Vec3 position;     // metres, world space
  // Linear RGB, each in [0, 1]; empty: its category's colour in the display
  // palette (docs/model.md#indicators, include/soundpaint/display.h).
  std::optional<Vec3> color;
  std::string category = "sound";  // free text, e.g. "footsteps"
  float max_distance = 30.0f;      // D_max == R_max, metres, >= 0
  float loudness = 1.0f;           // E0, initial ray energy, >= 0
  double duration = 1.0;           // seconds of sound per interval, >= 0
  double interval = 1.0;           // seconds between sound starts, > 0
  double phase = 0.0;              // seconds before the first start, >= 0
  // The sound it plays (soundpaint/signal.h; docs/model.md#loudness-from-the-signal).
  // Set: each step's E0 is `loudness` scaled by the signal's short-term
  // level at the play position (the config's `signal` law), and nothing is
  // emitted below the law's floor. Empty: E0 is `loudness` whenever it plays.
  // Shared and immutable, so copies of a description are cheap.
  std::shared_ptr<const Signal> signal;
  bool loop = false;  // the signal starts again where it ends (looping sounds)
};

enum class BudgetWeighting { Even, Proximity };

// What the CPU backend casts its rays with (key "cpu_traversal"):
// soundpaint's own traversal, the GPU backend's reference bit for bit (the
// default), or Embree's, faster and equal up to float rounding, where the
// library was built with it (-DSOUNDPAINT_EMBREE=ON; embree_available()).
// Only the cast to the nearest surface changes; the GPU backend ignores it.
enum class CpuTraversal { Soundpaint, Embree };

// Whether this build of the library can cast with Embree.
bool embree_available();

// Every key of the JSON configuration, with its default.
// Diffraction at the scene's exposed edges: the config's `diffraction`
// (docs/model.md#diffraction). Off by default: without it the model is the
// paper's, and runs are byte-identical to runs without the key.
struct DiffractionSettings {
  bool enabled = false;
  float edge_angle = 45.0f;    // degrees in (0, 180]: a convex edge whose faces turn by at least this diffracts
  float frequency = 500.0f;    // Hz, > 0: the wavenumber k = 2 pi f / c of the deflection width
  std::optional<float> reach;  // metres, > 0: how near an edge a struck ray may turn; default c / (2 f)
  float gain = 1.0f;           // in [0, 1]: the share of its energy a turned ray keeps
};

// Speed of sound (m/s) that turns a frequency into a wavelength.
inline constexpr float kSpeedOfSound = 343.0f;

// The reach in effect: the config's, else half a wavelength at `frequency`.
inline float diffraction_reach(const DiffractionSettings& d) {
  return d.reach ? *d.reach : kSpeedOfSound / (2.0f * d.frequency);
}

// Cues for the player (docs/model.md#cues-for-the-player): what the ring
// keeps and where rays go, so that the spots a player sees say where each
// sound is. The config's `cues`. {"listen": false} (guiding then off too)
// gives the earlier model: the ring keeps spots by E / E0 alone and rays
// go out uniformly, as in the paper.
struct CueSettings {
  // Cast each spot's way to the listener: the energy heard there and the
  // direction it arrives from (Indicator::heard_energy, ::arrival), and let
  // the ring keep what the player hears first.
  bool listen = true;
  // Share of each source's rays, in [0, 1], drawn from its guide (the
  // emission directions whose spots the player heard); the rest go out
  // uniformly. Needs `listen`.
  float guide_share = 0.5f;
  // Degrees in (0, 180]: a heard spot within this angle of its source, as
  // the listener sees both, points the player at it; the ring keeps such
  // spots first, the nearer the line the sooner, an even floor for every
  // source that has any.
  float toward_angle = 30.0f;
};

// How a source's signal becomes its E0 (the config's `signal`;
// docs/model.md#loudness-from-the-signal): the level L, in dB re full scale,
// of the RMS over `window` seconds from the play position, gives
//   E0 = loudness * clamp((L - floor_db) / (reference_db - floor_db), 0, 1),
// and a step whose E0 is 0 or at most min_energy emits nothing.
struct SignalSettings {
  std::optional<double> window;  // seconds in [0.001, 1]; default: the config's dt (a step's own sound)
  float floor_db = -60.0f;       // at or below this level nothing is emitted
  float reference_db = 0.0f;     // this level and above give E0 = loudness; > floor_db
};

struct Config {
  float scan_radius = 50.0f;       // R_scan, metres
  std::uint32_t ray_budget = 500;  // new rays per step, all sources together
  // Ring-buffer capacity, > 0. Not the paper's prototype's 20,000: the ring
  // admits capacity * dt / lifetime spots a step, the most informative first,
  // and 4,000 (67 a step at 60 Hz) keeps the strongest, which cluster where
  // each sound is, rather than carpeting every wall (docs/accessibility.md).
  std::uint32_t max_indicators = 4000;
  BudgetWeighting budget_weighting = BudgetWeighting::Even;
  std::uint32_t max_bounces = 4;                  // interactions before a ray dies, <= 64
  float bounce_energy_loss = 0.2f;                // e_loss in [0, 1]
  float max_wall_thickness = 0.5f;                // W_max, metres, > 0
  float min_energy = 0.05f;                       // tau_min
  float air_attenuation = 0.02f;                  // alpha_air, energy per metre
  float indicator_size = 0.25f;                   // metres at E == E0
  float indicator_lifetime = 1.0f;                // seconds, > 0
  double dt = 1.0 / 60.0;                         // seconds per step, > 0
  std::uint32_t seed = 1;                         // random stream seed
  std::map<std::string, LayerProperties> layers;  // overrides of presets, by layer name
  std::optional<Vec3> listener_position;          // overrides the scene's camera
  std::vector<SourceDesc> sources;                // added after the scene's sources
  DisplaySettings display;                        // how indicators are drawn (docs/model.md#the-display)
  DiffractionSettings diffraction;                // sound bending round edges (docs/model.md#diffraction)
  CueSettings cues;                               // what reaches the player (docs/model.md#cues-for-the-player)
  SignalSettings signal;                          // loudness from the signal (docs/model.md#loudness-from-the-signal)
  CpuTraversal cpu_traversal = CpuTraversal::Soundpaint;
};

// Largest accepted values (inclusive); larger values are configuration errors.
// Upper bound for max_bounces: the GPU records 2 * max_bounces + 1
// wavefront iterations a step, so this bounds its command buffer's size.
inline constexpr std::uint32_t kMaxBouncesLimit = 64;
inline constexpr std::uint32_t kMaxRayBudget = 1u << 24;
inline constexpr std::uint32_t kMaxIndicatorsLimit = 1u << 24;

// Parses a JSON configuration. `origin` names the text in error messages
// (usually the file path). Missing keys keep their defaults. Counts
// (ray_budget, max_indicators, max_bounces, seed) must be JSON integers
// (5.0 is rejected); numbers stored as float must fit a float. A layer entry
// that omits a field takes it from what the layer would get without the
// entry. Errors: ErrorCode::InvalidConfig naming the key path.
Result<Config> parse_config(std::string_view json_text, std::string_view origin = "config");

// Reads and parses a configuration file (ErrorCode::Io if unreadable).
Result<Config> load_config(const std::filesystem::path& path);

// Built-in presets: concrete, brick, wood, glass, metal, carpet, default.
const std::map<std::string, LayerProperties>& layer_presets();

// The properties used for triangles of `layer_name`. Names are compared
// exactly first, then normalised (ASCII lower case, one trailing Blender-style
// ".NNN" removed: "Wood.001" -> "wood"). Order: the config's entry of that
// name (exact, then normalised), else the preset of the normalised name, else
// the config's "default" entry, else the "default" preset.
LayerProperties resolve_layer(const Config& config, std::string_view layer_name);

}  // namespace sp

SP_CPP_API_END
