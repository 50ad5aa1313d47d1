// Which of a step's indicators the ring admits (sp_ring.h has the rule and
// the bins), shared by the GPU's admission kernel and the CPU's ring.
//
// Buffers: C++ passes `const uint* admission_histogram` through
// SP_ADMISSION_ARGS_DECL; GLSL declares a storage buffer of that name
// before including this file.
#ifndef SP_ADMISSION_H
#define SP_ADMISSION_H

#include "sp_ring.h"

#ifdef __cplusplus
#define SP_ADMISSION_ARGS_DECL const uint *admission_histogram,
#define SP_ADMISSION_ARGS_DECL_MUT uint *admission_histogram,
#define SP_ADMISSION_ARGS admission_histogram,
#else
#define SP_ADMISSION_ARGS_DECL
#define SP_ADMISSION_ARGS_DECL_MUT
#define SP_ADMISSION_ARGS
#endif

SP_BEGIN_NAMESPACE

// How many indicators lie in bins [from, to).
SP_INLINE uint sp_admission_count(SP_ADMISSION_ARGS_DECL uint from, uint to) {
  uint count = 0u;
  for (uint b = from; b < to; ++b) count += admission_histogram[b];
  return count;
}

// How many indicators class c has, as counted beside the histogram.
SP_INLINE uint sp_class_count(SP_ADMISSION_ARGS_DECL uint c) {
  return admission_histogram[SP_ADMISSION_CLASS_COUNTS + c];
}

// The lowest bin of class c's section such that the indicators in it and
// above it (within the section) number at most `share`; the section's end
// when even its top bin holds more.
// `histogram`: SP_ADMISSION_TIEBREAKS to read the tie-break bins, else 0.
SP_INLINE uint sp_class_threshold(SP_ADMISSION_ARGS_DECL uint c, uint share, uint histogram) {
  uint first = sp_section_first(c);
  uint end = first + sp_section_levels(c);
  uint admitted = 0u;
  uint threshold = end;
  for (uint b = end; b > first; --b) {
    uint more = admitted + admission_histogram[histogram + b - 1u];
    if (more > share) break;
    admitted = more;
    threshold = b - 1u;
  }
  return threshold;
}

// The unheard classes' shares of `quota` given how many indicators each
// has: an equal third each, what a class cannot use passed on to the
// others, the most important first (direct, through walls, reflected).
// Returns share[c].
SP_INLINE uint sp_class_share(uint quota, uint c, uint count0, uint count1, uint count2) {
  uint counts[3] = {count0, count1, count2};
  uint shares[3];
  uint base = quota / 3u;
  uint left = quota;
  for (uint k = 0u; k < 3u; ++k) {
    shares[k] = min(counts[k], base + (k < quota % 3u ? 1u : 0u));
    left -= shares[k];
  }
  for (uint k = 0u; k < 3u; ++k) {
    uint more = min(counts[k] - shares[k], left);
    shares[k] += more;
    left -= more;
  }
  return shares[c];
}

// Sets class c's plan for a share of `share` indicators. A class with no
// share (its threshold above every bin) or a share of all it has (below
// every bin) needs no walk over its bins.
SP_INLINE void sp_plan_class(SP_ADMISSION_ARGS_DECL_MUT uint c, uint share) {
  uint first = sp_section_first(c);
  uint end = first + sp_section_levels(c);
  uint count = sp_class_count(SP_ADMISSION_ARGS c);
  uint threshold;
  uint remaining;
  if (share == 0u) {
    threshold = end;
    remaining = 0u;
  } else if (share >= count) {
    threshold = first;
    remaining = share - count;
  } else {
    threshold = sp_class_threshold(SP_ADMISSION_ARGS c, share, 0u);
    remaining = share - sp_admission_count(SP_ADMISSION_ARGS threshold, end);
  }
  admission_histogram[SP_ADMISSION_PLAN_THRESHOLD + c] = threshold;
  admission_histogram[SP_ADMISSION_PLAN_REMAINING + c] = remaining;
}

