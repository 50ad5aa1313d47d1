// soundpaint for games that play their sounds through OpenAL (OpenAL Soft):
// the optional library soundpaint::openal (find_package(soundpaint
// COMPONENTS openal)). The core library never depends on OpenAL.
//
// Two calls are all a game adds (README.md "OpenAL"):
//   alBufferData(buffer, format, data, size, rate);
//   adapter.note_buffer_data(buffer, format, data, size, rate, "sound/player/footsteps/boot1.wav");
//   ...
//   adapter.update();   // once a frame, with the game's AL context current
// update() reads every AL source once (position, playing state, gain, play
// offset, looping, the buffer attached) and mirrors each as a soundpaint
// voice (SoundScene::set_voice): added when first heard playing, moved,
// started and stopped with it, removed when the AL source is deleted, and
// described anew when a reused AL source plays another buffer. Its cues
// follow the buffer's own samples at AL's play offset
// (docs/model.md#loudness-from-the-signal), scaled by AL_GAIN.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include <AL/al.h>

#include "soundpaint/category_rules.h"
#include "soundpaint/math.h"
#include "soundpaint/result.h"
#include "soundpaint/signal.h"
#include "soundpaint/simulation.h"

namespace sp::openal {

struct AdapterSettings {
  // AL's listener becomes soundpaint's (SoundScene::set_listener) every update.
  bool follow_listener = true;
  // AL coordinates (positions of sources and listener) to the scene's, in
  // metres: identity when the game's AL space is the level's. A source with
  // AL_SOURCE_RELATIVE is placed relative to AL's listener first.
  Mat4 to_scene;
  float max_distance = 30.0f;  // D_max of every mirrored source, metres
  float loudness = 1.0f;       // E0 at the signal law's reference level
  // Buffer names to categories (soundpaint/category_rules.h); a name it
  // ignores is never painted. Without rules the name is the category.
  std::shared_ptr<const CategoryRules> rules;
};

// What one update() saw.
struct FrameReport {
  std::uint32_t al_sources = 0;  // AL sources that exist
  std::uint32_t playing = 0;     // of them, mirrored and playing
  std::uint32_t added = 0;       // soundpaint sources added this update
  std::uint32_t removed = 0;     // removed: their AL source was deleted
};

// Not thread-safe: call it from the thread that owns the AL context (the
// SoundScene calls it makes may meet a render thread's step: they queue).
// The SoundScene must outlive the adapter.
class Adapter {
 public:
  explicit Adapter(SoundScene& scene, AdapterSettings settings = {});

  // The call beside alBufferData: the same arguments, and the asset name
  // the game knows the sound by (its category comes from it). Reads
  // AL_FORMAT_MONO8/16, STEREO8/16 and, with AL_EXT_float32,
  // MONO/STEREO_FLOAT32. Errors (InvalidArgument, naming the buffer): an
  // unreadable format, data NULL or a size that is not whole frames, a bad
  // rate. A buffer given again is described anew.
  Result<bool> note_buffer_data(ALuint buffer, ALenum format, const ALvoid* data, ALsizei size, ALsizei frequency,
                                std::string_view name);
  // The wrapper: alBufferData, then note_buffer_data (not when AL refused it).
  Result<bool> buffer_data(ALuint buffer, ALenum format, const ALvoid* data, ALsizei size, ALsizei frequency,
                           std::string_view name);

  // Once a frame. Errors: no current AL context (InvalidArgument: nothing
  // is read); an AL source playing a buffer never given to
  // note_buffer_data (InvalidArgument naming both; every other source is
  // still mirrored, and that one is not painted).
  Result<FrameReport> update();

  // The soundpaint source mirroring AL source `source`, if any.
  std::optional<std::uint32_t> source_id(ALuint source) const;

 private:
  struct Buffer {
    std::shared_ptr<const Signal> signal;
    std::optional<std::string> category;  // empty: ignored by the rules
    std::uint64_t generation = 0;         // which note_buffer_data described it
  };
  struct Mirror {
    std::uint32_t id = 0;          // the soundpaint source
    std::uint64_t generation = 0;  // the buffer description it was made from (0: none yet)
    bool loop = false;             // AL_LOOPING when last read
  };
  Result<bool> mirror(ALuint source, const Vec3& listener, FrameReport& report, std::string& problem);

  SoundScene& scene_;
  AdapterSettings settings_;
  std::map<ALuint, Buffer> buffers_;
  std::map<ALuint, Mirror> mirrors_;
  ALuint highest_source_ = 0;  // the highest AL source id seen
  std::uint64_t generations_ = 0;
};

}  // namespace sp::openal
