#include "io/output_location.h"

#include <fcntl.h>
#include <limits.h>
#include <sys/vfs.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <deque>
#include <system_error>

#include "io/output_path.h"
#include "io/standard_streams.h"
#include "soundpaint/result.h"

namespace sp {
namespace {

namespace fs = std::filesystem;

// As the kernel's own limit on links followed in one lookup (ELOOP).
constexpr int kMaxSymlinkHops = 40;
// Filesystem magic numbers (linux/magic.h) of the pseudo file systems.
constexpr long kProcMagic = 0x9fa0;
constexpr long kSysfsMagic = 0x62656572;

[[noreturn]] void fail(const fs::path& path, const std::string& what) {
  throw Exception(ErrorCode::Io, "cannot write " + path.string() + ": " + what);
}

// A folder reached by the walk: held open, and its absolute path, kept by
// hand (every link on the way resolved, so ".." is its textual parent).
struct Folder {
  FileDescriptor fd;
  struct stat status {};
  fs::path path;
};

// /proc's links (/dev/stdout -> /proc/self/fd/1 -> wherever standard output
// goes) name another file's descriptor, not a place to put a new file: a
// rename there would replace whatever the shell redirected to.
bool under_pseudo_file_system(const fs::path& absolute) {
  for (const char* root : {"/proc", "/sys"}) {
    const fs::path prefix(root);
    if (std::mismatch(prefix.begin(), prefix.end(), absolute.begin(), absolute.end()).first == prefix.end())
      return true;
  }
  return false;
}

void refuse_pseudo_file_system(const fs::path& requested, const Folder& folder) {
  struct statfs fs_status {};
  const bool pseudo =
      ::fstatfs(folder.fd.get(), &fs_status) == 0 &&
      (static_cast<long>(fs_status.f_type) == kProcMagic || static_cast<long>(fs_status.f_type) == kSysfsMagic);
  if (pseudo || under_pseudo_file_system(folder.path))
    fail(requested, "it leads into /proc or /sys; give - for standard output");
}

Folder open_folder(const fs::path& requested, int at, const char* name, fs::path path) {
  Folder folder{FileDescriptor(::openat(at, name, O_PATH | O_DIRECTORY | O_CLOEXEC)), {}, std::move(path)};
  if (!folder.fd.valid() || ::fstat(folder.fd.get(), &folder.status) != 0) {
    const int error = errno;
    fail(requested, "its folder " + folder.path.string() + ": " + std::strerror(error));
  }
  refuse_pseudo_file_system(requested, folder);
  return folder;
}

Folder start_folder(const fs::path& requested, const std::string& text) {
  if (!text.empty() && text.front() == '/') return open_folder(requested, AT_FDCWD, "/", "/");
  std::error_code ec;
  fs::path here = fs::current_path(ec);
  if (ec) fail(requested, "the current folder: " + ec.message());
  return open_folder(requested, AT_FDCWD, ".", std::move(here));
}

// Puts the components of `text` before the pending ones. A trailing '/'
// adds ".": the path then names a directory.
void push_front_components(std::deque<std::string>& pending, const std::string& text) {
  std::deque<std::string> parts;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t slash = text.find('/', start);
    if (slash == std::string::npos) slash = text.size();
    if (slash > start) parts.push_back(text.substr(start, slash - start));
    start = slash + 1;
  }
  if (!text.empty() && text.back() == '/') parts.push_back(".");
  pending.insert(pending.begin(), parts.begin(), parts.end());
}

bool sticky_and_world_writable(const struct stat& folder) {
  return (folder.st_mode & S_ISVTX) != 0 && (folder.st_mode & S_IWOTH) != 0;
}

// The kernel's fs.protected_symlinks rule, applied whatever the sysctl says.
void refuse_foreign_link(const fs::path& requested, const Folder& folder, const struct stat& link,
                         const std::string& name) {
  if (!sticky_and_world_writable(folder.status) || link.st_uid == ::geteuid() || link.st_uid == folder.status.st_uid)
    return;
  fail(requested, "the symbolic link " + (folder.path / name).string() + " belongs to another user (uid " +
                      std::to_string(link.st_uid) +
                      ") in a sticky world-writable folder, where links of other users are not followed");
}

std::string read_link(const fs::path& requested, int link, const fs::path& where) {
  char target[PATH_MAX];
  const ssize_t length = ::readlinkat(link, "", target, sizeof target);
  if (length < 0) {
    const int error = errno;
    fail(requested, "cannot read the symbolic link " + where.string() + ": " + std::strerror(error));
  }
  if (length == 0 || static_cast<std::size_t>(length) == sizeof target)
    fail(requested, "the symbolic link " + where.string() + " is empty or too long");
  return std::string(target, static_cast<std::size_t>(length));
}

}  // namespace

