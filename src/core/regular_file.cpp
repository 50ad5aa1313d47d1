#include "core/regular_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

namespace sp {

std::vector<unsigned char> read_regular_file(const FileOpener& open, std::uint64_t max_bytes, ErrorCode code,
                                             const FileVetter& vet) {
  const auto fail = [code](const std::string& what) { throw Exception(code, what); };
  struct stat checked {};
  {
    // O_PATH: a device is never opened for real, a FIFO never waited on.
    const FileDescriptor look = open(O_PATH);
    if (vet) vet(look.get());
    if (::fstat(look.get(), &checked) != 0) fail(std::string("cannot open: ") + std::strerror(errno));
  }
  if (S_ISDIR(checked.st_mode)) fail("is a directory");
  if (!S_ISREG(checked.st_mode)) fail("is not a regular file (a device, FIFO or socket)");
  if (static_cast<std::uint64_t>(checked.st_size) > max_bytes) {
    fail("is larger than " + std::to_string(max_bytes) + " bytes");
  }
  // O_NONBLOCK: should the name have been swapped for a FIFO since the
  // check, opening it must not wait for a writer.
  const FileDescriptor file = open(O_RDONLY | O_NOCTTY | O_NONBLOCK);
  struct stat reading {};
  if (::fstat(file.get(), &reading) != 0 || !S_ISREG(reading.st_mode) || reading.st_dev != checked.st_dev ||
      reading.st_ino != checked.st_ino || reading.st_size != checked.st_size) {
    fail("changed while being read");
  }
  // Exactly st_size bytes: a file that grows meanwhile is cut there rather
  // than read without bound (pseudo-files that report size 0 read as empty).
  std::vector<unsigned char> bytes(static_cast<std::size_t>(reading.st_size));
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

std::vector<unsigned char> read_regular_file(const std::filesystem::path& path, std::uint64_t max_bytes,
                                             ErrorCode code) {
  const FileOpener open = [&path, code](int flags) {
    FileDescriptor fd(::open(path.c_str(), flags | O_CLOEXEC));
    if (fd.valid()) return fd;
    if (errno == ENOENT || errno == ENOTDIR) throw Exception(code, "file not found");
    throw Exception(code, std::string("cannot open: ") + std::strerror(errno));
  };
  return read_regular_file(open, max_bytes, code);
}

}  // namespace sp
