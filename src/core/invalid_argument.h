// The error an API call returns for an argument it refuses.
#pragma once

#include <string>
#include <utility>

#include "soundpaint/result.h"

namespace sp {

inline Error invalid_argument_error(std::string message) {
  return Error{ErrorCode::InvalidArgument, std::move(message), 0};
}

}  // namespace sp
