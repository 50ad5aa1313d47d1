// Where an output file named by a user goes, decided before anything is
// written (README "Command line").
//
// Outputs are regular files written through a temporary file and a rename
// (AtomicFile), which must never turn something else into a regular file:
// "-" is standard output; a symbolic link is written through, to the file it
// names (the link stays a link), unless another user planted it in a
// sticky, world-writable folder such as /tmp; a device, FIFO, socket or
// directory is refused, so that `--stats /dev/null` fails rather than
// replace the device node when run as root; an existing file with other
// hard links, or another user's file in a sticky folder, is never replaced.
// The walk itself: io/output_location.h.
#pragma once

#include <filesystem>
#include <span>
#include <string>

namespace sp {

struct OutputTarget {
  bool to_stdout = false;      // the path was "-"
  std::filesystem::path file;  // else: absolute, every symbolic link resolved
};

// True for "-", which every output option takes as standard output.
bool names_stdout(const std::filesystem::path& path);

// Resolves `path` as described above. Throws sp::Exception(Io) naming `path`
// when it is empty, its folder does not exist, it names a directory or
// something that is not a regular file, a rule above refuses it, or it is
// "-" while standard output is closed.
OutputTarget resolve_output(const std::filesystem::path& path);

// One output of a command: the option that named it and its path.
struct NamedOutput {
  std::string option;  // "--stats"
  std::filesystem::path path;
};

// Throws sp::Exception(InvalidArgument) naming both options when two
// outputs resolve to the same file (or both to standard output): one would
// silently replace the other. Unresolvable paths are left for the writers
// to report.
void check_distinct_outputs(std::span<const NamedOutput> outputs);

}  // namespace sp
