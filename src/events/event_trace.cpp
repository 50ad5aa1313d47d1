#include "events/event_trace.h"

#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "core/regular_file.h"

namespace sp::events {
namespace {

using nlohmann::json;

// A trace of a long match: 30 s of OpenArena is about 1 MiB.
constexpr std::uint64_t kMaxTraceBytes = std::uint64_t{1} << 30;

[[noreturn]] void fail(const std::string& where, const std::string& what) {
  throw Exception(ErrorCode::InvalidArgument, where + ": " + what);
}

const json& field(const json& line, const char* key, const std::string& where) {
  const auto found = line.find(key);
  if (found == line.end()) fail(where, std::string("needs \"") + key + "\"");
  return *found;
}

double number(const json& line, const char* key, const std::string& where) {
  const json& v = field(line, key, where);
  if (!v.is_number() || !std::isfinite(v.get<double>())) fail(where, std::string("\"") + key + "\" must be a number");
  return v.get<double>();
}

std::uint32_t id(const json& line, const char* key, const std::string& where) {
  const json& v = field(line, key, where);
  if (!v.is_number_unsigned() || v.get<std::uint64_t>() > 0xFFFFFFFFull)
    fail(where, std::string("\"") + key + "\" must be an id (an integer >= 0)");
  return static_cast<std::uint32_t>(v.get<std::uint64_t>());
}

Vec3 vec3(const json& line, const char* key, const std::string& where) {
  const json& v = field(line, key, where);
  if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() || !v[2].is_number())
    fail(where, std::string("\"") + key + "\" must be [x, y, z]");
  Vec3 out(v[0].get<float>(), v[1].get<float>(), v[2].get<float>());
  if (!std::isfinite(out.x) || !std::isfinite(out.y) || !std::isfinite(out.z))
    fail(where, std::string("\"") + key + "\" must be finite");
  return out;
}

bool flag(const json& line, const char* key) {
  const auto found = line.find(key);
  return found != line.end() && found->is_boolean() && found->get<bool>();
}

std::shared_ptr<const Signal> envelope(const json& line, const std::string& where) {
  const json& levels = field(line, "levels", where);
  if (!levels.is_array()) fail(where, "\"levels\" must be an array of dB levels (null: silence)");
  std::vector<float> db;
  for (const json& level : levels)
    db.push_back(level.is_null() ? -std::numeric_limits<float>::infinity() : level.get<float>());
  if (db.empty()) db.push_back(-std::numeric_limits<float>::infinity());  // an empty buffer: silence
  auto signal = Signal::from_levels(db, number(line, "hop", where));
  if (!signal) fail(where, signal.error().message);
  return std::make_shared<const Signal>(std::move(signal).value());
}

// Parses one line; false for a line to skip (the header, a summary, a type
// this reader does not know).
bool parse_line(const json& line, const std::string& where, TraceEvent& e, bool& header_seen) {
  if (!line.is_object()) fail(where, "each line must be a JSON object");
  const json& type_value = field(line, "type", where);
  if (!type_value.is_string()) fail(where, "\"type\" must be a string");
  const std::string type = type_value.get<std::string>();
  if (type == "header") {
    const json& version = field(line, "version", where);
    if (!version.is_number_integer() || version.get<int>() != kTraceVersion)
      fail(where, "trace version " + version.dump() + " is not the one this soundpaint reads (1)");
    header_seen = true;
    return false;
  }
  if (!header_seen) fail(where, "the first line must be the header ({\"type\": \"header\", \"version\": 1, ...})");
  using K = TraceEvent::Kind;
  e = TraceEvent{};
  e.t = number(line, "t", where);
  if (type == "buffer") {
    e.kind = K::Buffer;
    e.id = id(line, "buffer", where);
    const json& name = field(line, "name", where);
    if (name.is_string()) e.name = name.get<std::string>();
    e.signal = envelope(line, where);
  } else if (type == "play") {
    e.kind = K::Play;
    e.id = id(line, "source", where);
    e.buffer = id(line, "buffer", where);
    e.position = vec3(line, "position", where);
    e.gain = static_cast<float>(number(line, "gain", where));
    e.loop = flag(line, "loop");
    e.relative = flag(line, "relative");
  } else if (type == "move") {
    e.kind = K::Move;
    e.id = id(line, "source", where);
    e.position = vec3(line, "position", where);
  } else if (type == "gain") {
    e.kind = K::Gain;
    e.id = id(line, "source", where);
    e.gain = static_cast<float>(number(line, "gain", where));
  } else if (type == "stop") {
    e.kind = K::Stop;
    e.id = id(line, "source", where);
    if (line.value("by", std::string()) == "delete") e.kind = K::Delete;
  } else if (type == "listener") {
    e.kind = K::Listener;
    e.position = vec3(line, "position", where);
  } else if (type == "orientation") {
    e.kind = K::Orientation;
    e.position = vec3(line, "forward", where);
    e.up = vec3(line, "up", where);
  } else {
    return false;  // distance_model, summary, or a later writer's type
  }
  if (e.gain < 0.0f) fail(where, "\"gain\" must be >= 0");
  return true;
}

}  // namespace

Vec3 to_scene(TraceAxes axes, Vec3 game) {
  if (axes == TraceAxes::Identity) return game;
  constexpr float kUnitsPerMetre = 32.0f;
  return {game.x / kUnitsPerMetre, game.z / kUnitsPerMetre, -game.y / kUnitsPerMetre};
}

