// What a build without an optional part says when a config asks for it.
#pragma once

namespace sp {

// Completes "cpu_traversal: Embree ..." and its twins (parser, World, CPU
// backend): how to get a build that has it.
inline constexpr const char* kEmbreeBuildHint =
    "needs soundpaint built with -DSOUNDPAINT_EMBREE=ON (Debian: libembree-dev)";

}  // namespace sp
