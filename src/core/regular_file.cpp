#include "core/regular_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

namespace sp {
namespace {

// Closes the descriptor on every path out, exceptions included.
class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) : fd_(fd) {}
  ~FileDescriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

}  // namespace

std::vector<unsigned char> read_regular_file(const std::filesystem::path& path, std::uint64_t max_bytes,
                                             ErrorCode code) {
  const auto fail = [code](const std::string& what) { throw Exception(code, what); };
  struct stat before {};
  if (::stat(path.c_str(), &before) != 0) {
    if (errno == ENOENT || errno == ENOTDIR) fail("file not found");
    fail(std::string("cannot open: ") + std::strerror(errno));
  }
  if (S_ISDIR(before.st_mode)) fail("is a directory");
  // Only now is it opened: a device is never touched, not even opened.
  if (!S_ISREG(before.st_mode)) fail("is not a regular file (a device, FIFO or socket)");
  if (static_cast<std::uint64_t>(before.st_size) > max_bytes) {
    fail("is larger than " + std::to_string(max_bytes) + " bytes");
  }
  // O_NONBLOCK: should the path have been swapped for a FIFO since the
  // stat, opening it must not wait for a writer.
  const FileDescriptor file(::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK));
  if (file.get() < 0) fail(std::string("cannot open: ") + std::strerror(errno));
  struct stat opened {};
  if (::fstat(file.get(), &opened) != 0 || !S_ISREG(opened.st_mode) || opened.st_dev != before.st_dev ||
      opened.st_ino != before.st_ino || opened.st_size != before.st_size) {
    fail("changed while being read");
  }
  // Exactly st_size bytes: a file that grows meanwhile is cut there rather
  // than read without bound (pseudo-files that report size 0 read as empty).
  std::vector<unsigned char> bytes(static_cast<std::size_t>(opened.st_size));
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ::ssize_t got = ::read(file.get(), bytes.data() + done, bytes.size() - done);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) fail("read error");
    if (got == 0) fail("changed while being read");
    done += static_cast<std::size_t>(got);
  }
  return bytes;
}

}  // namespace sp