std::vector<TraceEvent> load_trace(const std::filesystem::path& path) {
  const std::string origin = path.string();
  std::vector<unsigned char> bytes;
  try {
    bytes = read_regular_file(path, kMaxTraceBytes, ErrorCode::Io);
  } catch (const Exception& e) {
    throw Exception(e.error().code, origin + ": " + e.error().message);
  }
  std::vector<TraceEvent> events;
  bool header_seen = false;
  double last_t = 0.0;
  std::size_t begin = 0, line_number = 0;
  while (begin < bytes.size()) {
    std::size_t end = begin;
    while (end < bytes.size() && bytes[end] != '\n') ++end;
    ++line_number;
    const std::string where = origin + ":" + std::to_string(line_number);
    const std::string_view text(reinterpret_cast<const char*>(bytes.data()) + begin, end - begin);
    begin = end + 1;
    if (text.find_first_not_of(" \t\r") == std::string_view::npos) continue;
    json line;
    try {
      line = json::parse(text);
    } catch (const json::parse_error&) {
      fail(where, "not a JSON object on one line");
    }
    TraceEvent e;
    if (!parse_line(line, where, e, header_seen)) continue;
    if (e.t < last_t)
      fail(where, "time goes backwards (" + std::to_string(e.t) + " after " + std::to_string(last_t) + ")");
    last_t = e.t;
    events.push_back(std::move(e));
  }
  if (!header_seen) fail(origin, "empty: no header line");
  return events;
}

TraceReplay::TraceReplay(std::vector<TraceEvent> events, ReplaySettings settings)
    : events_(std::move(events)), settings_(std::move(settings)) {}

void TraceReplay::advance(SoundScene& scene, double time) {
  if (!started_) {
    // The trace's sounds are the game's: they replace the scene's and the config's.
    for (std::uint32_t id = 0; id < scene.source_slot_count(); ++id)
      if (scene.has_source(id)) (void)scene.remove_source(id);
    started_ = true;
  }
  const double until = settings_.start + time;
  while (next_ < events_.size() && events_[next_].t <= until) apply(scene, events_[next_++]);
}

Vec3 TraceReplay::place(const Voice& voice) const {
  Vec3 game = voice.game_position;
  // AL_SOURCE_RELATIVE: the offset is from the listener (ioquake3's local sounds).
  if (voice.relative) game = Vec3(game.x + game_listener_.x, game.y + game_listener_.y, game.z + game_listener_.z);
  return to_scene(settings_.axes, game);
}

void TraceReplay::apply(SoundScene& scene, const TraceEvent& e) {
  using K = TraceEvent::Kind;
  // Scene calls fail only on ids this replay made itself or on checked
  // values; an error there is a bug, not bad input: let it throw.
  auto check = [](auto result) {
    if (!result) throw Exception(result.error());
  };
  switch (e.kind) {
    case K::Buffer: {
      Buffer& b = buffers_[e.id];
      b.signal = e.signal;
      const std::string name = e.name.value_or("");
      b.category = settings_.rules ? settings_.rules->category_of(name)
                                   : std::optional<std::string>(name.empty() ? "sound" : name);
      return;
    }
    case K::Play: {
      const auto buffer = buffers_.find(e.buffer);
      auto voice = voices_.find(e.id);
      const bool paintable = buffer != buffers_.end() && buffer->second.category.has_value();
      if (!paintable) {
        if (voice != voices_.end()) {
          voice->second.state.playing = false;
          check(scene.set_voice(voice->second.id, voice->second.state));
        }
        return;
      }
      SourceDesc desc;
      desc.category = *buffer->second.category;
      desc.max_distance = settings_.max_distance;
      desc.duration = 0.0;  // a voice: the trace says when it plays
      desc.signal = buffer->second.signal;
      desc.loop = e.loop;
      if (voice == voices_.end()) {
        voice = voices_.emplace(e.id, Voice{}).first;
        voice->second.game_position = e.position;
        voice->second.relative = e.relative;
        desc.position = place(voice->second);
        voice->second.id = scene.add_source(desc).value();
        added_ += 1;
      } else {
        voice->second.game_position = e.position;
        voice->second.relative = e.relative;
        desc.position = place(voice->second);
        check(scene.update_source(voice->second.id, desc));
      }
      Voice& v = voice->second;
      v.buffer = e.buffer;
      v.state.position = desc.position;
      v.state.playing = true;
      v.state.gain = e.gain;
      v.state.signal_position = 0.0;  // a play starts the sound
      check(scene.set_voice(v.id, v.state));
      v.state.signal_position = -1.0;  // and then it runs on
      return;
    }
    default:
      break;
  }
  if (e.kind == K::Listener) {
    game_listener_ = e.position;
    listener_ = to_scene(settings_.axes, e.position);
    if (settings_.follow_listener) check(scene.set_listener(*listener_));
    for (auto& [source, v] : voices_) {
      if (!v.relative || !v.state.playing) continue;  // a local sound goes where the player goes
      v.state.position = place(v);
      check(scene.set_voice(v.id, v.state));
    }
    return;
  }
  if (e.kind == K::Orientation) {
    const Vec3 origin = to_scene(settings_.axes, Vec3()), tip = to_scene(settings_.axes, e.position);
    forward_ = Vec3(tip.x - origin.x, tip.y - origin.y, tip.z - origin.z);
    return;
  }
  const auto voice = voices_.find(e.id);
  if (voice == voices_.end()) return;  // a source this replay never painted
  Voice& v = voice->second;
  if (e.kind == K::Delete) {
    check(scene.remove_source(v.id));
    voices_.erase(voice);
    return;
  }
  if (e.kind == K::Move) v.game_position = e.position;
  if (e.kind == K::Gain) v.state.gain = e.gain;
  if (e.kind == K::Stop) v.state.playing = false;
  v.state.position = place(v);
  check(scene.set_voice(v.id, v.state));
}

}  // namespace sp::events
