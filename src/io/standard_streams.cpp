#include "io/standard_streams.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace sp {
namespace {

bool g_stdout_closed = false;

bool is_open(int fd) { return ::fcntl(fd, F_GETFD) != -1 || errno != EBADF; }

// Opened in the direction the stream is not used in, so that every use
// fails as it did while closed; "/" when there is no /dev/null (a bare
// chroot): reads and writes on a directory fail too.
int open_placeholder(int fd) {
  const int wrong_way = fd == STDIN_FILENO ? O_WRONLY : O_RDONLY;
  const int placeholder = ::open("/dev/null", wrong_way | O_NOCTTY);
  return placeholder >= 0 ? placeholder : ::open("/", O_RDONLY | O_DIRECTORY);
}

}  // namespace

bool reserve_standard_streams() {
  for (int fd : {STDIN_FILENO, STDOUT_FILENO, STDERR_FILENO}) {
    if (is_open(fd)) continue;
    if (fd == STDOUT_FILENO) g_stdout_closed = true;
    // The lowest free number: this one, since those below are open now.
    if (open_placeholder(fd) != fd) return false;
  }
  return true;
}

bool standard_output_closed() { return g_stdout_closed; }

std::optional<std::string> standard_output_error() {
  errno = 0;
  const bool flushed = std::fflush(stdout) == 0;
  const int error = errno;
  if (flushed && !std::ferror(stdout)) return std::nullopt;
  if (g_stdout_closed) return std::string("it is closed");
  return std::string(std::strerror(error ? error : EIO));
}

}  // namespace sp
