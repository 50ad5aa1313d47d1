#include "io/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <optional>
#include <string>
#include <utility>

#include "io/temporary_files.h"
#include "soundpaint/result.h"

namespace sp {
namespace {

// Names taken (by a stale file of an earlier process with our pid) before
// giving up.
constexpr int kNameAttempts = 8;

bool same_file(const struct stat& a, const struct stat& b) { return a.st_dev == b.st_dev && a.st_ino == b.st_ino; }

std::string error_text(int error) { return std::strerror(error ? error : EIO); }

}  // namespace

AtomicFile::AtomicFile(std::filesystem::path target)
    : requested_(std::move(target)), target_(locate_output(requested_)) {
  if (target_.to_stdout) {
    file_ = stdout;
    return;
  }
  try {
    create_temporary();
    if (target_.existing) keep_owner_and_mode(*target_.existing);
  } catch (...) {
    discard();
    throw;
  }
}

AtomicFile::~AtomicFile() { discard(); }

void AtomicFile::discard() noexcept {
  if (target_.to_stdout) return;  // standard output stays open
  if (file_) std::fclose(std::exchange(file_, nullptr));
  // Removed before it leaves the registry: a signal in between only
  // removes a name that is already gone.
  if (!temporary_.empty()) (void)::unlinkat(target_.folder.get(), temporary_.c_str(), 0);
  temporary_.clear();
  if (registry_slot_ >= 0) unregister_temporary_file(std::exchange(registry_slot_, -1));
}

void AtomicFile::fail(const std::string& what) {
  throw Exception(ErrorCode::Io, "cannot write " + requested_.string() + ": " + what);
}

void AtomicFile::create_temporary() {
  // pid + counter: unique among concurrent writers of this and other
  // processes; the target's name is cut so that the whole fits NAME_MAX.
  static std::atomic<unsigned> counter{0};
  const std::string pid_part = ".tmp-" + std::to_string(::getpid()) + "-";
  for (int attempt = 0; attempt < kNameAttempts; ++attempt) {
    const std::string suffix = pid_part + std::to_string(counter++);
    const std::string name = target_.name.substr(0, kMaxTemporaryNameBytes - suffix.size()) + suffix;
    // Recorded before it exists, so that no signal finds it unrecorded.
    registry_slot_ = register_temporary_file(target_.folder.get(), name.c_str());
    // Readable by us alone until it takes the replaced file's mode.
    const mode_t mode = target_.existing ? 0600 : 0666;
    const int fd =
        ::openat(target_.folder.get(), name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, mode);
    if (fd >= 0) {
      temporary_ = name;
      file_ = ::fdopen(fd, "wb");
      if (!file_) {
        const int error = errno;
        ::close(fd);
        fail(error_text(error));
      }
      return;
    }
    const int error = errno;
    unregister_temporary_file(std::exchange(registry_slot_, -1));
    if (error != EEXIST) fail(error_text(error));
  }
  fail("no free name for a temporary file beside it");
}

// A replacement that silently changed a file's owner or mode (another
// user's 0600 file turned into root's 0644 one) would surprise its owner.
void AtomicFile::keep_owner_and_mode(const struct stat& replaced) {
  const int fd = ::fileno(file_);
  struct stat mine {};
  if (::fstat(fd, &mine) != 0) fail(error_text(errno));
  const uid_t uid = replaced.st_uid != mine.st_uid ? replaced.st_uid : static_cast<uid_t>(-1);
  const gid_t gid = replaced.st_gid != mine.st_gid ? replaced.st_gid : static_cast<gid_t>(-1);
  if ((uid != static_cast<uid_t>(-1) || gid != static_cast<gid_t>(-1)) && ::fchown(fd, uid, gid) != 0) {
    const std::string why = error_text(errno);
    fail("it belongs to uid " + std::to_string(replaced.st_uid) + ", gid " + std::to_string(replaced.st_gid) +
         ", and its replacement could not keep that owner (" + why + "); write elsewhere");
  }
  // Permission bits only: never a set-user-ID bit on our output.
  if (::fchmod(fd, replaced.st_mode & 0777) != 0) fail(error_text(errno));
}

void AtomicFile::write(std::string_view bytes) {
  if (!file_) fail("already committed");
  errno = 0;
  if (std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size()) fail("write failed: " + error_text(errno));
}

void AtomicFile::commit() {
  if (!file_) fail("already committed");
  errno = 0;
  const bool flushed = std::fflush(file_) == 0 && !std::ferror(file_);
  const int flush_error = errno;
  if (target_.to_stdout) {
    file_ = nullptr;
    if (!flushed) fail("flush failed: " + error_text(flush_error));
    return;
  }
  if (!flushed) fail("flush failed: " + error_text(flush_error));
  // What is under the name now, which may differ from what was there when
  // the run started: the same rules apply to it.
  const std::optional<struct stat> replaced = regular_file_now(requested_, target_.folder.get(), target_.name);
  if (replaced) {
    check_replaceable(requested_, target_.folder_status, *replaced);
    if (!target_.existing || !same_file(*replaced, *target_.existing)) keep_owner_and_mode(*replaced);
  }
  if (::fsync(::fileno(file_)) != 0) fail("flush failed: " + error_text(errno));
  if (std::fclose(std::exchange(file_, nullptr)) != 0) fail("flush failed: " + error_text(errno));
  rename_over_target(replaced.has_value());
  unregister_temporary_file(std::exchange(registry_slot_, -1));
  temporary_.clear();
}

void AtomicFile::rename_over_target(bool replacing) {
  const int folder = target_.folder.get();
  if (!replacing) {
    // The name was free a moment ago: take it only if it still is, so that
    // a file put there meanwhile is never replaced unchecked.
    if (::renameat2(folder, temporary_.c_str(), folder, target_.name.c_str(), RENAME_NOREPLACE) == 0) return;
    if (errno == EEXIST) fail("a file appeared under its name while it was written, and is not replaced");
    // A file system without RENAME_NOREPLACE gets a plain rename.
    if (errno != EINVAL && errno != ENOSYS) fail(error_text(errno));
  }
  if (::renameat(folder, temporary_.c_str(), folder, target_.name.c_str()) != 0) fail(error_text(errno));
}

}  // namespace sp