// Fills the plan's thresholds and remainders from the histogram of
// admission bins, for at most `budget` admissions (sp_admission_budget):
// first the source classes, max-min fair (each gets as many as it has, up
// to an even share of what is left, rounds repeated while any is left and
// any class wants more; the last units one each to the lowest slots); then
// the unheard classes by thirds; then spots heard away from their source.
SP_INLINE void sp_plan_admission(SP_ADMISSION_ARGS_DECL_MUT uint budget) {
  uint counts[SP_ADMISSION_SOURCE_CLASSES];
  uint shares[SP_ADMISSION_SOURCE_CLASSES];
  uint wanting = 0u;
  for (uint c = 0u; c < SP_ADMISSION_SOURCE_CLASSES; ++c) {
    counts[c] = sp_class_count(SP_ADMISSION_ARGS c);
    shares[c] = 0u;
    if (counts[c] > 0u) wanting += 1u;
  }
  uint left = budget;
  while (left > 0u && wanting > 0u) {
    uint each = left / wanting;
    for (uint c = 0u; c < SP_ADMISSION_SOURCE_CLASSES && left > 0u; ++c) {
      if (shares[c] == counts[c]) continue;
      uint give = min(counts[c] - shares[c], max(each, 1u));
      shares[c] += give;
      left -= give;
      if (shares[c] == counts[c]) wanting -= 1u;
    }
  }
  for (uint c = 0u; c < SP_ADMISSION_SOURCE_CLASSES; ++c) sp_plan_class(SP_ADMISSION_ARGS c, shares[c]);
  uint count0 = sp_class_count(SP_ADMISSION_ARGS SP_ADMISSION_CLASS_DIRECT);
  uint count1 = sp_class_count(SP_ADMISSION_ARGS SP_ADMISSION_CLASS_THROUGH);
  uint count2 = sp_class_count(SP_ADMISSION_ARGS SP_ADMISSION_CLASS_REFLECTED);
  uint unheard = left;
  for (uint k = 0u; k < 3u; ++k) {
    uint share = sp_class_share(unheard, k, count0, count1, count2);
    sp_plan_class(SP_ADMISSION_ARGS SP_ADMISSION_CLASS_DIRECT + k, share);
    left -= share;
  }
  uint elsewhere = min(sp_class_count(SP_ADMISSION_ARGS SP_ADMISSION_CLASS_ELSEWHERE), left);
  sp_plan_class(SP_ADMISSION_ARGS SP_ADMISSION_CLASS_ELSEWHERE, elsewhere);
}

// With the tie-break histogram counting the tie-break bins of each class's
// overflowing bin, fills the plan's tie-break thresholds of classes
// [0, class_count) (all of them: SP_ADMISSION_CLASSES).
SP_INLINE void sp_plan_tiebreak(SP_ADMISSION_ARGS_DECL_MUT uint class_count) {
  for (uint c = 0u; c < class_count; ++c) {
    uint remaining = admission_histogram[SP_ADMISSION_PLAN_REMAINING + c];
    // Nothing left for the bin below the threshold: no tie-break admits.
    admission_histogram[SP_ADMISSION_PLAN_TIEBREAK + c] =
        remaining == 0u ? sp_section_first(c) + sp_section_levels(c)
                        : sp_class_threshold(SP_ADMISSION_ARGS c, remaining, SP_ADMISSION_TIEBREAKS);
  }
}

// Whether an indicator in admission bin `bin`, tie-break bin `tiebreak`, is
// admitted under its step's plan: at or above its class's threshold, or in
// the bin just below it with a tie-break bin at or above that threshold.
SP_INLINE bool sp_admitted(SP_ADMISSION_ARGS_DECL uint bin, uint tiebreak) {
  uint c = sp_bin_class(bin);
  uint threshold = admission_histogram[SP_ADMISSION_PLAN_THRESHOLD + c];
  return bin >= threshold || (bin + 1u == threshold && tiebreak >= admission_histogram[SP_ADMISSION_PLAN_TIEBREAK + c]);
}

// Whether an indicator in bin `bin` is in its class's overflowing bin, the
// one whose tie-break bins are counted.
SP_INLINE bool sp_in_tiebreak_bin(SP_ADMISSION_ARGS_DECL uint bin) {
  return bin + 1u == admission_histogram[SP_ADMISSION_PLAN_THRESHOLD + sp_bin_class(bin)];
}

SP_END_NAMESPACE

#endif  // SP_ADMISSION_H
