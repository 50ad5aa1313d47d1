// The indicator ring's rules, shared by GLSL and C++: how old an indicator
// is, whether it is live (drawn, and returned by live_indicators), how
// opaque, and which of a step's indicators the ring admits
// (docs/model.md#the-ring-spots-that-live-out-their-lifetime).
//
// A step makes far more indicators than the ring can show for a whole lifetime:
// at 500 rays a step, about 4,000 against a ring of 20,000, which a ring that
// overwrites its oldest (the paper's prototype's) would overwrite within 5
// steps, so spots would live a twelfth of their second and never fade. Instead,
// each step admits at most `quota` = ceil(capacity * dt / lifetime) indicators,
// so the ring turns over once per lifetime and every admitted spot lives it
// out; the most informative are kept: a share each for direct sound (first
// hits), sound through walls and reflections, and within each by energy
// relative to the source's loudness (E / E0, so a quiet or distant source's
// strongest spots compete with a loud one's on equal terms). Every indicator
// still reaches the CSV and the stats: admission only decides what is drawn.
#ifndef SP_RING_H
#define SP_RING_H

#include "sp_connect.h"
#include "sp_types.h"

// The display never shows a spot for less than this (seconds), whatever
// indicator_lifetime says, and the spot is live as long: each spot then
// brightens and fades at most once per 1/3 s, under the
// three-flashes-per-second limit of WCAG 2.3.1. The ring's quota counts
// with it, so a spot is not overwritten before.
#define SP_MIN_DISPLAY_LIFETIME (1.0f / 3.0f)

// Admission sorts a step's indicators into classes, each a section of
// admission bins by a level of worth (docs/model.md#the-ring-spots-that-live-out-their-lifetime):
// - heard toward their source (Indicator::toward > 0), a class per source
//   slot (modulo SP_ADMISSION_SOURCE_CLASSES), so that every audible source
//   keeps a floor: the step's admissions are shared among these classes
//   first, evenly as far as each has spots (max-min fair). Level: the
//   energy heard relative to E0 times `toward`.
// - heard but away from their source: what is left goes to them next, by
//   the energy heard relative to E0.
// - not heard: direct sound (first hits), sound that crossed matter (exits,
//   and anything after a penetration) and the rest (reflections,
//   diffraction), an equal share each of what is left, by E / E0.
#define SP_ADMISSION_SOURCE_CLASSES 64u
#define SP_ADMISSION_TOWARD_LEVELS 64u
#define SP_ADMISSION_LEVELS 512u
#define SP_ADMISSION_CLASS_ELSEWHERE SP_ADMISSION_SOURCE_CLASSES
#define SP_ADMISSION_CLASS_DIRECT (SP_ADMISSION_SOURCE_CLASSES + 1u)
#define SP_ADMISSION_CLASS_THROUGH (SP_ADMISSION_SOURCE_CLASSES + 2u)
#define SP_ADMISSION_CLASS_REFLECTED (SP_ADMISSION_SOURCE_CLASSES + 3u)
#define SP_ADMISSION_CLASSES (SP_ADMISSION_SOURCE_CLASSES + 4u)
#define SP_ADMISSION_TOWARD_BINS (SP_ADMISSION_SOURCE_CLASSES * SP_ADMISSION_TOWARD_LEVELS)
#define SP_ADMISSION_BINS (SP_ADMISSION_TOWARD_BINS + 4u * SP_ADMISSION_LEVELS)

