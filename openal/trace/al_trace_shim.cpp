// libsoundpaint_al_trace.so: an OpenAL library for games that load OpenAL by
// name (ioquake3's s_alDriver cvar), which forwards every al*/alc* call to
// the real OpenAL Soft (dlopen of libopenal.so.1) and records what the game
// does as a sound-event trace, one JSON object per line (README.md
// "Sound-event traces", a contract). The game is not modified.
//
//   SOUNDPAINT_TRACE=out.jsonl        where the trace goes (required; unset: a pure pass-through)
//   SOUNDPAINT_SOUND_NAMES=names.tsv  "fnv1a64-hex<TAB>asset/path" lines: the asset name of
//                                      each buffer, found by the hash of its samples
//   SOUNDPAINT_REAL_OPENAL=path       the real library (default libopenal.so.1)
//
// Names. alBufferData carries samples, not a file name, and ioquake3 reads
// its sounds from pk3 archives through its own file system, so no file read
// names them either. A buffer is named by its content instead: the 64-bit
// FNV-1a hash of the bytes given to alBufferData, which for a .wav is its
// data chunk as stored (ioquake3's S_CodecLoad hands it over unchanged);
// scripts/openarena-sound-names.py hashes every sound in the game's pk3s.
#include <AL/al.h>
#include <AL/alc.h>
#include <dlfcn.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <mutex>
#include <string>
#include <unordered_map>
#include <vector>

#define SP_SHIM extern "C" __attribute__((visibility("default")))

namespace {

// The trace's own version: readers refuse others.
constexpr int kTraceVersion = 1;
constexpr double kHopSeconds = 0.01;  // one level per 10 ms of each buffer

void* real_library() {
  static void* handle = [] {
    const char* path = std::getenv("SOUNDPAINT_REAL_OPENAL");
    void* h = dlopen(path != nullptr ? path : "libopenal.so.1", RTLD_NOW | RTLD_LOCAL);
    if (h == nullptr) {
      std::fprintf(stderr, "soundpaint al_trace: cannot load the real OpenAL: %s\n", dlerror());
      std::abort();
    }
    return h;
  }();
  return handle;
}

void* real_symbol(const char* name) {
  void* symbol = dlsym(real_library(), name);
  if (symbol == nullptr) {
    std::fprintf(stderr, "soundpaint al_trace: the real OpenAL has no %s\n", name);
    std::abort();
  }
  return symbol;
}

}  // namespace

