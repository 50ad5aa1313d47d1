// The C API of signals and voices (soundpaint_signal.h): thin wrappers over
// sp::Signal and SoundScene's voice calls, which name the problem; checked
// here is what C adds (NULL pointers, live handles, lengths).
#include <cmath>
#include <limits>
#include <memory>
#include <span>

#include "capi/capi_internal.h"
#include "soundpaint/signal.h"
#include "soundpaint/soundpaint_signal.h"

struct sp_signal {
  sp::capi::ContextRef context;  // the default one's allocator gave its memory
  std::shared_ptr<const sp::Signal> signal;
};

namespace {

using sp::capi::guarded;
using sp::capi::HandleKind;
using sp::capi::require;
using sp::capi::unwrap;

const sp_signal& signal_of(const sp_signal* signal, const char* fn) {
  sp::capi::require_live(HandleKind::Signal, signal, fn, "signal");
  return *signal;
}

// Registers a new handle for `made` and stores it in *out.
void hand_out(sp::Signal made, sp_signal** out) {
  auto handle = sp::capi::make_handle<sp_signal>(sp::capi::default_context());
  handle->signal = std::make_shared<const sp::Signal>(std::move(made));
  sp::capi::register_handle(HandleKind::Signal, handle.get());
  *out = handle.release();
}

template <class Sample>
std::span<const Sample> samples_of(const Sample* samples, uint64_t count, const char* fn) {
  require(samples != nullptr || count == 0, fn, "samples is NULL");
  require(count <= std::numeric_limits<std::size_t>::max() / sizeof(Sample), fn, "count is too large");
  return {samples, static_cast<std::size_t>(count)};
}

}  // namespace

extern "C" {

sp_result sp_signal_create_f32(const float* samples, uint64_t count, double sample_rate, uint32_t channels,
                               sp_signal** out) noexcept {
  return guarded([&] {
    const char* fn = "sp_signal_create_f32";
    require(out != nullptr, fn, "out is NULL");
    hand_out(unwrap(sp::Signal::from_pcm(samples_of(samples, count, fn), sample_rate, channels)), out);
  });
}

sp_result sp_signal_create_s16(const int16_t* samples, uint64_t count, double sample_rate, uint32_t channels,
                               sp_signal** out) noexcept {
  return guarded([&] {
    const char* fn = "sp_signal_create_s16";
    require(out != nullptr, fn, "out is NULL");
    hand_out(unwrap(sp::Signal::from_pcm16(samples_of(samples, count, fn), sample_rate, channels)), out);
  });
}

sp_result sp_signal_create_levels(const float* levels_db, uint64_t count, double hop_seconds,
                                  sp_signal** out) noexcept {
  return guarded([&] {
    const char* fn = "sp_signal_create_levels";
    require(out != nullptr, fn, "out is NULL");
    hand_out(unwrap(sp::Signal::from_levels(samples_of(levels_db, count, fn), hop_seconds)), out);
  });
}

sp_result sp_signal_destroy(sp_signal* signal) noexcept {
  return guarded([&] { sp::capi::destroy_handle(HandleKind::Signal, signal, "sp_signal_destroy", "signal"); });
}

sp_result sp_signal_duration(const sp_signal* signal, double* out_seconds) noexcept {
  return guarded([&] {
    const char* fn = "sp_signal_duration";
    const sp_signal& s = signal_of(signal, fn);
    require(out_seconds != nullptr, fn, "out_seconds is NULL");
    *out_seconds = s.signal->duration();
  });
}

sp_result sp_signal_level_db(const sp_signal* signal, double position, double window, int loop,
                             double* out_db) noexcept {
  return guarded([&] {
    const char* fn = "sp_signal_level_db";
    const sp_signal& s = signal_of(signal, fn);
    require(out_db != nullptr, fn, "out_db is NULL");
    require(std::isfinite(position), fn, "position is not finite");
    require(std::isfinite(window) && window > 0.0, fn, "window must be finite and > 0");
    *out_db = s.signal->level_db(position, window, loop != 0);
  });
}

sp_result sp_sound_scene_set_signal(sp_sound_scene* scene, uint32_t id, const sp_signal* signal, int loop) noexcept {
  return guarded([&] {
    const char* fn = "sp_sound_scene_set_signal";
    sp::SoundScene& s = sp::capi::scene_of(scene, fn);
    std::shared_ptr<const sp::Signal> attached;
    if (signal != nullptr) attached = signal_of(signal, fn).signal;
    unwrap(s.set_signal(id, std::move(attached), loop != 0));
  });
}

void sp_voice_state_init(sp_voice_state* state) noexcept {
  if (state == nullptr) return;
  const sp::VoiceState defaults;
  sp_voice_state out{};
  for (int k = 0; k < 3; ++k) out.position[k] = defaults.position[k];
  out.playing = defaults.playing ? 1 : 0;
  out.gain = defaults.gain;
  out.signal_position = defaults.signal_position;
  *state = out;
}

sp_result sp_sound_scene_set_voice(sp_sound_scene* scene, uint32_t id, const sp_voice_state* state) noexcept {
  return guarded([&] {
    const char* fn = "sp_sound_scene_set_voice";
    sp::SoundScene& s = sp::capi::scene_of(scene, fn);
    require(state != nullptr, fn, "state is NULL");
    sp::VoiceState v;
    v.position = sp::Vec3(state->position[0], state->position[1], state->position[2]);
    v.playing = state->playing != 0;
    v.gain = state->gain;
    v.signal_position = state->signal_position;
    unwrap(s.set_voice(id, v));
  });
}

sp_result sp_sound_scene_set_voice_level(sp_sound_scene* scene, uint32_t id, double level_db) noexcept {
  return guarded(
      [&] { unwrap(sp::capi::scene_of(scene, "sp_sound_scene_set_voice_level").set_voice_level(id, level_db)); });
}

sp_result sp_sound_scene_feed_voice(sp_sound_scene* scene, uint32_t id, const float* samples, uint64_t count) noexcept {
  return guarded([&] {
    const char* fn = "sp_sound_scene_feed_voice";
    sp::SoundScene& s = sp::capi::scene_of(scene, fn);
    unwrap(s.feed_voice(id, samples_of(samples, count, fn)));
  });
}

}  // extern "C"
