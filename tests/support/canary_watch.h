// Proof that a file was never opened: an inotify watch on a canary file
// placed where soundpaint must not look (no LD_PRELOAD or strace needed).
// Looking a path up (stat, realpath) does not count; opening or reading it
// does.
#pragma once

#include <sys/inotify.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace sp::test {

class CanaryWatch {
 public:
  explicit CanaryWatch(const std::filesystem::path& canary) : fd_(inotify_init1(IN_NONBLOCK | IN_CLOEXEC)) {
    if (fd_ < 0) throw std::runtime_error(std::string("inotify_init1: ") + std::strerror(errno));
    if (inotify_add_watch(fd_, canary.c_str(), IN_OPEN | IN_ACCESS) < 0) {
      ::close(fd_);
      throw std::runtime_error("inotify_add_watch " + canary.string() + ": " + std::strerror(errno));
    }
  }
  ~CanaryWatch() { ::close(fd_); }
  CanaryWatch(const CanaryWatch&) = delete;
  CanaryWatch& operator=(const CanaryWatch&) = delete;

  // Opens and reads of the canary since the last call. Events are queued
  // when the open happens, so no waiting is needed.
  int take_events() {
    alignas(inotify_event) char buffer[4096];
    int events = 0;
    for (;;) {
      const ssize_t got = ::read(fd_, buffer, sizeof buffer);
      if (got <= 0) return events;
      for (ssize_t at = 0; at < got;) {
        const auto* event = reinterpret_cast<const inotify_event*>(buffer + at);
        ++events;
        at += static_cast<ssize_t>(sizeof(inotify_event) + event->len);
      }
    }
  }

 private:
  int fd_;
};

}  // namespace sp::test
