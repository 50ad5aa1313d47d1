// --events TRACE and its companions (README "Sound-event traces"), shared by
// simulate and render: a recorded game's sounds replayed on the scene.
#pragma once

#include <optional>
#include <set>
#include <string>

#include "cli/options.h"
#include "events/event_trace.h"

namespace sp::cli {

// --events TRACE, --event-rules RULES.json, --event-axes identity|quake,
// --event-start SECONDS (values).
inline const std::set<std::string> kEventValueOptions = {"--events", "--event-rules", "--event-axes", "--event-start"};

std::string event_help();

// The replay the options ask for, or nothing without --events. Throws
// sp::Exception naming the option or the file on bad input.
std::optional<events::TraceReplay> load_event_replay(const ParsedArgs& parsed);

}  // namespace sp::cli