// The admission buffer (sp_admission.h uses it; the GPU keeps it whole).
// The histogram of admission bins, then the histogram of
// tie-break bins (two, so that neither needs clearing between the phases:
// the copy phase clears what the step counted, in parallel), then the
// plan of the step's admission: per class, its threshold bin, the rest of
// its share left for the bin below it, and that bin's tie-break threshold;
// then per class how many indicators it has (counted with the histogram,
// so that planning reads a number a class, not its bins).
#define SP_ADMISSION_TIEBREAKS SP_ADMISSION_BINS
#define SP_ADMISSION_PLAN_THRESHOLD (2u * SP_ADMISSION_BINS)
#define SP_ADMISSION_PLAN_REMAINING (2u * SP_ADMISSION_BINS + SP_ADMISSION_CLASSES)
#define SP_ADMISSION_PLAN_TIEBREAK (2u * SP_ADMISSION_BINS + 2u * SP_ADMISSION_CLASSES)
#define SP_ADMISSION_CLASS_COUNTS (2u * SP_ADMISSION_BINS + 3u * SP_ADMISSION_CLASSES)
#define SP_ADMISSION_BUFFER_SIZE (2u * SP_ADMISSION_BINS + 4u * SP_ADMISSION_CLASSES)

// The admitted indicators of a step go into the ring in canonical order
// (iteration, ray, kind), as the CPU backend lays them, so that when later
// steps overwrite part of a batch still live, both backends lose the same
// spots. Their order is found with a bitmap over the canonical keys and
// the running counts of its words, after the admission histograms in the
// admission buffer; iterations run 1 .. `iterations`.
#define SP_ORDER_KEYS(max_rays, iterations) (((iterations) + 1u) * (max_rays)*2u)
#define SP_ORDER_WORDS(max_rays, iterations) ((SP_ORDER_KEYS(max_rays, iterations) + 31u) / 32u)
#define SP_ORDER_BITMAP SP_ADMISSION_BUFFER_SIZE
// Then the list of the step's indicators in a class's overflowing bin
// (capture slots), whose tie-breaks are decided after the rest.
#define SP_TIEBREAK_LIST(max_rays, iterations) (SP_ORDER_BITMAP + 2u * SP_ORDER_WORDS(max_rays, iterations))

SP_BEGIN_NAMESPACE

// Age of an indicator born at step `birth`, seen at step `now` (the last
// step run: the draw shows whole steps, not the time between them), in
// seconds.
SP_INLINE float sp_indicator_age(uint now, uint birth, float dt) {
  uint steps = now >= birth ? now - birth : 0u;
  SP_PRECISE float age = float(steps) * dt;
  return age;
}

// How long the display shows a spot of `indicator_lifetime` seconds, and
// how long it is live: never under SP_MIN_DISPLAY_LIFETIME. Given a display
// lifetime, returns it unchanged.
SP_INLINE float sp_display_lifetime(float indicator_lifetime) {
  return max(indicator_lifetime, SP_MIN_DISPLAY_LIFETIME);
}

// The one liveness rule (docs/model.md#the-ring-spots-that-live-out-their-lifetime):
// whether an indicator born at step `birth` is live at step `now`, its age
// below the display lifetime. The draw shows a slot only while this holds
// (and the spot is not hidden, capped, faced away or too faint to see), and
// live_indicators() returns exactly the slots for which it holds, so that
// what is live is what is drawn. `lifetime` may be indicator_lifetime or
// the display lifetime: the answer is the same.
SP_INLINE bool sp_indicator_live(uint now, uint birth, float dt, float lifetime) {
  return sp_indicator_age(now, birth, dt) < sp_display_lifetime(lifetime);
}

// Opacity at age a is I * max(0, 1 - a / lifetime) (docs/model.md#indicators).
SP_INLINE float sp_indicator_opacity(float intensity, float age, float lifetime) {
  return intensity * max(0.0f, 1.0f - age / lifetime);
}

// Direct sound: a hit of a ray that has neither reflected, penetrated nor
// diffracted.
SP_INLINE bool sp_is_direct(Indicator ind) {
  return ind.kind == SP_INDICATOR_HIT && ind.bounces == 0u && ind.penetrations == 0u && ind.diffractions == 0u;
}

