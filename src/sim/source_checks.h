// Validation of a source description, shared by make_world (scene and
// config sources) and SoundScene (sources the host adds at run time).
#pragma once

#include <cstddef>

#include "soundpaint/config.h"

namespace sp {

// Throws sp::Exception(InvalidArgument) naming source `id` and the field:
// non-finite position, colour outside [0, 1], negative range or loudness,
// interval <= 0.
void check_source(const SourceDesc& source, std::size_t id);

}  // namespace sp
