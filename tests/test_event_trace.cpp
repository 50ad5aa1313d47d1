// Sound-event traces (README "Sound-event traces") and the category rules
// that name their sounds: wildcards, priorities and ignore entries decided
// by hand; a hand-written trace replayed onto a scene puts, moves, stops and
// removes its sources where and when its lines say, in the scene's
// coordinates (OpenArena: (x, y, z) game units -> (x/32, z/32, -y/32) m);
// bad traces get an error naming the file, the line and the problem.
#include <cmath>
#include <filesystem>
#include <map>
#include <vector>
#include <string>

#include <gtest/gtest.h>

#include "events/event_trace.h"
#include "support/scene_builder.h"
#include "support/test_directory.h"

namespace sp {
namespace {

TEST(CategoryRules, WildcardsMatchAnyRunAndOneCharacterIgnoringCase) {
  EXPECT_TRUE(wildcard_match("sound/weapons/*", "sound/weapons/rocket/rocklf1a.wav"));
  EXPECT_TRUE(wildcard_match("sound/player/footsteps/*", "Sound/Player/Footsteps/Boot1.wav"));
  EXPECT_TRUE(wildcard_match("sound/misc/menu?.wav", "sound/misc/menu3.wav"));
  EXPECT_FALSE(wildcard_match("sound/misc/menu?.wav", "sound/misc/menu10.wav"));
  EXPECT_FALSE(wildcard_match("sound/weapons/*", "sound/world/fan.wav"));
  EXPECT_TRUE(wildcard_match("*x*.wav", "rocklx1a.wav"));
  EXPECT_FALSE(wildcard_match("*x*.wav", "rocklf1a.wav"));
}

TEST(CategoryRules, HighestPriorityWinsIgnoreAndDefault) {
  const CategoryRules rules = CategoryRules::parse(R"({"version": 1, "rules": [
      {"match": "sound/weapons/*", "category": "gunfire", "priority": 10},
      {"match": "sound/weapons/rocket/rocklx*", "category": "explosion", "priority": 30},
      {"match": "sound/weapons/change.wav", "ignore": true, "priority": 40},
      {"match": "sound/*", "category": "low", "priority": 10}],
      "default": "sound"})")
                                  .value();
  EXPECT_EQ(rules.category_of("sound/weapons/machinegun/machgf1b.wav"), "gunfire");  // tie: the earlier rule
  EXPECT_EQ(rules.category_of("sound/weapons/rocket/rocklx1a.wav"), "explosion");
  EXPECT_EQ(rules.category_of("sound/weapons/change.wav"), std::nullopt);
  EXPECT_EQ(rules.category_of("music/track1.ogg"), "sound");
  const CategoryRules strict = CategoryRules::parse(R"({"version": 1, "rules": []})").value();
  EXPECT_EQ(strict.category_of("anything"), std::nullopt);  // no default: unmatched names are ignored
}

TEST(CategoryRules, BadFilesNameTheKey) {
  auto message = [](const char* text) { return CategoryRules::parse(text, "r.json").error().message; };
  EXPECT_NE(message(R"({"rules": []})").find("needs \"version\": 1"), std::string::npos);
  EXPECT_NE(message(R"({"version": 2, "rules": []})").find("key \"version\""), std::string::npos);
  EXPECT_NE(message(R"({"version": 1, "rules": [{"match": "a"}]})").find("key \"rules[0]\": needs \"category\""),
            std::string::npos);
  EXPECT_NE(message(R"({"version": 1, "rules": [{"match": "a", "category": "b", "colour": 1}]})").find("colour"),
            std::string::npos);
  EXPECT_NE(message("{").find("r.json"), std::string::npos);
}

// A trace written by hand: a footstep buffer (-6 dB, 30 ms) and a silent one.
constexpr const char* kTrace =
    R"({"type":"header","format":"soundpaint-sound-events","version":1}
{"t":0.0,"type":"buffer","buffer":1,"name":"sound/player/footsteps/boot1.wav","hop":0.01,"levels":[-6.0,-6.0,-6.0]}
{"t":0.0,"type":"buffer","buffer":2,"name":"sound/feedback/hit.wav","hop":0.01,"levels":[-6.0]}
{"t":0.0,"type":"listener","position":[64,0,48]}
{"t":0.05,"type":"play","source":3,"buffer":1,"position":[32,-64,16],"gain":1.0,"loop":false,"relative":false}
{"t":0.05,"type":"play","source":4,"buffer":2,"position":[0,0,0],"gain":1.0,"loop":false,"relative":false}
{"t":0.10,"type":"move","source":3,"position":[64,-64,16]}
{"t":0.20,"type":"stop","source":3,"by":"stop"}
{"t":0.30,"type":"stop","source":3,"by":"delete"}
{"t":0.30,"type":"summary","frames":18}
)";

class EventTrace : public test::TestDirectory {};

