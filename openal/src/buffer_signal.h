// An AL buffer's PCM, as alBufferData takes it, read into a Signal.
#pragma once

#include <AL/al.h>

#include "soundpaint/result.h"
#include "soundpaint/signal.h"

namespace sp::openal {

// Errors (InvalidArgument) say what is wrong with the format, data or size,
// without naming the buffer (the caller does).
Result<Signal> buffer_signal(ALenum format, const ALvoid* data, ALsizei size, ALsizei frequency);

}  // namespace sp::openal
