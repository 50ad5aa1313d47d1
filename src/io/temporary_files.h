// Temporary output files that a fatal signal must not leave behind.
//
// AtomicFile writes each output to a temporary file beside its target; a run
// stopped by Ctrl-C (SIGINT), SIGTERM, SIGHUP or a broken pipe (SIGPIPE)
// would leave it there, hundreds of megabytes for a long simulation. Every
// live temporary file is recorded here, in a fixed table that a signal
// handler may read: no allocation, no lock, only atomics, unlinkat() and
// sigaction()/raise() in the handler (all async-signal-safe).
#pragma once

namespace sp {

// Records the temporary file `name` (one path component, at most
// kMaxTemporaryNameBytes bytes) in the folder open as `folder_fd`, which
// must stay open until unregister_temporary_file(). Returns the slot to
// pass there. Throws sp::Exception(Io) when the table is full.
int register_temporary_file(int folder_fd, const char* name);

// Forgets the slot. Call after the file is renamed or removed: a signal in
// between then only removes a name that no longer exists.
void unregister_temporary_file(int slot) noexcept;

// The longest temporary file name the table holds (NAME_MAX).
inline constexpr int kMaxTemporaryNameBytes = 255;

// Installs the handler for SIGINT, SIGTERM, SIGHUP and SIGPIPE: it removes
// every recorded temporary file, then dies of the same signal (default
// action, so the shell sees status 128 + signal). A signal ignored when the
// process started (nohup, a parent ignoring SIGPIPE) stays ignored. Call
// once, early in main(), before threads start.
void remove_temporary_files_on_fatal_signals();

}  // namespace sp
