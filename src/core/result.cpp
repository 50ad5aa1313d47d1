#include "soundpaint/result.h"

namespace sp {

const char* to_string(ErrorCode code) {
  switch (code) {
    case ErrorCode::InvalidArgument:
      return "invalid argument";
    case ErrorCode::InvalidScene:
      return "invalid scene";
    case ErrorCode::InvalidConfig:
      return "invalid config";
    case ErrorCode::Io:
      return "I/O error";
    case ErrorCode::Vulkan:
      return "Vulkan error";
    case ErrorCode::LimitExceeded:
      return "limit exceeded";
  }
  return "unknown error";
}

}  // namespace sp