TEST_F(EventTrace, ReplayPlacesMovesStopsAndRemovesInSceneCoordinates) {
  events::ReplaySettings settings;
  settings.axes = events::TraceAxes::Quake;
  settings.rules = std::make_shared<const CategoryRules>(CategoryRules::parse(R"({"version": 1, "rules": [
      {"match": "sound/player/footsteps/*", "category": "footsteps"},
      {"match": "sound/feedback/*", "ignore": true}]})")
                                                             .value());
  events::TraceReplay replay(events::load_trace(write("trace.jsonl", std::string(kTrace))), settings);
  Scene scene = test::closed_room();  // its own source is replaced by the trace's
  Config config;
  config.listener_position = Vec3(0, 1.5f, 0);
  auto sim = create_cpu_simulator(make_world(scene, config).value(), CpuSettings{1}).value();
  SoundScene& live = sim->scene();

  replay.advance(live, 0.0);
  EXPECT_FALSE(live.has_source(0));                    // the scene's own source is gone
  EXPECT_EQ(live.listener(), Vec3(2.0f, 1.5f, 0.0f));  // (64, 0, 48) / 32, z up -> y up
  replay.advance(live, 0.05);
  ASSERT_TRUE(sim->step().ok());
  ASSERT_EQ(replay.sources_added(), 1u);  // the ignored hit sound is never painted
  const std::uint32_t id = 0;             // the freed slot, reused
  EXPECT_EQ(sim->world().sources[id].category, "footsteps");
  EXPECT_EQ(sim->world().sources[id].position, Vec3(1.0f, 0.5f, 2.0f));  // (32, -64, 16) -> (1, 0.5, 2)
  replay.advance(live, 0.10);
  ASSERT_TRUE(sim->step().ok());
  EXPECT_EQ(sim->world().sources[id].position, Vec3(2.0f, 0.5f, 2.0f));
  EXPECT_GT(sim->last_step_indicators().value().size(), 0u);  // playing, -6 dB
  replay.advance(live, 0.20);
  ASSERT_TRUE(sim->step().ok());
  ASSERT_TRUE(sim->step().ok());
  EXPECT_TRUE(sim->last_step_indicators().value().empty());  // stopped
  replay.advance(live, 0.30);
  EXPECT_FALSE(live.has_source(id));       // deleted
  EXPECT_EQ(replay.events_applied(), 8u);  // the header and summary lines are not events
}

// Three seconds of a real bot match on OpenArena's oa_dm1, recorded by the
// trace shim (scripts/openarena-trace.sh), replayed with the shipped rules
// in a box around where the bots fought (the level itself lives outside
// the repository): footsteps and gunfire are painted, every first hit
// from a source at a point the trace put it.
TEST_F(EventTrace, RecordedOpenArenaMatchPaintsFootstepsAndGunfireWhereTheBotsWere) {
  const std::filesystem::path trace = std::filesystem::path(SP_TEST_DATA_DIR) / "openarena-oa_dm1-bots.jsonl";
  const std::filesystem::path rules =
      std::filesystem::path(SP_SCENES_DIR) / ".." / "data" / "openarena-categories.json";
  std::vector<events::TraceEvent> events = events::load_trace(trace);
  // Where the trace put each source, in metres.
  std::map<std::uint32_t, std::vector<Vec3>> placed;
  for (const events::TraceEvent& e : events)
    if (e.kind == events::TraceEvent::Kind::Play || e.kind == events::TraceEvent::Kind::Move)
      placed[e.id].push_back(events::to_scene(events::TraceAxes::Quake, e.position));
  events::ReplaySettings settings;
  settings.axes = events::TraceAxes::Quake;
  settings.start = 37.0;
  settings.rules = std::make_shared<const CategoryRules>(CategoryRules::load(rules).value());
  events::TraceReplay replay(std::move(events), settings);

  Scene scene;
  test::add_closed_room(scene, {-20.0f, -5.0f, -60.0f}, {25.0f, 6.0f, -20.0f}, 0.3f, "concrete");
  Config config;
  config.listener_position = Vec3(-13.5f, 1.57f, -49.9f);
  auto sim = create_cpu_simulator(make_world(scene, config).value(), CpuSettings{1}).value();
  std::map<std::string, std::size_t> spots;
  for (int n = 0; n < 180; ++n) {
    replay.advance(sim->scene(), n / 60.0);
    ASSERT_TRUE(sim->step().ok());
    for (const Indicator& i : sim->last_step_indicators().value()) {
      const SourceDesc& source = sim->world().sources[i.source_id];
      spots[source.category] += 1;
    }
  }
  EXPECT_GT(replay.sources_added(), 5u);
  EXPECT_GT(spots["footsteps"], 100u);
  EXPECT_GT(spots["gunfire"], 100u);
  // Every source the replay made stands where the trace last put one of
  // the game's AL sources.
  for (std::uint32_t id = 0; id < sim->scene().source_slot_count(); ++id) {
    if (!sim->scene().has_source(id)) continue;
    const Vec3 p = sim->world().sources[id].position;
    bool found = false;
    for (const auto& [al_source, points] : placed)
      for (const Vec3& q : points) found = found || (std::abs(p.x - q.x) < 1e-3f && std::abs(p.z - q.z) < 1e-3f);
    EXPECT_TRUE(found) << "source " << id << " at " << p.x << ", " << p.y << ", " << p.z;
  }
}

TEST_F(EventTrace, BadTracesNameTheLineAndTheProblem) {
  auto error = [&](const std::string& text) {
    try {
      events::load_trace(write("trace.jsonl", text));
    } catch (const Exception& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const std::string header = R"({"type":"header","version":1})"
                             "\n";
  EXPECT_NE(error(R"({"type":"header","version":2})").find(":1: trace version 2 is not the one"), std::string::npos);
  EXPECT_NE(error(R"({"t":0,"type":"listener","position":[0,0,0]})").find(":1: the first line must be the header"),
            std::string::npos);
  EXPECT_NE(error(header + R"({"t":0,"type":"play","source":1})").find(":2: needs \"buffer\""), std::string::npos);
  EXPECT_NE(error(header + "{\"t\":1,\"type\":\"stop\",\"source\":1}\n{\"t\":0.5,\"type\":\"stop\",\"source\":1}")
                .find(":3: time goes backwards"),
            std::string::npos);
  EXPECT_NE(error(header + "not json").find(":2: not a JSON object"), std::string::npos);
  EXPECT_NE(error("").find("empty: no header line"), std::string::npos);
}

}  // namespace
}  // namespace sp
