// Arrays of a BVH build (millions of 32-byte records and nodes) backed by
// transparent huge pages where the system offers them.
//
// Why: a build writes every page of its arrays once, right after allocating
// them, so on a 1M-triangle scene it takes ~40,000 first-touch page faults of
// 4 KiB. In a virtual machine each fault is expensive: on the 2-vCPU
// benchmark machine they cost more than the build's own work (the 1M build
// fell from ~730 to ~190 ms once its arrays sat on 2 MiB pages;
// bench/RESULTS.md section 12). Embree's allocator does the same.
//
// Small arrays (below kLargeArrayBytes) come from the ordinary heap: a huge
// page is only worth it, and only aligned, for arrays of several of them.
// Elsewhere than Linux the alignment is kept and the hint is skipped.
#pragma once

#include <cstddef>
#include <limits>
#include <new>
#include <utility>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

#include "core/default_init_allocator.h"

namespace sp {

// Size of a transparent huge page on x86-64 and most Arm64 kernels.
inline constexpr std::size_t kHugePageBytes = std::size_t{2} << 20;
// From this size on, an array is aligned to and rounded up to huge pages.
inline constexpr std::size_t kLargeArrayBytes = 2u * kHugePageBytes;

template <class T>
struct LargeArrayAllocator {
  using value_type = T;

  LargeArrayAllocator() = default;
  template <class U>
  LargeArrayAllocator(const LargeArrayAllocator<U>&) noexcept {}

  T* allocate(std::size_t n) {
    if (n > max_size()) throw std::bad_array_new_length();
    const std::size_t bytes = n * sizeof(T);
    if (bytes < kLargeArrayBytes) return static_cast<T*>(::operator new (bytes, std::align_val_t{alignof(T)}));
    const std::size_t rounded = round_up(bytes);
    void* p = ::operator new (rounded, std::align_val_t{kHugePageBytes});
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    // A hint: where huge pages are off or unavailable it fails harmlessly.
    (void)madvise(p, rounded, MADV_HUGEPAGE);
#endif
    return static_cast<T*>(p);
  }

  // The unsized aligned delete: the sized one is declared only where the
  // compiler enables sized deallocation (clang before 19 does not).
  void deallocate(T* p, std::size_t n) noexcept {
    const std::size_t bytes = n * sizeof(T);
    ::operator delete (p, std::align_val_t{bytes < kLargeArrayBytes ? alignof(T) : kHugePageBytes});
  }

  // resize() and the sizing constructor default-initialise, as `new T[n]`
  // does, rather than zero: trivial elements are left unwritten. The build
  // writes each element once, on two threads; zeroing first was a serial
  // pass over the whole array that cost more than the writing (1M
  // triangles: the gather took 37 ms on two threads against 21 on one).
  // Write every element that resize() adds (core/default_init_allocator.h).
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    default_init_construct(p, std::forward<Args>(args)...);
  }

  // Leaves room to round up to a whole huge page without overflow.
  static constexpr std::size_t max_size() noexcept {
    return (std::numeric_limits<std::size_t>::max() - kHugePageBytes) / sizeof(T);
  }

 private:
  static std::size_t round_up(std::size_t bytes) { return (bytes + kHugePageBytes - 1u) & ~(kHugePageBytes - 1u); }
};

// Stateless: any two allocate and free each other's arrays.
template <class T, class U>
bool operator==(const LargeArrayAllocator<T>&, const LargeArrayAllocator<U>&) noexcept {
  return true;
}

template <class T>
using LargeArray = std::vector<T, LargeArrayAllocator<T>>;

}  // namespace sp
