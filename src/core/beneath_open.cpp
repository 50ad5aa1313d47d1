#include "core/beneath_open.h"

#include <fcntl.h>
#include <limits.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdint>
#include <string>
#include <vector>

#ifdef SYS_openat2
#include <linux/openat2.h>
#endif

namespace sp {
namespace {

OpenResult failed(int error) { return OpenResult{FileDescriptor(), error}; }

// The components of `path` still to resolve, pushed so that the first is on
// top (at the back). Empty components ("a//b") mean nothing; a trailing
// '/' says the last component must be a directory, which a trailing "."
// checks.
void push_components(std::vector<std::string>& pending, std::string_view path) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (start < path.size()) {
    std::size_t end = path.find('/', start);
    if (end == std::string_view::npos) end = path.size();
    if (end > start) parts.emplace_back(path.substr(start, end - start));
    start = end + 1;
  }
  if (!path.empty() && path.back() == '/') parts.emplace_back(".");
  pending.insert(pending.end(), parts.rbegin(), parts.rend());
}

// The text of the symbolic link `link` (an O_PATH | O_NOFOLLOW descriptor
// of the link itself, so that it is the link just looked at that is read).
int read_link(int link, std::string& target) {
  std::string text(PATH_MAX, '\0');
  const ::ssize_t length = ::readlinkat(link, "", text.data(), text.size());
  if (length < 0) return errno;
  if (static_cast<std::size_t>(length) == text.size()) return ENAMETOOLONG;
  text.resize(static_cast<std::size_t>(length));
  target = std::move(text);
  return 0;
}

}  // namespace

OpenResult open_beneath_by_walk(int root, std::string_view path, int flags) {
  if (path.find('\0') != std::string_view::npos) return failed(EINVAL);
  if (path.empty()) return failed(ENOENT);
  if (path.front() == '/') return failed(EXDEV);

  // The directories entered below `root`, innermost last: ".." returns to
  // the one before, the descriptor this walk came through, never to a
  // parent looked up again (which a rename could have changed).
  std::vector<FileDescriptor> trail;
  const auto here = [&] { return trail.empty() ? root : trail.back().get(); };
  std::vector<std::string> pending;
  push_components(pending, path);
  int links = 0;

  while (!pending.empty()) {
    std::string name = std::move(pending.back());
    pending.pop_back();
    const bool last = pending.empty();
    const bool climbs = name == "..";
    if (climbs) {
      if (trail.empty()) return failed(EXDEV);
      trail.pop_back();
    }
    // "." and ".." name the directory the walk is now in.
    const bool names_here = climbs || name == ".";
    if (names_here && !last) continue;

    if (!names_here) {
      // O_PATH | O_NOFOLLOW opens nothing for real and follows nothing: it
      // pins the entry, link or not, so that what is checked is what is used.
      FileDescriptor entry(::openat(here(), name.c_str(), O_PATH | O_NOFOLLOW | O_CLOEXEC));
      if (!entry.valid()) return failed(errno);
      struct stat status {};
      if (::fstat(entry.get(), &status) != 0) return failed(errno);
      if (S_ISLNK(status.st_mode)) {
        if (++links > kMaxSymbolicLinks) return failed(ELOOP);
        std::string target;
        if (const int error = read_link(entry.get(), target); error != 0) return failed(error);
        if (target.empty()) return failed(ENOENT);
        if (target.front() == '/') return failed(EXDEV);
        push_components(pending, target);  // resolved from the link's own folder, here()
        continue;
      }
      if (!last) {
        if (!S_ISDIR(status.st_mode)) return failed(ENOTDIR);
        trail.push_back(std::move(entry));
        continue;
      }
    }

    // The last component, opened as asked from the directory just checked,
    // still without following: it is the entry looked at, or whatever
    // replaced it in this same directory, which is looked at again.
    FileDescriptor opened(::openat(here(), names_here ? "." : name.c_str(), flags | O_NOFOLLOW | O_CLOEXEC));
    bool became_link = !opened.valid() && errno == ELOOP;
    if (!opened.valid() && !became_link) return failed(errno);
    if (opened.valid() && (flags & O_PATH) != 0) {
      struct stat status {};
      if (::fstat(opened.get(), &status) != 0) return failed(errno);
      became_link = S_ISLNK(status.st_mode);
    }
    if (!became_link) return OpenResult{std::move(opened), 0};
    if (++links > kMaxSymbolicLinks) return failed(ELOOP);
    pending.push_back(std::move(name));
  }
  return failed(ENOENT);  // not reached: the last component always returns
}

OpenResult open_beneath_by_openat2(int root, std::string_view path, int flags) {
#ifdef SYS_openat2
  if (path.find('\0') != std::string_view::npos) return failed(EINVAL);
  const std::string text(path);
  ::open_how how{};
  how.flags = static_cast<std::uint64_t>(static_cast<unsigned>(flags | O_CLOEXEC));
  how.resolve = RESOLVE_BENEATH | RESOLVE_NO_MAGICLINKS;
  const long fd = ::syscall(SYS_openat2, root, text.c_str(), &how, sizeof how);
  if (fd < 0) return failed(errno);
  return OpenResult{FileDescriptor(static_cast<int>(fd)), 0};
#else
  (void)root, (void)path, (void)flags;
  return failed(ENOSYS);
#endif
}

OpenResult open_beneath(int root, std::string_view path, int flags) {
  // Learnt once: a kernel without openat2 does not grow one.
  static std::atomic<bool> kernel_lacks_openat2{false};
  if (!kernel_lacks_openat2.load(std::memory_order_relaxed)) {
    OpenResult opened = open_beneath_by_openat2(root, path, flags);
    if (opened.error == ENOSYS) kernel_lacks_openat2.store(true, std::memory_order_relaxed);
    // EPERM: a seccomp filter that refuses syscalls it does not know (a
    // real EPERM comes back from the walk too). EAGAIN: a rename raced with
    // a ".." step, which the walk resolves through the descriptors it holds.
    if (opened.error != ENOSYS && opened.error != EPERM && opened.error != EAGAIN) return opened;
  }
  return open_beneath_by_walk(root, path, flags);
}

}  // namespace sp
