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

// The plan of a step's admission, stored after the histogram's bins in the
// same buffer: per class, its threshold bin, the rest of its share left for
// the bin below it, and that bin's tie-break threshold.
#define SP_ADMISSION_PLAN_THRESHOLD SP_ADMISSION_BINS
#define SP_ADMISSION_PLAN_REMAINING (SP_ADMISSION_BINS + SP_ADMISSION_CLASSES)
#define SP_ADMISSION_PLAN_TIEBREAK (SP_ADMISSION_BINS + 2u * SP_ADMISSION_CLASSES)
#define SP_ADMISSION_BUFFER_SIZE (SP_ADMISSION_BINS + 3u * SP_ADMISSION_CLASSES)

SP_BEGIN_NAMESPACE

// How many indicators lie in bins [from, to).
SP_INLINE uint sp_admission_count(SP_ADMISSION_ARGS_DECL uint from, uint to) {
  uint count = 0u;
  for (uint b = from; b < to; ++b) count += admission_histogram[b];
  return count;
}

// The lowest bin of class c's section such that the indicators in it and
// above it (within the section) number at most `share`; the section's end
// when even its top bin holds more.
SP_INLINE uint sp_class_threshold(SP_ADMISSION_ARGS_DECL uint c, uint share) {
  uint first = c * SP_ADMISSION_LEVELS;
  uint admitted = 0u;
  uint threshold = first + SP_ADMISSION_LEVELS;
  for (uint b = first + SP_ADMISSION_LEVELS; b > first; --b) {
    uint more = admitted + admission_histogram[b - 1u];
    if (more > share) break;
    admitted = more;
    threshold = b - 1u;
  }
  return threshold;
}

// Each class's share of `quota` given how many indicators it has: an equal
// third each, what a class cannot use passed on to the others, the most
// important first (direct, through walls, reflected). Returns share[c].
SP_INLINE uint sp_class_share(uint quota, uint c, uint count0, uint count1, uint count2) {
  uint counts[3] = {count0, count1, count2};
  uint shares[3];
  uint base = quota / SP_ADMISSION_CLASSES;
  uint left = quota;
  for (uint k = 0u; k < 3u; ++k) {
    shares[k] = min(counts[k], base + (k < quota % SP_ADMISSION_CLASSES ? 1u : 0u));
    left -= shares[k];
  }
  for (uint k = 0u; k < 3u; ++k) {
    uint more = min(counts[k] - shares[k], left);
    shares[k] += more;
    left -= more;
  }
  return shares[c];
}

// Fills the plan's thresholds and remainders from the histogram of
// admission bins.
SP_INLINE void sp_plan_admission(SP_ADMISSION_ARGS_DECL_MUT uint quota) {
  uint count0 = sp_admission_count(SP_ADMISSION_ARGS 0u, SP_ADMISSION_LEVELS);
  uint count1 = sp_admission_count(SP_ADMISSION_ARGS SP_ADMISSION_LEVELS, 2u * SP_ADMISSION_LEVELS);
  uint count2 = sp_admission_count(SP_ADMISSION_ARGS 2u * SP_ADMISSION_LEVELS, SP_ADMISSION_BINS);
  for (uint c = 0u; c < SP_ADMISSION_CLASSES; ++c) {
    uint share = sp_class_share(quota, c, count0, count1, count2);
    uint threshold = sp_class_threshold(SP_ADMISSION_ARGS c, share);
    uint section_end = (c + 1u) * SP_ADMISSION_LEVELS;
    admission_histogram[SP_ADMISSION_PLAN_THRESHOLD + c] = threshold;
    admission_histogram[SP_ADMISSION_PLAN_REMAINING + c] =
        share - sp_admission_count(SP_ADMISSION_ARGS threshold, section_end);
  }
}

// With the histogram now counting tie-break bins of each class's
// overflowing bin, fills the plan's tie-break thresholds of classes
// [0, class_count) (all of them: SP_ADMISSION_CLASSES).
SP_INLINE void sp_plan_tiebreak(SP_ADMISSION_ARGS_DECL_MUT uint class_count) {
  for (uint c = 0u; c < class_count; ++c)
    admission_histogram[SP_ADMISSION_PLAN_TIEBREAK + c] =
        sp_class_threshold(SP_ADMISSION_ARGS c, admission_histogram[SP_ADMISSION_PLAN_REMAINING + c]);
}

// Whether an indicator in admission bin `bin`, tie-break bin `tiebreak`, is
// admitted under its step's plan: at or above its class's threshold, or in
// the bin just below it with a tie-break bin at or above that threshold.
SP_INLINE bool sp_admitted(SP_ADMISSION_ARGS_DECL uint bin, uint tiebreak) {
  uint c = bin / SP_ADMISSION_LEVELS;
  uint threshold = admission_histogram[SP_ADMISSION_PLAN_THRESHOLD + c];
  return bin >= threshold || (bin + 1u == threshold && tiebreak >= admission_histogram[SP_ADMISSION_PLAN_TIEBREAK + c]);
}

// Whether an indicator in bin `bin` is in its class's overflowing bin, the
// one whose tie-break bins are counted.
SP_INLINE bool sp_in_tiebreak_bin(SP_ADMISSION_ARGS_DECL uint bin) {
  return bin + 1u == admission_histogram[SP_ADMISSION_PLAN_THRESHOLD + bin / SP_ADMISSION_LEVELS];
}

SP_END_NAMESPACE

#endif  // SP_ADMISSION_H
