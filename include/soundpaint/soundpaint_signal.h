/* soundpaint C API: cues that follow the sound a source really plays
 * (docs/model.md "Loudness from the signal") and the voice API an audio
 * engine feeds (docs/integrating.md "Voices"). C99; the conventions of
 * soundpaint.h hold (results, last error, handle checks, threads).
 *
 * Levels are in dB re full scale: 20 log10(RMS), full scale being a sample
 * of magnitude 1.0 (float) or 32768 (16-bit). A step's E0 is the source's
 * loudness times clamp((L - floor) / (reference - floor), 0, 1), L the level
 * over the config's "signal.window" from the play position; at or below the
 * floor (and where E0 <= min_energy) the source emits nothing that step.
 */
#ifndef SOUNDPAINT_SOUNDPAINT_SIGNAL_H
#define SOUNDPAINT_SOUNDPAINT_SIGNAL_H

#include <stdint.h>

#include "soundpaint/soundpaint.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A sound's loudness envelope (soundpaint/signal.h): immutable once made,
 * shareable between sources and threads. A source it is attached to keeps
 * its own reference, so the handle may be destroyed right after. */
typedef struct sp_signal sp_signal;

/* From interleaved PCM: `count` samples (a multiple of `channels`, 1 to 8)
 * at `sample_rate` Hz in [1000, 768000]. Errors: SP_ERROR_INVALID_ARGUMENT
 * naming the problem (no samples, a bad rate, a non-finite sample). */
SP_API sp_result sp_signal_create_f32(const float* samples, uint64_t count, double sample_rate, uint32_t channels,
                                      sp_signal** out) SP_NOEXCEPT;
SP_API sp_result sp_signal_create_s16(const int16_t* samples, uint64_t count, double sample_rate, uint32_t channels,
                                      sp_signal** out) SP_NOEXCEPT;
/* From an envelope computed elsewhere: `count` levels in dB re full scale
 * (-INFINITY for silence), one per `hop_seconds` in [0.0005, 1]. */
SP_API sp_result sp_signal_create_levels(const float* levels_db, uint64_t count, double hop_seconds,
                                         sp_signal** out) SP_NOEXCEPT;
/* Destroys a signal; NULL is a no-op. Sources it was attached to keep it. */
SP_API sp_result sp_signal_destroy(sp_signal* signal) SP_NOEXCEPT;
/* Seconds of sound. */
SP_API sp_result sp_signal_duration(const sp_signal* signal, double* out_seconds) SP_NOEXCEPT;
/* The level of [position, position + window) seconds, as the simulation
 * reads it (past the end: silence, or the start again with `loop` != 0);
 * -INFINITY for silence. */
SP_API sp_result sp_signal_level_db(const sp_signal* signal, double position, double window, int loop,
                                    double* out_db) SP_NOEXCEPT;

/* Attaches the sound source `id` plays (NULL detaches: E0 is its loudness
 * again); `loop` != 0 repeats it. Any thread, applied at the next step. */
SP_API sp_result sp_sound_scene_set_signal(sp_sound_scene* scene, uint32_t id, const sp_signal* signal,
                                           int loop) SP_NOEXCEPT;

/* What an audio engine knows of one voice (sp_sound_scene_set_voice).
 * Fill it with sp_voice_state_init first. */
typedef struct sp_voice_state {
  float position[3];      /* metres, world space, finite */
  int playing;            /* non-zero: playing from the next step until a call says stopped */
  float gain;             /* linear amplitude factor >= 0 on its level; default 1 */
  double signal_position; /* seconds into its signal at the next step; negative (default -1): keep running */
} sp_voice_state;

/* Defaults: at the origin, stopped, gain 1, position kept. NULL: no-op. */
SP_API void sp_voice_state_init(sp_voice_state* state) SP_NOEXCEPT;

/* A voice is a source whose playing the engine tells: add it with
 * duration 0 (silent by pattern), then give its state once a frame or
 * whenever it changes. Any thread (the audio thread included). */
SP_API sp_result sp_sound_scene_set_voice(sp_sound_scene* scene, uint32_t id, const sp_voice_state* state) SP_NOEXCEPT;
/* The level of what the voice plays now, dB re full scale before its gain;
 * holds until the next, overriding its signal. -INFINITY: silence; NaN:
 * back to the signal. Any thread. */
SP_API sp_result sp_sound_scene_set_voice_level(sp_sound_scene* scene, uint32_t id, double level_db) SP_NOEXCEPT;
/* sp_sound_scene_set_voice_level with the RMS level of `count` interleaved
 * float samples (full scale 1): one call per block a DSP callback
 * processes. Any thread. */
SP_API sp_result sp_sound_scene_feed_voice(sp_sound_scene* scene, uint32_t id, const float* samples,
                                           uint64_t count) SP_NOEXCEPT;

#ifdef __cplusplus
}
#endif

#endif /* SOUNDPAINT_SOUNDPAINT_SIGNAL_H */
