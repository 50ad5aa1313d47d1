// The OpenAL adapter (soundpaint/openal.h): AL sources read once a frame and
// mirrored as soundpaint voices whose cues follow their buffers' samples.
//
// AL cannot list its sources, so update() asks alIsSource of the ids from 1
// to 64 past the highest it has seen: OpenAL Soft numbers sources from 1,
// lowest free first, in blocks of 64, so every live source lies there.
#include <AL/alc.h>

#include <cmath>
#include <string>
#include <utility>

#include "buffer_signal.h"
#include "soundpaint/openal.h"

namespace sp::openal {
namespace {

constexpr ALuint kProbeMargin = 64;  // OpenAL Soft's block of source ids

Error invalid_call(std::string message) { return Error{ErrorCode::InvalidArgument, std::move(message), 0}; }

Vec3 transform(const Mat4& m, Vec3 p) {
  Vec3 out;
  for (int r = 0; r < 3; ++r) out[r] = m[0][r] * p.x + m[1][r] * p.y + m[2][r] * p.z + m[3][r];
  return out;
}

Vec3 get_position(ALuint source) {
  ALfloat x = 0, y = 0, z = 0;
  alGetSource3f(source, AL_POSITION, &x, &y, &z);
  return {x, y, z};
}

}  // namespace

Adapter::Adapter(SoundScene& scene, AdapterSettings settings) : scene_(scene), settings_(std::move(settings)) {}

Result<bool> Adapter::note_buffer_data(ALuint buffer, ALenum format, const ALvoid* data, ALsizei size,
                                       ALsizei frequency, std::string_view name) {
  auto signal = buffer_signal(format, data, size, frequency);
  if (!signal)
    return invalid_call("openal: buffer " + std::to_string(buffer) + " (\"" + std::string(name) +
                        "\"): " + signal.error().message);
  Buffer described;
  described.signal = std::make_shared<const Signal>(std::move(signal).value());
  described.category = settings_.rules ? settings_.rules->category_of(name) : std::optional<std::string>(name);
  // A buffer id refilled with other samples must be described anew too.
  described.generation = ++generations_;
  buffers_[buffer] = std::move(described);
  return true;
}

Result<bool> Adapter::buffer_data(ALuint buffer, ALenum format, const ALvoid* data, ALsizei size, ALsizei frequency,
                                  std::string_view name) {
  alGetError();  // clear an earlier error, so the one read below is alBufferData's
  alBufferData(buffer, format, data, size, frequency);
  if (const ALenum error = alGetError(); error != AL_NO_ERROR)
    return invalid_call("openal: alBufferData(buffer " + std::to_string(buffer) +
                        ") failed: " + (alGetString(error) != nullptr ? alGetString(error) : "unknown AL error"));
  return note_buffer_data(buffer, format, data, size, frequency, name);
}

std::optional<std::uint32_t> Adapter::source_id(ALuint source) const {
  const auto found = mirrors_.find(source);
  if (found == mirrors_.end()) return std::nullopt;
  return found->second.id;
}

Result<FrameReport> Adapter::update() {
  if (alcGetCurrentContext() == nullptr)
    return invalid_call("openal: no current AL context (call alcMakeContextCurrent before Adapter::update)");
  FrameReport report;
  ALfloat lx = 0, ly = 0, lz = 0;
  alGetListener3f(AL_POSITION, &lx, &ly, &lz);
  const Vec3 listener(lx, ly, lz);
  if (settings_.follow_listener)
    if (auto moved = scene_.set_listener(transform(settings_.to_scene, listener)); !moved) return moved.error();

  std::string problem;
  std::uint32_t problems = 0;
  // The bound grows as sources are found: a block of 64 ids past the last one.
  for (ALuint source = 1; source <= highest_source_ + kProbeMargin; ++source) {
    if (alIsSource(source) != AL_TRUE) {
      if (auto gone = mirrors_.find(source); gone != mirrors_.end()) {
        (void)scene_.remove_source(gone->second.id);  // fails only if the host removed it first
        mirrors_.erase(gone);
        report.removed += 1;
      }
      continue;
    }
    report.al_sources += 1;
    if (source > highest_source_) highest_source_ = source;
    std::string trouble;
    if (auto mirrored = mirror(source, listener, report, trouble); !mirrored) return mirrored.error();
    if (!trouble.empty() && problems++ == 0) problem = std::move(trouble);
  }
  if (problems > 0)
    return invalid_call(problem + (problems > 1 ? " (and " + std::to_string(problems - 1) + " more)" : std::string()));
  return report;
}

// Reads one AL source and brings its soundpaint voice in line. `problem`
// receives a misuse to report (the source is then left unpainted).
Result<bool> Adapter::mirror(ALuint source, const Vec3& listener, FrameReport& report, std::string& problem) {
  ALint state = AL_INITIAL, buffer = 0, looping = AL_FALSE, relative = AL_FALSE;
  ALfloat gain = 1.0f, offset = 0.0f;
  alGetSourcei(source, AL_SOURCE_STATE, &state);
  alGetSourcei(source, AL_BUFFER, &buffer);
  alGetSourcei(source, AL_LOOPING, &looping);
  alGetSourcei(source, AL_SOURCE_RELATIVE, &relative);
  alGetSourcef(source, AL_GAIN, &gain);
  alGetSourcef(source, AL_SEC_OFFSET, &offset);
  Vec3 position = get_position(source);
  if (relative == AL_TRUE) position = Vec3(position.x + listener.x, position.y + listener.y, position.z + listener.z);

  const bool playing = state == AL_PLAYING && buffer != 0;
  const auto described = buffers_.find(static_cast<ALuint>(buffer));
  if (playing && described == buffers_.end()) {
    problem = "openal: AL source " + std::to_string(source) + " plays buffer " + std::to_string(buffer) +
              ", which was never given to Adapter::note_buffer_data";
  }
  const bool paintable = described != buffers_.end() && described->second.category.has_value();
  auto mirrored = mirrors_.find(source);
  if (mirrored == mirrors_.end()) {
    if (!playing || !paintable) return true;  // nothing to show until it plays something we can paint
    mirrored = mirrors_.emplace(source, Mirror{}).first;
  }
  Mirror& m = mirrored->second;
  VoiceState voice;
  voice.position = transform(settings_.to_scene, position);
  voice.playing = playing && paintable;
  voice.gain = std::isfinite(gain) && gain >= 0.0f ? gain : 0.0f;
  voice.signal_position = std::isfinite(offset) && offset >= 0.0f ? offset : 0.0;
  if (paintable && m.generation != described->second.generation) {
    // New, or a reused AL source now playing another buffer (or its buffer
    // refilled): describe it anew.
    SourceDesc desc;
    desc.position = voice.position;
    desc.category = *described->second.category;
    desc.max_distance = settings_.max_distance;
    desc.loudness = settings_.loudness;
    desc.duration = 0.0;  // silent by pattern: the voice says when it plays
    desc.signal = described->second.signal;
    desc.loop = looping == AL_TRUE;
    if (m.generation == 0) {
      auto id = scene_.add_source(desc);
      if (!id) {
        mirrors_.erase(mirrored);
        return id.error();
      }
      m.id = id.value();
      report.added += 1;
    } else if (auto updated = scene_.update_source(m.id, desc); !updated) {
      return updated.error();
    }
    m.generation = described->second.generation;
    m.loop = looping == AL_TRUE;
  } else if (paintable && m.loop != (looping == AL_TRUE)) {
    m.loop = looping == AL_TRUE;
    if (auto looped = scene_.set_signal(m.id, described->second.signal, m.loop); !looped) return looped.error();
  }
  if (auto told = scene_.set_voice(m.id, voice); !told) return told.error();
  report.playing += voice.playing ? 1 : 0;
  return true;
}

}  // namespace sp::openal