SP_INLINE uint sp_admission_class(Indicator ind) {
  if (ind.heard > 0.0f) {
    return ind.toward > 0.0f ? ind.source_slot % SP_ADMISSION_SOURCE_CLASSES : SP_ADMISSION_CLASS_ELSEWHERE;
  }
  if (sp_is_direct(ind)) return SP_ADMISSION_CLASS_DIRECT;
  if (ind.kind == SP_INDICATOR_EXIT || ind.penetrations > 0u) return SP_ADMISSION_CLASS_THROUGH;
  return SP_ADMISSION_CLASS_REFLECTED;
}

// Class c's section of admission bins: its first bin and its levels.
SP_INLINE uint sp_section_first(uint c) {
  return c < SP_ADMISSION_SOURCE_CLASSES
             ? c * SP_ADMISSION_TOWARD_LEVELS
             : SP_ADMISSION_TOWARD_BINS + (c - SP_ADMISSION_SOURCE_CLASSES) * SP_ADMISSION_LEVELS;
}
SP_INLINE uint sp_section_levels(uint c) {
  return c < SP_ADMISSION_SOURCE_CLASSES ? SP_ADMISSION_TOWARD_LEVELS : SP_ADMISSION_LEVELS;
}
SP_INLINE uint sp_bin_class(uint bin) {
  return bin < SP_ADMISSION_TOWARD_BINS
             ? bin / SP_ADMISSION_TOWARD_LEVELS
             : SP_ADMISSION_SOURCE_CLASSES + (bin - SP_ADMISSION_TOWARD_BINS) / SP_ADMISSION_LEVELS;
}

// A worth in [0, 1] as one of `levels` levels.
SP_INLINE uint sp_admission_level(float worth, uint levels) {
  SP_PRECISE float scaled = min(max(worth, 0.0f), 1.0f) * float(levels - 1u);
  return uint(scaled);
}

// The admission bin of `ind`: its class's section, then its level of worth.
// inv_indicator_size = 1 / indicator_size (0 when the size is 0), so that
// size * inv_indicator_size is E / E0 with multiplications only, which
// round alike on every device.
SP_INLINE uint sp_admission_bin(Indicator ind, float inv_indicator_size) {
  uint c = sp_admission_class(ind);
  float worth;
  if (c < SP_ADMISSION_SOURCE_CLASSES) {
    SP_PRECISE float toward_worth = sp_heard_relative(ind, inv_indicator_size) * ind.toward;
    worth = toward_worth;
  } else if (c == SP_ADMISSION_CLASS_ELSEWHERE) {
    worth = sp_heard_relative(ind, inv_indicator_size);
  } else {
    SP_PRECISE float relative = ind.size * inv_indicator_size;
    worth = relative;
  }
  return sp_section_first(c) + sp_admission_level(worth, sp_section_levels(c));
}

// Within the bin where a class's share runs out, indicators are admitted by
// a tie-break bin in their class's section: a hash of what tells them apart
// (ray, step, event) over the section's levels, so that a bin larger than the whole quota (a
// small ring, or many spots of equal energy) still yields its share rather
// than nothing, in an order both backends agree on.
SP_INLINE uint sp_admission_tiebreak(Indicator ind) {
  uint h = ind.ray_index * 0x9E3779B1u ^ ind.step * 0x85EBCA77u ^ ind.iteration * 0x27D4EB2Fu;
  h ^= (ind.bounces | (ind.penetrations << 8u) | (ind.diffractions << 16u) | (ind.kind << 24u)) * 0xC2B2AE3Du;
  h ^= h >> 16u;
  h *= 0x7FEB352Du;
  h ^= h >> 15u;
  h *= 0x846CA68Bu;
  h ^= h >> 16u;
  uint c = sp_admission_class(ind);
  return sp_section_first(c) + h % sp_section_levels(c);
}

// How many of a step's indicators the ring may admit: its quota, or all of
// its free room (slots not live after this step's admission), whichever is
// more, so that a ring with room is not throttled; never more than its
// capacity.
SP_INLINE uint sp_admission_budget(uint quota, uint capacity, uint live) {
  uint free_slots = capacity - min(live, capacity);
  return min(capacity, max(quota, free_slots));
}

SP_END_NAMESPACE

#endif  // SP_RING_H
