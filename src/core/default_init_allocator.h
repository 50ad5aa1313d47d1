// A vector whose resize() leaves trivial elements unwritten, as `new T[n]`
// does, instead of zeroing them: for arrays whose every new element is
// written next, where zeroing first is a pass that only costs.
//
// Write every element that resize() adds: builds with assertions fill them
// with 0xFF bytes first (NaN floats, all-ones indices), so that an element
// left unwritten shows in the tests instead of reading as zero.
#pragma once

#include <cstring>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace sp {

// Placement construction as a default-initialising allocator does it: with
// no arguments, `new (p) U` (trivial types left unwritten; 0xFF under
// assertions); otherwise `new (p) U(args...)`.
template <class U, class... Args>
void default_init_construct(U* p, Args&&... args) {
  if constexpr (sizeof...(Args) == 0) {
#ifndef NDEBUG
    if constexpr (std::is_trivially_default_constructible_v<U>) std::memset(static_cast<void*>(p), 0xFF, sizeof(U));
#endif
    ::new (static_cast<void*>(p)) U;
  } else {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
}

// std::allocator's memory with default_init_construct.
template <class T>
struct DefaultInitAllocator {
  using value_type = T;

  DefaultInitAllocator() = default;
  template <class U>
  DefaultInitAllocator(const DefaultInitAllocator<U>&) noexcept {}

  T* allocate(std::size_t n) { return std::allocator<T>{}.allocate(n); }
  void deallocate(T* p, std::size_t n) noexcept { std::allocator<T>{}.deallocate(p, n); }

  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    default_init_construct(p, std::forward<Args>(args)...);
  }
};

// Stateless: any two allocate and free each other's arrays.
template <class T, class U>
bool operator==(const DefaultInitAllocator<T>&, const DefaultInitAllocator<U>&) noexcept {
  return true;
}

template <class T>
using DefaultInitVector = std::vector<T, DefaultInitAllocator<T>>;

}  // namespace sp