// The real function, looked up once per call site.
#define SP_REAL(fn)                                                               \
  ([]() {                                                                         \
    static const auto real = reinterpret_cast<decltype(&::fn)>(real_symbol(#fn)); \
    return real;                                                                  \
  }())

namespace {

struct SourceState {
  ALint buffer = 0;
  bool looping = false;
  bool relative = false;
  float gain = 1.0f;
  float position[3] = {0, 0, 0};
  bool playing = false;
};

// The recorder: one per process, every call under its mutex (ioquake3 calls
// AL from one thread; the mutex costs nothing then).
class Trace {
 public:
  Trace() {
    const char* path = std::getenv("SOUNDPAINT_TRACE");
    if (path == nullptr) return;
    out_ = std::fopen(path, "w");
    if (out_ == nullptr) {
      std::fprintf(stderr, "soundpaint al_trace: cannot write %s\n", path);
      return;
    }
    if (const char* names = std::getenv("SOUNDPAINT_SOUND_NAMES")) load_names(names);
    start_ = std::chrono::steady_clock::now();
    std::fprintf(out_,
                 "{\"type\":\"header\",\"format\":\"soundpaint-sound-events\",\"version\":%d,"
                 "\"clock\":\"seconds since the trace began\",\"names\":%zu}\n",
                 kTraceVersion, names_.size());
  }
  bool on() const { return out_ != nullptr; }
  std::mutex mutex;

  double now() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

  void buffer(ALuint buffer, ALenum format, const void* data, ALsizei size, ALsizei rate) {
    unsigned channels = 0, bytes = 0;
    if (format == AL_FORMAT_MONO8) channels = 1, bytes = 1;
    if (format == AL_FORMAT_STEREO8) channels = 2, bytes = 1;
    if (format == AL_FORMAT_MONO16) channels = 1, bytes = 2;
    if (format == AL_FORMAT_STEREO16) channels = 2, bytes = 2;
    std::uint64_t hash = 1469598103934665603ull;  // FNV-1a 64
    const auto* p = static_cast<const unsigned char*>(data);
    for (ALsizei i = 0; p != nullptr && i < size; ++i) hash = (hash ^ p[i]) * 1099511628211ull;
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(hash));
    const auto named = names_.find(hex);
    std::string levels;
    double duration = 0.0;
    if (channels != 0 && p != nullptr && rate > 0) {
      const std::size_t count = static_cast<std::size_t>(size) / bytes;
      const std::size_t frames = count / channels;
      duration = static_cast<double>(frames) / rate;
      const std::size_t hop = std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(rate * kHopSeconds)));
      for (std::size_t f = 0; f < frames; f += hop) {
        double sum = 0.0;
        const std::size_t end = std::min(frames, f + hop);
        for (std::size_t i = f * channels; i < end * channels; ++i) {
          double x = 0.0;
          if (bytes == 1) x = (static_cast<double>(p[i]) - 128.0) / 128.0;
          else {
            std::int16_t s;
            std::memcpy(&s, p + 2 * i, 2);
            x = s / 32768.0;
          }
          sum += x * x;
        }
        const double power = sum / static_cast<double>(hop * channels);
        char level[24];
        if (power > 0.0) std::snprintf(level, sizeof level, "%.1f", 10.0 * std::log10(power));
        else std::snprintf(level, sizeof level, "null");  // silence: -infinity
        if (!levels.empty()) levels += ',';
        levels += level;
      }
    }
    std::fprintf(out_,
                 "{\"t\":%.4f,\"type\":\"buffer\",\"buffer\":%u,\"name\":%s,\"hash\":\"%s\",\"format\":%d,"
                 "\"rate\":%d,\"duration\":%.4f,\"hop\":%.3f,\"levels\":[%s]}\n",
                 now(), buffer, named == names_.end() ? "null" : quoted(named->second).c_str(), hex, format, rate,
                 duration, kHopSeconds, levels.c_str());
  }

  void play(ALuint source) {
    SourceState& s = sources_[source];
    s.playing = true;
    std::fprintf(out_,
                 "{\"t\":%.4f,\"type\":\"play\",\"source\":%u,\"buffer\":%d,\"position\":[%.3f,%.3f,%.3f],"
                 "\"gain\":%.4f,\"loop\":%s,\"relative\":%s}\n",
                 now(), source, s.buffer, s.position[0], s.position[1], s.position[2], s.gain,
                 s.looping ? "true" : "false", s.relative ? "true" : "false");
  }
  void stop(ALuint source, const char* why) {
    auto found = sources_.find(source);
    if (found == sources_.end() || !found->second.playing) return;
    found->second.playing = false;
    std::fprintf(out_, "{\"t\":%.4f,\"type\":\"stop\",\"source\":%u,\"by\":\"%s\"}\n", now(), source, why);
  }
  void remove(ALuint source) {
    stop(source, "delete");
    sources_.erase(source);
  }
  void position(ALuint source, const float* v) {
    SourceState& s = sources_[source];
    if (std::memcmp(s.position, v, sizeof s.position) == 0) return;
    std::memcpy(s.position, v, sizeof s.position);
    if (s.playing)
      std::fprintf(out_, "{\"t\":%.4f,\"type\":\"move\",\"source\":%u,\"position\":[%.3f,%.3f,%.3f]}\n", now(), source,
                   v[0], v[1], v[2]);
  }
  void gain(ALuint source, float g) {
    SourceState& s = sources_[source];
    if (s.gain == g) return;
    s.gain = g;
    if (s.playing) std::fprintf(out_, "{\"t\":%.4f,\"type\":\"gain\",\"source\":%u,\"gain\":%.4f}\n", now(), source, g);
  }
  SourceState& source(ALuint id) { return sources_[id]; }
  void listener(const float* v) {
    // Once a frame (ioquake3 places its listener every frame): flushed, so a
    // game ended by a signal still leaves every frame but the last.
    frames_ += 1;
    std::fflush(out_);
    if (std::memcmp(listener_, v, sizeof listener_) == 0) return;
    std::memcpy(listener_, v, sizeof listener_);
    std::fprintf(out_, "{\"t\":%.4f,\"type\":\"listener\",\"position\":[%.3f,%.3f,%.3f]}\n", now(), v[0], v[1], v[2]);
  }
  void orientation(const float* v) {
    if (std::memcmp(orientation_, v, sizeof orientation_) == 0) return;
    std::memcpy(orientation_, v, sizeof orientation_);
    std::fprintf(out_, "{\"t\":%.4f,\"type\":\"orientation\",\"forward\":[%.4f,%.4f,%.4f],\"up\":[%.4f,%.4f,%.4f]}\n",
                 now(), v[0], v[1], v[2], v[3], v[4], v[5]);
  }
  void distance_model(ALenum model) {
    std::fprintf(out_, "{\"t\":%.4f,\"type\":\"distance_model\",\"model\":%d}\n", now(), model);
  }
  // Time the shim itself spent recording (not the real AL's), for the summary.
  void charge(double seconds) { spent_ += seconds; }
  void close() {
    if (out_ == nullptr) return;
    std::fprintf(out_, "{\"t\":%.4f,\"type\":\"summary\",\"frames\":%llu,\"record_us_per_frame\":%.2f}\n", now(),
                 static_cast<unsigned long long>(frames_), frames_ > 0 ? spent_ * 1e6 / double(frames_) : 0.0);
    std::fclose(out_);
    out_ = nullptr;
  }
  ~Trace() { close(); }

 private:
  static std::string quoted(const std::string& text) {
    std::string out = "\"";
    for (char c : text) {
      if (c == '"' || c == '\\') out += '\\';
      if (static_cast<unsigned char>(c) < 0x20) continue;  // asset names hold none
      out += c;
    }
    return out + "\"";
  }
  void load_names(const char* path) {
    std::ifstream in(path);
    for (std::string line; std::getline(in, line);) {
      const auto tab = line.find('\t');
      if (tab != std::string::npos) names_[line.substr(0, tab)] = line.substr(tab + 1);
    }
  }
  std::FILE* out_ = nullptr;
  std::chrono::steady_clock::time_point start_;
  std::unordered_map<std::string, std::string> names_;
  std::map<ALuint, SourceState> sources_;
  float listener_[3] = {0, 0, 0};
  float orientation_[6] = {0, 0, 0, 0, 0, 0};
  std::uint64_t frames_ = 0;
  double spent_ = 0.0;
};

