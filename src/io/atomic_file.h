// A file that appears under its final name only once fully written: data
// goes to a temporary file in the same directory (so the rename is atomic)
// and is renamed on commit; destruction without commit removes it.
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

  std::filesystem::path target_;
  std::filesystem::path temporary_;
  std::FILE* file_ = nullptr;
};

}  // namespace sp
