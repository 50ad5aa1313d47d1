// Standard input, output and error as the command line found them.
//
// A program started with descriptor 1 closed (`soundpaint ... >&-`) would
// hand that number to the next file it opens, and everything meant for
// standard output would land in that file: a CSV before a stats JSON. So
// the CLI reserves 0, 1 and 2 first, and remembers which were closed.
#pragma once

#include <optional>
#include <string>

namespace sp {

// Puts a descriptor on each of 0, 1 and 2 that is closed, on which every
// read or write fails (EBADF) as it would on the closed one, and records
// that standard output was closed. False when no descriptor could be opened
// (then the process should not go on: a later file could become fd 1).
bool reserve_standard_streams();

// True when reserve_standard_streams() found descriptor 1 closed: an output
// named "-" is then refused ("standard output is closed").
bool standard_output_closed();

// Flushes standard output; when it or an earlier write to it failed, the
// reason (such as "No space left on device", or "it is closed"), else none.
std::optional<std::string> standard_output_error();

}  // namespace sp
