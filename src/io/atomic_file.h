// A file that appears under its final name only once fully written: data
// goes to a temporary file in the same directory (so the rename is atomic)
// and is renamed on commit; destruction without commit removes it.
// The target is resolved by resolve_output() (io/output_path.h): "-" writes
// straight to standard output, a symbolic link is written through to its
// target, and anything but a regular file is refused before a byte is
// written.
#pragma once

#include <cstdio>
#include <filesystem>
#include <string_view>

namespace sp {

class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path target);  // throws Exception(Io)
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  void write(std::string_view bytes);  // throws Exception(Io)
  void commit();                       // throws Exception(Io)

 private:
  [[noreturn]] void fail(const char* what);

  std::filesystem::path requested_;  // as the user named it, for messages
  std::filesystem::path target_;     // resolved; empty for standard output
  std::filesystem::path temporary_;
  std::FILE* file_ = nullptr;
  bool to_stdout_ = false;
};

}  // namespace sp