OutputLocation locate_output(const fs::path& path) {
  OutputLocation out;
  if (names_stdout(path)) {
    if (standard_output_closed()) fail(path, "standard output is closed");
    out.to_stdout = true;
    return out;
  }
  if (path.empty()) throw Exception(ErrorCode::Io, "output path is empty");
  const std::string text = path.string();
  Folder folder = start_folder(path, text);
  std::deque<std::string> pending;
  push_front_components(pending, text);
  int hops = 0;
  std::string name;
  for (;;) {
    if (pending.empty()) fail(path, "it is a directory");
    name = pending.front();
    pending.pop_front();
    const bool last = pending.empty();
    if (name == "." || name == "..") {
      if (last) fail(path, "it is a directory");
      if (name == "..") folder = open_folder(path, folder.fd.get(), "..", folder.path.parent_path());
      continue;
    }
    // O_PATH | O_NOFOLLOW: the entry itself, link or not, opened once; its
    // status and its target are read from this descriptor.
    FileDescriptor entry(::openat(folder.fd.get(), name.c_str(), O_PATH | O_NOFOLLOW | O_CLOEXEC));
    if (!entry.valid()) {
      const int error = errno;
      if (last && error == ENOENT) break;  // a new file
      if (last) fail(path, std::strerror(error));
      fail(path, "its folder " + (folder.path / name).string() + ": " + std::strerror(error));
    }
    struct stat status {};
    if (::fstat(entry.get(), &status) != 0) fail(path, std::strerror(errno));
    if (S_ISLNK(status.st_mode)) {
      refuse_foreign_link(path, folder, status, name);
      if (++hops > kMaxSymlinkHops) fail(path, "too many levels of symbolic links");
      const std::string target = read_link(path, entry.get(), folder.path / name);
      if (target.front() == '/') folder = open_folder(path, AT_FDCWD, "/", "/");
      push_front_components(pending, target);
      continue;
    }
    if (S_ISDIR(status.st_mode)) {
      if (last) fail(path, "it is a directory");
      folder = Folder{std::move(entry), status, folder.path / name};
      refuse_pseudo_file_system(path, folder);
      continue;
    }
    if (!last) fail(path, "its folder " + (folder.path / name).string() + ": " + std::strerror(ENOTDIR));
    if (!S_ISREG(status.st_mode))
      fail(path, "not a regular file (a device, FIFO or socket); give - for standard output");
    out.existing = status;
    break;
  }
  out.file = folder.path / name;
  out.name = std::move(name);
  out.folder = std::move(folder.fd);
  out.folder_status = folder.status;
  if (out.existing) check_replaceable(path, out.folder_status, *out.existing);
  return out;
}

void check_replaceable(const fs::path& path, const struct stat& folder_status, const struct stat& existing) {
  if (existing.st_nlink > 1)
    fail(path, "it has " + std::to_string(existing.st_nlink) +
                   " hard links, and replacing it would split them; remove the other links or write elsewhere");
  if (sticky_and_world_writable(folder_status) && existing.st_uid != ::geteuid() &&
      existing.st_uid != folder_status.st_uid)
    fail(path, "it belongs to another user (uid " + std::to_string(existing.st_uid) +
                   ") in a sticky world-writable folder, and is not replaced");
}

std::optional<struct stat> regular_file_now(const fs::path& path, int folder, const std::string& name) {
  struct stat status {};
  if (::fstatat(folder, name.c_str(), &status, AT_SYMLINK_NOFOLLOW) != 0) {
    if (errno == ENOENT) return std::nullopt;
    fail(path, std::strerror(errno));
  }
  if (!S_ISREG(status.st_mode)) fail(path, "it was replaced by something that is not a regular file meanwhile");
  return status;
}

}  // namespace sp
