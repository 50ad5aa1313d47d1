#include "io/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <string>
#include <system_error>

#include "io/output_path.h"
#include "soundpaint/result.h"

namespace sp {

AtomicFile::AtomicFile(std::filesystem::path target) : requested_(std::move(target)) {
  const OutputTarget resolved = resolve_output(requested_);
  if (resolved.to_stdout) {
    to_stdout_ = true;
    file_ = stdout;
    return;
  }
  target_ = resolved.file;
  // pid + counter: unique among concurrent writers of this and other processes.
  static std::atomic<unsigned> counter{0};
  std::string temp = target_.string() + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  temporary_ = temp;
  file_ = std::fopen(temp.c_str(), "wbx");
  if (!file_) {
    temporary_.clear();
    throw Exception(ErrorCode::Io, "cannot write " + requested_.string() + ": " + std::strerror(errno));
  }
}

AtomicFile::~AtomicFile() {
  if (to_stdout_) return;  // standard output stays open
  if (file_) std::fclose(file_);
  if (!temporary_.empty()) {
    std::error_code ignored;
    std::filesystem::remove(temporary_, ignored);
  }
}

void AtomicFile::fail(const char* what) {
  int saved = errno;
  throw Exception(ErrorCode::Io,
                  "cannot write " + requested_.string() + ": " + what + ": " + std::strerror(saved ? saved : EIO));
}

void AtomicFile::write(std::string_view bytes) {
  if (!file_) throw Exception(ErrorCode::Io, "cannot write " + requested_.string() + ": already committed");
  errno = 0;
  if (std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size()) fail("write failed");
}

void AtomicFile::commit() {
  if (!file_) throw Exception(ErrorCode::Io, "cannot write " + requested_.string() + ": already committed");
  errno = 0;
  if (to_stdout_) {
    const bool flushed = std::fflush(file_) == 0;
    file_ = nullptr;
    if (!flushed) fail("flush failed");
    return;
  }
  bool flushed = std::fflush(file_) == 0 && ::fsync(::fileno(file_)) == 0;
  bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (!flushed || !closed) fail("flush failed");
  std::error_code ec;
  std::filesystem::rename(temporary_, target_, ec);
  if (ec) throw Exception(ErrorCode::Io, "cannot write " + requested_.string() + ": " + ec.message());
  temporary_.clear();
}

}  // namespace sp
