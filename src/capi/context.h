// sp_context: what a host decides once for every object it creates through
// the C API (soundpaint.h, "Contexts"): where messages go, where the C
// layer's handle memory comes from, how many threads a simulation may use.
// Objects keep their context alive (a reference count), so the host may
// destroy the context and its objects in any order.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <string>
#include <utility>

#include "soundpaint/soundpaint.h"

struct sp_context {
  sp_log_callback log = nullptr;
  void* log_user_data = nullptr;
  sp_allocator allocator{};  // both callbacks set, or both NULL (malloc and free)
  std::uint32_t max_threads = 0;
  std::uint32_t flags = 0;
  // The host's reference (until sp_context_destroy) plus one per object.
  std::atomic<std::uint32_t> references{1};
};

namespace sp::capi {

// The process-wide context of the entry points without one: no log,
// malloc, one thread per core. Never destroyed.
sp_context& default_context() noexcept;

// Memory from the context's allocator; throws std::bad_alloc when it
// returns NULL. release() gives it back the same way.
void* allocate(sp_context& context, std::size_t size, std::size_t alignment);
void release(sp_context& context, void* memory) noexcept;

// Sends `message` to the context's log callback, if any. Never throws.
void log(const sp_context& context, sp_log_level level, const char* message) noexcept;

// Drops one reference; the last one frees the context through its allocator.
void release_reference(sp_context* context) noexcept;

// A counted reference to a context, as every handle holds one.
class ContextRef {
 public:
  ContextRef() = default;
  explicit ContextRef(sp_context& context) noexcept : context_(&context) {
    context_->references.fetch_add(1, std::memory_order_relaxed);
  }
  ContextRef(const ContextRef& other) noexcept : ContextRef() {
    if (other.context_ != nullptr) *this = ContextRef(*other.context_);
  }
  ContextRef(ContextRef&& other) noexcept : context_(std::exchange(other.context_, nullptr)) {}
  ContextRef& operator=(ContextRef other) noexcept {
    std::swap(context_, other.context_);
    return *this;
  }
  ~ContextRef() {
    if (context_ != nullptr) release_reference(context_);
  }
  sp_context& operator*() const noexcept { return *context_; }
  sp_context* operator->() const noexcept { return context_; }

 private:
  sp_context* context_ = nullptr;
};

// Destroys a handle made by make_handle and returns its memory to its
// context's allocator, keeping the context alive until then.
template <class T>
void delete_handle(T* handle) noexcept {
  if (handle == nullptr) return;
  const ContextRef context = handle->context;
  handle->~T();
  release(*context, handle);
}

template <class T>
struct HandleDeleter {
  void operator()(T* handle) const noexcept { delete_handle(handle); }
};
template <class T>
using HandlePtr = std::unique_ptr<T, HandleDeleter<T>>;

// A new handle of type T (which has a ContextRef member `context`) in
// memory from `context`'s allocator: the C layer's own allocations route
// through the host's callbacks.
template <class T>
HandlePtr<T> make_handle(sp_context& context) {
  void* memory = allocate(context, sizeof(T), alignof(T));
  T* handle = nullptr;
  try {
    handle = new (memory) T{};
  } catch (...) {
    release(context, memory);
    throw;
  }
  handle->context = ContextRef(context);
  return HandlePtr<T>(handle);
}

// Throws InvalidArgument unless `size` is the size of a sized struct this
// library knows (`known`): `what` names the struct ("options").
void require_struct_size(std::uint32_t size, std::size_t known, const char* function, const char* what);

}  // namespace sp::capi
