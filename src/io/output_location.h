// Where an output file goes, found once and held open (README "Security").
//
// The path is walked one component at a time from a directory descriptor,
// as the kernel walks it, but by us, so that the rules below hold whatever
// the system's settings, and so that nothing is looked up twice: the folder
// found is kept open, and the file is created and renamed inside it.
//
// - A symbolic link in a sticky, world-writable folder (/tmp) is followed
//   only when it belongs to us (the effective user) or to the folder's
//   owner: the kernel's fs.protected_symlinks rule. Another user's link
//   there may point at anything, a third user's file included.
// - A link is otherwise written through: the file goes where it points, and
//   the link stays a link.
// - /proc and /sys are refused, as are directories, devices, FIFOs and
//   sockets: none is a place for a new regular file.
#pragma once

#include <sys/stat.h>

#include <filesystem>
#include <optional>
#include <string>

#include "core/file_descriptor.h"

namespace sp {

struct OutputLocation {
  bool to_stdout = false;               // the path was "-"
  FileDescriptor folder;                // the folder the file goes in (O_PATH)
  struct stat folder_status {};         // of `folder`
  std::string name;                     // the file's name in `folder`
  std::filesystem::path file;           // absolute, every link resolved: for messages and comparisons
  std::optional<struct stat> existing;  // the regular file there now, if any
};

// Walks `path` as described above. Throws sp::Exception(Io), "cannot write
// PATH: why", when a rule refuses it, a folder on the way is missing, or
// standard output is named but closed.
OutputLocation locate_output(const std::filesystem::path& path);

// Throws sp::Exception(Io) naming `path` when `existing`, a regular file in
// a folder with `folder_status`, must not be replaced by a rename:
// - it has other hard links: a rename would split them from it, leaving
//   them with the old contents (and writing in place would instead let a
//   link planted by another user aim our output at their victim's file);
// - it belongs to another user (not the folder's owner) in a sticky,
//   world-writable folder: the kernel's fs.protected_regular rule.
void check_replaceable(const std::filesystem::path& path, const struct stat& folder_status,
                       const struct stat& existing);

// The state of `name` in `folder` now: its status when it is a regular
// file, none when absent. Throws sp::Exception(Io) naming `path` when it is
// anything else (it changed since it was located).
std::optional<struct stat> regular_file_now(const std::filesystem::path& path, int folder, const std::string& name);

}  // namespace sp
