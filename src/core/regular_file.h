// Reading whole files that come from strangers (scenes, buffers, configs).
//
// The file's type and size are checked before a byte is read, and nothing
// but a regular file is ever opened for reading: a device such as /dev/zero
// would otherwise be read until memory runs out, a FIFO would block, and
// opening some devices has side effects of its own. So the checks are made
// on an O_PATH descriptor, which opens nothing for real. Linux cannot turn
// that descriptor into a readable one (short of /proc/self/fd, which may not
// be mounted), so the file is opened again, by the same opener, and read
// only when it is the very file checked (same device and inode): a name
// swapped in between is noticed, never read.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <vector>

#include "core/file_descriptor.h"
#include "soundpaint/result.h"

namespace sp {

// Opens the file to read with the open(2) `flags` it is given, or throws
// sp::Exception with a message that does not name the file ("file not
// found", "cannot open: <reason>", or the caller's own reasons).
using FileOpener = std::function<FileDescriptor(int flags)>;

// Looks at the file before anything else is checked (given the O_PATH
// descriptor) and throws sp::Exception to refuse it; may be empty.
using FileVetter = std::function<void(int fd)>;

// The whole content of the file `open` opens, which must be a regular file
// of at most `max_bytes` bytes. `open` is called twice: with O_PATH, for the
// checks (`vet`'s first), then with O_RDONLY | O_NONBLOCK | O_NOCTTY, to
// read; the two must be the same file (the same device and inode), or
// nothing is read. Throws what `open` and `vet` throw, else sp::Exception
// with `code` and a message that does not name the file (callers add it):
// "is a directory", "is not a regular file (a device, FIFO or socket)", "is
// larger than N bytes", "read error", "changed while being read".
std::vector<unsigned char> read_regular_file(const FileOpener& open, std::uint64_t max_bytes, ErrorCode code,
                                             const FileVetter& vet = {});

// read_regular_file of the file at `path` (symbolic links are followed;
// relative to the current directory): "file not found", "cannot open:
// <reason>", and the messages above.
std::vector<unsigned char> read_regular_file(const std::filesystem::path& path, std::uint64_t max_bytes,
                                             ErrorCode code);

}  // namespace sp
