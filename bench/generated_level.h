// A deterministic procedural level for the scaling benchmarks, built in
// memory (no file): a 4 x 4 grid of 8 x 8 m rooms, 3 m high, with 0.2 m
// walls (a 1.2 x 2.2 m door in every interior wall), floor and ceiling slabs,
// two or three furniture boxes per room, 15 sources with the paper's emission
// pattern (every 0.25 s for 0.1 s, staggered phases) and the listener in room
// (1, 1). Every face of every box is tessellated into cells of about the same
// edge length, chosen so that the total comes close to the requested triangle
// count: the surfaces the rays see are the same at every size, only the
// triangle count changes.
#pragma once

#include <cstddef>

#include "soundpaint/scene.h"

namespace spbench {

// At least 1,380 triangles (the untessellated boxes); counts above a few
// thousand are met within about 1 %. Same input, same scene, bit for bit.
sp::Scene generate_level(std::size_t target_triangles);

}  // namespace spbench