Trace& trace() {
  static Trace t;
  return t;
}

// Runs `record` on the trace under its lock, timed, when tracing is on.
template <class Fn>
void record(Fn&& fn) {
  Trace& t = trace();
  if (!t.on()) return;
  const auto start = std::chrono::steady_clock::now();
  std::lock_guard lock(t.mutex);
  fn(t);
  t.charge(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

}  // namespace

SP_SHIM void alBufferData(ALuint buffer, ALenum format, const ALvoid* data, ALsizei size, ALsizei freq) {
  SP_REAL(alBufferData)(buffer, format, data, size, freq);
  record([&](Trace& t) { t.buffer(buffer, format, data, size, freq); });
}
SP_SHIM void alSourcePlay(ALuint source) {
  SP_REAL(alSourcePlay)(source);
  record([&](Trace& t) { t.play(source); });
}
SP_SHIM void alSourcePlayv(ALsizei n, const ALuint* sources) {
  SP_REAL(alSourcePlayv)(n, sources);
  record([&](Trace& t) {
    for (ALsizei i = 0; i < n; ++i) t.play(sources[i]);
  });
}
SP_SHIM void alSourceStop(ALuint source) {
  SP_REAL(alSourceStop)(source);
  record([&](Trace& t) { t.stop(source, "stop"); });
}
SP_SHIM void alSourceStopv(ALsizei n, const ALuint* sources) {
  SP_REAL(alSourceStopv)(n, sources);
  record([&](Trace& t) {
    for (ALsizei i = 0; i < n; ++i) t.stop(sources[i], "stop");
  });
}
SP_SHIM void alSourcePause(ALuint source) {
  SP_REAL(alSourcePause)(source);
  record([&](Trace& t) { t.stop(source, "pause"); });
}
SP_SHIM void alSourcePausev(ALsizei n, const ALuint* sources) {
  SP_REAL(alSourcePausev)(n, sources);
  record([&](Trace& t) {
    for (ALsizei i = 0; i < n; ++i) t.stop(sources[i], "pause");
  });
}
SP_SHIM void alSourceRewind(ALuint source) {
  SP_REAL(alSourceRewind)(source);
  record([&](Trace& t) { t.stop(source, "rewind"); });
}
SP_SHIM void alSourceRewindv(ALsizei n, const ALuint* sources) {
  SP_REAL(alSourceRewindv)(n, sources);
  record([&](Trace& t) {
    for (ALsizei i = 0; i < n; ++i) t.stop(sources[i], "rewind");
  });
}
SP_SHIM void alDeleteSources(ALsizei n, const ALuint* sources) {
  SP_REAL(alDeleteSources)(n, sources);
  record([&](Trace& t) {
    for (ALsizei i = 0; i < n; ++i) t.remove(sources[i]);
  });
}
SP_SHIM void alSourcei(ALuint source, ALenum param, ALint value) {
  SP_REAL(alSourcei)(source, param, value);
  record([&](Trace& t) {
    if (param == AL_BUFFER) t.source(source).buffer = value;
    if (param == AL_LOOPING) t.source(source).looping = value == AL_TRUE;
    if (param == AL_SOURCE_RELATIVE) t.source(source).relative = value == AL_TRUE;
  });
}
SP_SHIM void alSourcef(ALuint source, ALenum param, ALfloat value) {
  SP_REAL(alSourcef)(source, param, value);
  if (param == AL_GAIN) record([&](Trace& t) { t.gain(source, value); });
}
SP_SHIM void alSource3f(ALuint source, ALenum param, ALfloat x, ALfloat y, ALfloat z) {
  SP_REAL(alSource3f)(source, param, x, y, z);
  const float v[3] = {x, y, z};
  if (param == AL_POSITION) record([&](Trace& t) { t.position(source, v); });
}
SP_SHIM void alSourcefv(ALuint source, ALenum param, const ALfloat* values) {
  SP_REAL(alSourcefv)(source, param, values);
  if (param == AL_POSITION && values != nullptr) record([&](Trace& t) { t.position(source, values); });
}
SP_SHIM void alListener3f(ALenum param, ALfloat x, ALfloat y, ALfloat z) {
  SP_REAL(alListener3f)(param, x, y, z);
  const float v[3] = {x, y, z};
  if (param == AL_POSITION) record([&](Trace& t) { t.listener(v); });
}
SP_SHIM void alListenerfv(ALenum param, const ALfloat* values) {
  SP_REAL(alListenerfv)(param, values);
  if (values == nullptr) return;
  if (param == AL_POSITION) record([&](Trace& t) { t.listener(values); });
  if (param == AL_ORIENTATION) record([&](Trace& t) { t.orientation(values); });
}
SP_SHIM void alDistanceModel(ALenum model) {
  SP_REAL(alDistanceModel)(model);
  record([&](Trace& t) { t.distance_model(model); });
}
SP_SHIM ALCboolean alcCloseDevice(ALCdevice* device) {
  {
    std::lock_guard lock(trace().mutex);
    trace().close();
  }
  return SP_REAL(alcCloseDevice)(device);
}

#include "al_forward.inc"
