#include "view/config_watch.h"

#include <cstdint>
#include <string_view>
#include <utility>

#include "core/regular_file.h"

namespace sp::view {
namespace {

// load_config's own cap (README "Security"), so a file the viewer started
// with is never refused on reload for its size, nor the reverse.
constexpr std::uint64_t kMaxConfigFileBytes = 64ull << 20;

}  // namespace

std::optional<Result<Config>> ConfigWatch::poll() {
  Snapshot now;
  try {
    now.bytes = read_regular_file(path_, kMaxConfigFileBytes, ErrorCode::Io);
  } catch (const Exception& e) {
    now.read_error = e.error().message;
  }
  if (last_ && *last_ == now) return std::nullopt;
  last_ = std::move(now);
  const std::string origin = path_.string();
  if (!last_->read_error.empty())
    return Result<Config>(Error{ErrorCode::Io, origin + ": cannot read config file: " + last_->read_error, 0});
  const std::string_view text(reinterpret_cast<const char*>(last_->bytes.data()), last_->bytes.size());
  return parse_config(text, origin);
}

}  // namespace sp::view
