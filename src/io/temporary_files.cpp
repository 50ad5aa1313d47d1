#include "io/temporary_files.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cstring>
#include <string>

#include "soundpaint/result.h"

namespace sp {
namespace {

// More than any command keeps open at once (simulate: two outputs).
constexpr int kSlots = 16;

// A slot's life: Free -> Filling (register writes it) -> Live -> Free
// (unregister), or Live -> Claimed once the handler has taken it; a claimed
// slot is never written again, so the handler never reads a name while it
// changes.
enum SlotState : int { kFree, kFilling, kLive, kClaimed };
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler may only use lock-free atomics");
static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler may only use lock-free atomics");

struct Slot {
  std::atomic<int> state{kFree};
  int folder_fd = -1;
  char name[kMaxTemporaryNameBytes + 1] = {};
};

Slot g_slots[kSlots];
// Two signals may land on two threads at once: the second waits for the
// first to finish removing files rather than kill the process mid-way.
std::atomic<bool> g_removal_started{false};
std::atomic<bool> g_removal_done{false};

constexpr int kFatalSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGPIPE};

void remove_temporary_files_and_die(int signo) {
  if (!g_removal_started.exchange(true)) {
    for (Slot& slot : g_slots) {
      int live = kLive;
      if (slot.state.compare_exchange_strong(live, kClaimed)) (void)::unlinkat(slot.folder_fd, slot.name, 0);
    }
    g_removal_done.store(true);
  } else {
    while (!g_removal_done.load()) {
    }
  }
  // Die of the same signal, so the parent sees what killed us: the default
  // action, then the signal again, which is blocked while this handler runs
  // and is delivered as soon as it is unblocked.
  struct sigaction default_action {};
  default_action.sa_handler = SIG_DFL;
  sigemptyset(&default_action.sa_mask);
  (void)::sigaction(signo, &default_action, nullptr);
  (void)::raise(signo);
  sigset_t just_this;
  sigemptyset(&just_this);
  sigaddset(&just_this, signo);
  (void)::sigprocmask(SIG_UNBLOCK, &just_this, nullptr);
  ::_exit(128 + signo);  // not reached: every one of these signals terminates
}

}  // namespace

int register_temporary_file(int folder_fd, const char* name) {
  const std::size_t length = std::strlen(name);
  if (length > static_cast<std::size_t>(kMaxTemporaryNameBytes))
    throw Exception(ErrorCode::Io, std::string("temporary file name too long: ") + name);
  for (int i = 0; i < kSlots; ++i) {
    Slot& slot = g_slots[i];
    int free = kFree;
    if (!slot.state.compare_exchange_strong(free, kFilling)) continue;
    slot.folder_fd = folder_fd;
    std::memcpy(slot.name, name, length + 1);
    slot.state.store(kLive);
    return i;
  }
  throw Exception(ErrorCode::Io, "more than " + std::to_string(kSlots) + " output files open at once");
}

void unregister_temporary_file(int slot) noexcept {
  if (slot < 0 || slot >= kSlots) return;
  int live = kLive;
  // Fails only when the handler has claimed it: the process is dying.
  (void)g_slots[slot].state.compare_exchange_strong(live, kFree);
}

void remove_temporary_files_on_fatal_signals() {
  for (int signo : kFatalSignals) {
    struct sigaction current {};
    if (::sigaction(signo, nullptr, &current) != 0 || current.sa_handler == SIG_IGN) continue;
    struct sigaction action {};
    action.sa_handler = remove_temporary_files_and_die;
    // All four blocked while one is handled: a second Ctrl-C waits.
    sigemptyset(&action.sa_mask);
    for (int other : kFatalSignals) sigaddset(&action.sa_mask, other);
    (void)::sigaction(signo, &action, nullptr);
  }
}

}  // namespace sp
