#include "io/atomic_file.h"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <string>
#include <system_error>
#include <unistd.h>

#include "soundpaint/result.h"

namespace sp {

AtomicFile::AtomicFile(std::filesystem::path target) : target_(std::move(target)) {
  if (target_.empty()) throw Exception(ErrorCode::Io, "output path is empty");
  std::error_code ec;
  if (std::filesystem::is_directory(target_, ec))
    throw Exception(ErrorCode::Io, "cannot write " + target_.string() + ": it is a directory");
  // pid + counter: unique among concurrent writers of this and other processes.
  static std::atomic<unsigned> counter{0};
  std::string temp = target_.string() + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  temporary_ = temp;
  file_ = std::fopen(temp.c_str(), "wbx");
  if (!file_) {
    temporary_.clear();
    throw Exception(ErrorCode::Io, "cannot write " + target_.string() + ": " + std::strerror(errno));
  }
}

AtomicFile::~AtomicFile() {
  if (file_) std::fclose(file_);
  if (!temporary_.empty()) {
    std::error_code ignored;
    std::filesystem::remove(temporary_, ignored);
  }
}

void AtomicFile::fail(const char* what) {
  int saved = errno;
  throw Exception(ErrorCode::Io,
                  "cannot write " + target_.string() + ": " + what + ": " + std::strerror(saved ? saved : EIO));
}

void AtomicFile::write(std::string_view bytes) {
  if (!file_) throw Exception(ErrorCode::Io, "cannot write " + target_.string() + ": already committed");
  errno = 0;
  if (std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size()) fail("write failed");
}

void AtomicFile::commit() {
  if (!file_) throw Exception(ErrorCode::Io, "cannot write " + target_.string() + ": already committed");
  errno = 0;
  bool flushed = std::fflush(file_) == 0 && ::fsync(::fileno(file_)) == 0;
  bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (!flushed || !closed) fail("flush failed");
  std::error_code ec;
  std::filesystem::rename(temporary_, target_, ec);
  if (ec) throw Exception(ErrorCode::Io, "cannot write " + target_.string() + ": " + ec.message());
  temporary_.clear();
}

}  // namespace sp
