// Opening a path that a stranger wrote, without ever leaving a folder.
//
// A check on a path and a later open of the same path can see two different
// files: whoever controls the folder can swap a subfolder for a symbolic
// link in between. So the folder is opened once, and every path is resolved
// from that descriptor, each step from the descriptor the previous step
// checked: the check is the open, and whatever the descriptor returned is,
// it was beneath the folder when it was opened.
//
// Linux's openat2(2) does this in the kernel (RESOLVE_BENEATH); where it is
// missing (before Linux 5.6, or refused by a seccomp filter) the same rules
// are applied by walking the path one component at a time with
// openat(O_NOFOLLOW), reading each symbolic link's text and resolving it
// ourselves.
#pragma once

#include <string_view>

#include "core/file_descriptor.h"

namespace sp {

// A descriptor, or the errno that says why there is none.
struct OpenResult {
  FileDescriptor fd;
  int error = 0;  // 0 when fd is valid
};

// Symbolic links followed in one resolution before it counts as a loop
// (ELOOP): Linux's own limit, so both ways agree.
inline constexpr int kMaxSymbolicLinks = 40;

// Opens `path`, relative to the directory `root` (a descriptor, O_PATH is
// enough; not owned), with open(2) `flags` (O_CLOEXEC is always added;
// O_CREAT and O_TMPFILE are not supported), like openat(2) except that no
// step of the resolution leaves `root`:
//  - symbolic links are followed only while they stay beneath `root`:
//    relative targets only, resolved where the link lies;
//  - ".." may climb back up to `root` but never above it;
//  - magic links (/proc/<pid>/fd/...) are never followed.
// Errors, as openat2(2) reports them with RESOLVE_BENEATH |
// RESOLVE_NO_MAGICLINKS: EXDEV when `path` is absolute, when ".." climbs
// above `root` or a link leads out of it or has an absolute target; ELOOP
// after kMaxSymbolicLinks links; ENOENT (also for an empty path), ENOTDIR,
// EACCES, ... as openat(2). Thread-safe; uses openat2 where the kernel
// allows it, else open_beneath_by_walk.
OpenResult open_beneath(int root, std::string_view path, int flags);

// The two ways open_beneath works, for tests. The first reports ENOSYS
// where this build or the kernel lacks openat2 (EPERM under some seccomp
// filters); the second works everywhere. Where both run, both answer the
// same, except that openat2 may fail with EAGAIN when a rename races with a
// ".." step (open_beneath then walks instead).
OpenResult open_beneath_by_openat2(int root, std::string_view path, int flags);
OpenResult open_beneath_by_walk(int root, std::string_view path, int flags);

}  // namespace sp
