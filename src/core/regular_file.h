// Reading whole files that come from strangers (scenes, buffers, configs).
//
// The file's type and size are checked before a byte is read, and nothing
// but a regular file is ever opened: a device such as /dev/zero would
// otherwise be read until memory runs out, a FIFO would block, and opening
// some devices has side effects of its own.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "soundpaint/result.h"

namespace sp {

// The whole content of `path`, which must be a regular file (symbolic links
// are followed) of at most `max_bytes` bytes. Throws sp::Exception with
// `code` and a message that does not name the path (callers add it):
// "file not found", "is a directory", "is not a regular file (a device,
// FIFO or socket)", "is larger than N bytes", "cannot open: <reason>",
// "read error", "changed while being read".
std::vector<unsigned char> read_regular_file(const std::filesystem::path& path, std::uint64_t max_bytes,
                                             ErrorCode code);

}  // namespace sp
