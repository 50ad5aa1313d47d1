// A file that appears under its final name only once fully written: data
// goes to a temporary file in the same directory (so the rename is atomic)
// and is renamed on commit; destruction without commit removes it, and so
// does a fatal signal (io/temporary_files.h).
// The target is located by locate_output() (io/output_location.h): "-"
// writes straight to standard output, a symbolic link is written through to
// its target (unless another user planted it in a sticky folder), and
// anything but a regular file is refused before a byte is written. The
// folder found is held open: the temporary file is created and renamed in
// it, so nothing is looked up twice.
// A replaced file keeps its owner, group and permission bits; when they
// cannot be kept (another user's file, and we are not root), or when the
// file has other hard links, it is refused instead (check_replaceable()).
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>

#include "io/output_location.h"

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
  [[noreturn]] void fail(const std::string& what);
  void create_temporary();
  void keep_owner_and_mode(const struct stat& replaced);
  void rename_over_target(bool replacing);
  void discard() noexcept;  // closes and removes the temporary file, if any

  std::filesystem::path requested_;  // as the user named it, for messages
  OutputLocation target_;
  std::string temporary_;  // its name in target_.folder; empty when there is none
  int registry_slot_ = -1;
  std::FILE* file_ = nullptr;
};

}  // namespace sp
