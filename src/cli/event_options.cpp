#include "cli/event_options.h"

#include <cmath>
#include <memory>

namespace sp::cli {

std::string event_help() {
  return "  --events TRACE       replay a sound-event trace (one JSON object per line, as the\n"
         "                       OpenAL trace shim writes it): its sources play, move and stop\n"
         "                       on the scene as the game's did, their loudness from the samples\n"
         "  --event-rules FILE   category rules for the trace's asset names (wildcards,\n"
         "                       priorities, ignore; default: the name is the category)\n"
         "  --event-axes A       identity (default) or quake: 32 units = 1 m, (x, y, z) -> (x/32, z/32, -y/32)\n"
         "  --event-start S      trace time, in seconds, of step 0 (default 0)\n";
}

std::optional<events::TraceReplay> load_event_replay(const ParsedArgs& parsed) {
  const std::optional<std::string> path = parsed.value("--events");
  for (const char* companion : {"--event-rules", "--event-axes", "--event-start"})
    if (!path && parsed.value(companion))
      throw Exception(ErrorCode::InvalidArgument, std::string(companion) + " needs --events TRACE");
  if (!path) return std::nullopt;
  events::ReplaySettings settings;
  const std::string axes = parsed.value("--event-axes").value_or("identity");
  if (axes == "quake") settings.axes = events::TraceAxes::Quake;
  else if (axes != "identity")
    throw Exception(ErrorCode::InvalidArgument, "--event-axes must be identity or quake, not '" + axes + "'");
  if (auto start = parsed.value("--event-start")) {
    char* end = nullptr;
    settings.start = std::strtod(start->c_str(), &end);
    if (end == start->c_str() || *end != '\0' || !std::isfinite(settings.start) || settings.start < 0.0)
      throw Exception(ErrorCode::InvalidArgument, "--event-start must be seconds >= 0, not '" + *start + "'");
  }
  if (auto rules = parsed.value("--event-rules"))
    settings.rules = std::make_shared<const CategoryRules>(CategoryRules::load(*rules).value());
  return events::TraceReplay(events::load_trace(*path), std::move(settings));
}

}  // namespace sp::cli
