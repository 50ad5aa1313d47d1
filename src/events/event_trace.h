// Sound-event traces (README.md "Sound-event traces", a contract): what a
// game's audio did, one JSON object per line, as the OpenAL trace shim
// (openal/trace/) records it, replayed onto a running simulation's
// SoundScene step by step (`soundpaint simulate|render --events`).
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "soundpaint/category_rules.h"
#include "soundpaint/math.h"
#include "soundpaint/signal.h"
#include "soundpaint/simulation.h"

namespace sp::events {

inline constexpr int kTraceVersion = 1;

// Game coordinates to the scene's (metres).
enum class TraceAxes {
  Identity,  // the trace is in the scene's coordinates already
  // Quake 3 / ioquake3 (OpenArena): 32 units = 1 m, z up; a point (x, y, z)
  // is (x / 32, z / 32, -y / 32) in levels converted to glTF (shared levels' README).
  Quake,
};
Vec3 to_scene(TraceAxes axes, Vec3 game);

// One line of a trace, parsed. Unknown "type"s are kept out (a later
// writer may add some); the header's version must be kTraceVersion.
struct TraceEvent {
  enum class Kind { Buffer, Play, Move, Gain, Stop, Delete, Listener, Orientation } kind = Kind::Play;
  double t = 0.0;                        // seconds since the trace began
  std::uint32_t id = 0;                  // the source, or the buffer of a Buffer event
  std::uint32_t buffer = 0;              // Play: the buffer it plays
  Vec3 position;                         // Play, Move, Listener (game coordinates); Orientation: forward
  Vec3 up;                               // Orientation
  float gain = 1.0f;                     // Play, Gain
  bool loop = false, relative = false;   // Play
  std::optional<std::string> name;       // Buffer: the asset name, if known
  std::shared_ptr<const Signal> signal;  // Buffer: its envelope
};

struct ReplaySettings {
  TraceAxes axes = TraceAxes::Identity;
  double start = 0.0;                          // trace time of step 0, seconds
  std::shared_ptr<const CategoryRules> rules;  // names to categories; none: the name is the category
  float max_distance = 40.0f;                  // D_max of every replayed source, metres
  bool follow_listener = true;                 // the trace's listener becomes soundpaint's
};

// The trace of `path`, in time order. Throws sp::Exception (InvalidArgument)
// naming the file, the line and the problem: not JSON, a missing or
// mistyped field, a version other than kTraceVersion, time going backwards.
std::vector<TraceEvent> load_trace(const std::filesystem::path& path);

// Applies a trace's events to a SoundScene as time passes: each buffer's
// envelope becomes a Signal, each AL source a voice (added when it first
// plays a buffer its rules do not ignore, moved, started and stopped with
// it, removed when deleted), the listener the listener.
class TraceReplay {
 public:
  TraceReplay(std::vector<TraceEvent> events, ReplaySettings settings);
  // Applies every event up to trace time settings.start + `time`. The first
  // call removes the scene's own sources: the trace's sounds replace them.
  void advance(SoundScene& scene, double time);
  // The listener's latest position and facing, in scene coordinates.
  std::optional<Vec3> listener() const { return listener_; }
  std::optional<Vec3> forward() const { return forward_; }
  std::size_t events_applied() const { return next_; }
  std::uint32_t sources_added() const { return added_; }

 private:
  struct Buffer {
    std::shared_ptr<const Signal> signal;
    std::optional<std::string> category;  // empty: ignored
  };
  struct Voice {
    std::uint32_t id = 0;
    std::uint32_t buffer = 0;
    VoiceState state;
    Vec3 game_position;
    bool relative = false;
  };
  void apply(SoundScene& scene, const TraceEvent& event);
  Vec3 place(const Voice& voice) const;

  std::vector<TraceEvent> events_;
  ReplaySettings settings_;
  std::size_t next_ = 0;
  std::map<std::uint32_t, Buffer> buffers_;
  std::map<std::uint32_t, Voice> voices_;
  std::optional<Vec3> listener_, forward_;
  Vec3 game_listener_;
  std::uint32_t added_ = 0;
  bool started_ = false;
};

}  // namespace sp::events
