// The viewer's --config file, watched for changes by its content.
//
// An mtime alone misses changes: a save written in two parts within one
// tick of a coarse clock (one second on some file systems, two on FAT)
// leaves the same mtime on the truncated first part and the whole file, so
// the whole file would never be read. The watch compares the file's bytes
// instead, read afresh at each poll (a config is kilobytes; the parser's
// 64 MiB cap bounds the worst case).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "soundpaint/config.h"
#include "soundpaint/result.h"

namespace sp::view {

class ConfigWatch {
 public:
  explicit ConfigWatch(std::filesystem::path path) : path_(std::move(path)) {}

  // Reads the file. Returns nothing when what it found (its bytes, or the
  // reason it could not be read) is what the previous poll found; else the
  // config parsed from the bytes, or the one-line error naming the file
  // (ErrorCode::Io when unreadable, InvalidConfig when malformed). The first
  // poll always returns. An unchanged bad file is reported once.
  std::optional<Result<Config>> poll();

  const std::filesystem::path& path() const { return path_; }

 private:
  // What one poll found: the bytes, or why there were none.
  struct Snapshot {
    std::vector<unsigned char> bytes;
    std::string read_error;  // empty when the bytes were read
    bool operator==(const Snapshot&) const = default;
  };

  std::filesystem::path path_;
  std::optional<Snapshot> last_;
};

}  // namespace sp::view
