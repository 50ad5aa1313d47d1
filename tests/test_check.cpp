// sp::check_scene (`soundpaint check`) on scenes built to have exactly one
// problem each, with counts derived by hand, and on a closed room that must
// have none; names from the level escaped in its messages and exact in its
// JSON (sp::printable_text); a config over the memory budget reported, not
// failed; a level too large for float counted sanely.
#include <algorithm>
#include <cstdint>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include <nlohmann/json.hpp>

#include "bvh/mesh_topology.h"
#include "check/check_report_json.h"
#include "core/glm_interop.h"
#include "core/printable_text.h"
#include "sim/memory_estimate.h"
#include "soundpaint/check.h"
#include "support/check_findings.h"
#include "support/scene_builder.h"

namespace sp {
namespace {

using test::add_box;
using test::add_box_faces;
using test::add_quad;

CheckReport check(const Scene& scene, Config config = {}) {
  if (!config.listener_position && scene.sources.empty()) config.listener_position = glm::vec3(0, 1.5f, 0);
  CheckSettings settings;
  settings.probe_steps = 8;
  settings.probe_rays_per_step = 1000;
  settings.threads = 2;
  return check_scene(scene, config, settings).value();
}

std::string codes(const CheckReport& report) {
  std::string all;
  for (const CheckFinding& f : report.findings) all += f.code + ": " + f.message + "\n";
  return all;
}

// A 6 x 3 x 5 m room of 0.3 m concrete slabs around a source.
Scene closed_room() { return test::closed_room(); }

// The same room as a render mesh: one quad per wall, its front towards the
// room, nothing behind it.
Scene render_mesh_room() {
  Scene scene;
  const glm::vec3 lo(-3, 0, -2.5f), hi(3, 3, 2.5f);
  // add_box_faces' fronts face out of the box; flipped, they face in.
  add_box_faces(scene, lo, hi, "concrete", test::kAllFaces, test::kAllFaces);
  scene.sources.push_back(test::source_at({0.5f, 1.5f, 0.2f}));
  return scene;
}

TEST(Check, ClosedRoomHasNoFindings) {
  const CheckReport report = check(closed_room());
  EXPECT_TRUE(report.findings.empty()) << codes(report);
  EXPECT_EQ(report.triangles, 72u);
  EXPECT_GT(report.probe.penetrations, 1000u);
  EXPECT_EQ(report.probe.no_way_out, 0u);
}

TEST(Check, BoxWithoutItsBottomHasFourOpenEdges) {
  Scene scene;
  add_box_faces(scene, {0, 0, 0}, {1, 1, 1}, "wood", test::kAllFaces & ~test::kMinusY);
  const MeshTopology topology = analyse_mesh(to_glm(scene.vertices), scene.triangle_layers, 1);
  EXPECT_EQ(topology.open_edges, 4u);
  EXPECT_EQ(topology.inconsistent_edges, 0u);
  const CheckReport report = check(scene, [] {
    Config c;
    c.listener_position = glm::vec3(0.5f, 3, 0.5f);
    return c;
  }());
  const CheckFinding* open = test::find_finding(report, "open_edges");
  ASSERT_NE(open, nullptr) << codes(report);
  EXPECT_EQ(open->count, 4u);
  EXPECT_NE(open->message.find("wood 4"), std::string::npos) << open->message;
}

TEST(Check, TJunctionsOfATriangulatedSolidAreClosed) {
  // The +x face of a box is two quads split at z = 0.5; the neighbouring
  // faces are not split, so their edges meet the split at a T-junction.
  Scene scene;
  add_box_faces(scene, {0, 0, 0}, {1, 1, 1}, "brick", test::kAllFaces & ~test::kPlusX);
  add_quad(scene, {1, 0, 0}, {1, 1, 0}, {1, 1, 0.5f}, {1, 0, 0.5f}, "brick");
  add_quad(scene, {1, 0, 0.5f}, {1, 1, 0.5f}, {1, 1, 1}, {1, 0, 1}, "brick");
  const MeshTopology topology = analyse_mesh(to_glm(scene.vertices), scene.triangle_layers, 1);
  EXPECT_EQ(topology.open_edges, 0u);
  EXPECT_EQ(topology.inconsistent_edges, 0u);
  // Without the split face the same box is open on that side: 4 edges.
  Scene open;
  add_box_faces(open, {0, 0, 0}, {1, 1, 1}, "brick", test::kAllFaces & ~test::kPlusX);
  EXPECT_EQ(analyse_mesh(to_glm(open.vertices), open.triangle_layers, 1).open_edges, 4u);
}

// A comb (issue 38): one long edge along x, covered the other way round by
// the bases of `teeth` small triangles, each [i, i + 1] on the same line.
// Every base is closed by the long edge; the other two edges of each
// triangle lie on lines of their own and are open: 2 + 2 * teeth. With
// tooth `missing` left out, the long edge's stretch [missing, missing + 1]
// is covered one way only, so the long edge is open too. All the bases lie
// on one line, which a search pairing every stretch with every edge took
// quadratic time over (minutes at 100,000 teeth).
TEST(Check, CollinearEdgesOfACombAreMatchedAlongTheirLine) {
  constexpr int kTeeth = 20000;
  for (const int missing : {-1, 777}) {
    Scene scene;
    const float n = static_cast<float>(kTeeth);
    test::add_triangle(scene, {0, 0, 0}, {n, 0, 0}, {n / 2, 5, 0}, "concrete");  // base runs +x
    for (int i = 0; i < kTeeth; ++i) {
      if (i == missing) continue;
      const float x = static_cast<float>(i);
      test::add_triangle(scene, {x + 1, 0, 0}, {x, 0, 0}, {x + 0.5f, -1, 0}, "concrete");  // base runs -x
    }
    const MeshTopology topology = analyse_mesh(to_glm(scene.vertices), scene.triangle_layers, 1);
    const std::uint64_t teeth = missing < 0 ? kTeeth : kTeeth - 1;
    EXPECT_EQ(topology.open_edges, 2u + 2u * teeth + (missing < 0 ? 0u : 1u)) << "tooth missing: " << missing;
  }
}

// Corners far out (a level near 1e15 m, where float spacing is 2^26 m):
// equal coordinates still weld, so two triangles sharing an edge are one
// piece of surface, and the weld's grid arithmetic stays in range (it
// overflowed int64 past 9.2e14 m; UBSan in scripts/test.sh).
TEST(Check, CornersFarOutWeldByEquality) {
  for (const float far : {1.0e15f, -3.0e38f, 5000.0f}) {
    Scene scene;
    const float step = far * 1e-6f;
    add_quad(scene, {far, far, far}, {far + step, far, far}, {far + step, far + step, far}, {far, far + step, far},
             "concrete");
    const MeshTopology topology = analyse_mesh(to_glm(scene.vertices), scene.triangle_layers, 1);
    EXPECT_EQ(topology.solid_count, 1u) << far;
    EXPECT_EQ(topology.open_edges, 4u) << far;
  }
}

// The weld's rule, checked against every pair: each corner's welded
// position lies within 0.1 mm of it, equal corners share an id, and no two
// welded positions lie within 0.1 mm of each other (else one would have
// welded to the other). Clusters of corners a few micrometres apart, some
// straddling the grid's cell borders, and corners beyond 4096 m.
TEST(Check, WeldJoinsCornersWithinATenthOfAMillimetre) {
  std::mt19937 rng(38);
  std::uniform_real_distribution<float> place(-3.0f, 3.0f), jitter(-3e-5f, 3e-5f);
  std::vector<glm::vec3> corners;
  for (int cluster = 0; cluster < 300; ++cluster) {
    glm::vec3 centre(place(rng), place(rng), place(rng));
    if (cluster % 3 == 0) centre = glm::round(centre * 1e4f) / 1e4f;  // on a cell border
    if (cluster % 7 == 0) centre += glm::vec3(5000.0f, -9000.0f, 1.0e6f);
    for (int k = 0; k < 4; ++k) corners.push_back(centre + glm::vec3(jitter(rng), jitter(rng), jitter(rng)));
    corners.push_back(corners.back());  // an exact copy
  }
  std::vector<glm::vec3> positions;
  const std::vector<std::uint32_t> ids = weld(corners, positions);
  ASSERT_EQ(ids.size(), corners.size());
  for (std::size_t i = 0; i < corners.size(); ++i) {
    ASSERT_LT(ids[i], positions.size());
    EXPECT_LE(glm::distance(glm::dvec3(positions[ids[i]]), glm::dvec3(corners[i])), 1e-4) << i;
    if (i > 0 && corners[i] == corners[i - 1]) {
      EXPECT_EQ(ids[i], ids[i - 1]) << i;
    }
  }
  for (std::size_t a = 0; a < positions.size(); ++a)
    for (std::size_t b = 0; b < a; ++b) {
      EXPECT_GT(glm::distance(glm::dvec3(positions[a]), glm::dvec3(positions[b])), 1e-4) << a << " " << b;
    }
  EXPECT_LT(positions.size(), corners.size() / 2) << "the clusters weld";
}

TEST(Check, FlippedFaceHasFourInconsistentEdges) {
  Scene scene;
  add_box_faces(scene, {0, 0, 0}, {1, 1, 1}, "wood", test::kAllFaces, test::kPlusZ);
  const CheckReport report = check(scene, [] {
    Config c;
    c.listener_position = glm::vec3(0.5f, 3, 0.5f);
    return c;
  }());
  const CheckFinding* flipped = test::find_finding(report, "inconsistent_winding");
  ASSERT_NE(flipped, nullptr) << codes(report);
  EXPECT_EQ(flipped->count, 4u);  // the flipped face's outline; its diagonal is its own
  EXPECT_EQ(test::find_finding(report, "open_edges"), nullptr) << codes(report);
}

TEST(Check, DegenerateTrianglesAreCounted) {
  Scene scene = closed_room();
  test::add_triangle(scene, {0, 0, 0}, {1, 1, 1}, {2, 2, 2}, "concrete");  // collinear
  test::add_triangle(scene, {5, 5, 5}, {5, 5, 5}, {5, 5, 5}, "concrete");  // a point
  const CheckReport report = check(scene);
  const CheckFinding* degenerate = test::find_finding(report, "degenerate_triangles");
  ASSERT_NE(degenerate, nullptr) << codes(report);
  EXPECT_EQ(degenerate->count, 2u);
}

TEST(Check, LevelInQuakeUnitsIsProbablyNotInMetres) {
  Scene scene;
  test::add_closed_room(scene, {-1500, 0, -800}, {1500, 128, 800}, 16.0f, "concrete");
  scene.sources.push_back(test::source_at({0, 64, 0}, 3000.0f));
  const CheckReport report = check(scene);
  const CheckFinding* scale = test::find_finding(report, "scale");
  ASSERT_NE(scale, nullptr) << codes(report);
  EXPECT_EQ(scale->count, 3032u);  // 3000 inside plus two 16-unit walls
  EXPECT_EQ(test::find_finding(check(closed_room()), "scale"), nullptr);
}

TEST(Check, RenderMeshRoomLetsNoPenetrationOut) {
  // A sealed room's render mesh is a closed surface turned inside out (the
  // matter is everything outside): no open edge, but no way out either.
  const CheckReport report = check(render_mesh_room());
  EXPECT_EQ(test::find_finding(report, "open_edges"), nullptr) << codes(report);
  const CheckFinding* misses = test::find_finding(report, "penetration_misses");
  ASSERT_NE(misses, nullptr) << codes(report);
  EXPECT_EQ(report.probe.no_way_out, report.probe.penetrations);  // one surface, nothing behind it
  EXPECT_EQ(misses->count, report.probe.no_way_out);
  EXPECT_EQ(report.probe.back_face_hits, 0u);
}

TEST(Check, ThickWallsNeedALargerMaxWallThickness) {
  // 2 m walls: a way out always exists within the probe's 4 m (straight
  // through is 2 m), but hardly ever within the default W_max of 0.5 m.
  Scene scene;
  test::add_closed_room(scene, {-3, 0, -2.5f}, {3, 3, 2.5f}, 2.0f, "concrete");
  scene.sources.push_back(test::source_at({0.5f, 1.5f, 0.2f}));
  const CheckReport report = check(scene);
  EXPECT_EQ(test::find_finding(report, "penetration_misses"), nullptr) << codes(report);
  EXPECT_EQ(report.probe_at_config.no_way_out, report.probe_at_config.penetrations);
  ASSERT_NE(test::find_finding(report, "wall_thickness"), nullptr) << codes(report);
}

TEST(Check, RoomWoundInsideOutIsStruckFromBehind) {
  // The render-mesh room with its fronts facing out: every hit from the
  // source inside strikes the back of a face.
  Scene scene;
  add_box_faces(scene, {-3, 0, -2.5f}, {3, 3, 2.5f}, "concrete", test::kAllFaces);
  scene.sources.push_back(test::source_at({0.5f, 1.5f, 0.2f}));
  const CheckReport report = check(scene);
  const CheckFinding* back = test::find_finding(report, "back_faces");
  ASSERT_NE(back, nullptr) << codes(report);
  EXPECT_EQ(report.probe.back_face_hits, report.probe.hits);
  EXPECT_EQ(report.probe.penetrations, 0u);
}

TEST(Check, SheetLayersAreNotSearchedForAWayOut) {
  // The render-mesh room again, its layer declared a 5 cm sheet: each wall
  // is crossed on the spot, so nothing is missing.
  Config config;
  config.layers["concrete"] = {0.8f, 4.0f, 0.05f};
  const CheckReport report = check(render_mesh_room(), config);
  EXPECT_EQ(test::find_finding(report, "penetration_misses"), nullptr) << codes(report);
  EXPECT_EQ(report.probe.penetrations, 0u);
}

TEST(Check, InfoAndSimulateWarnWhenPenetrationMostlyFails) {
  CheckSettings at_config;
  at_config.probe_reach = 0.0f;  // the config's W_max, as info and simulate run it
  at_config.probe_steps = 4;
  Config config;
  const PenetrationProbe open = probe_penetration(render_mesh_room(), config, at_config).value();
  const std::string warning = penetration_warning(open);
  EXPECT_NE(warning.find("100% of probe penetrations find no way out"), std::string::npos) << warning;
  EXPECT_NE(warning.find("soundpaint check"), std::string::npos) << warning;
  config.listener_position = glm::vec3(0, 1.5f, 0);
  EXPECT_EQ(penetration_warning(probe_penetration(closed_room(), config, at_config).value()), "");
}

// A layer name with everything a hostile level would put in one: a new
// terminal title, a screen clear, and a forged line.
const std::string kHostileLayer = "wood\x1b]0;pwned\x07\x1b[2J\r\nsoundpaint: no findings\t\x7f";
const std::string kHostileLayerEscaped =
    "wood\\u{1b}]0;pwned\\u{7}\\u{1b}[2J\\u{d}\\u{a}soundpaint: no findings\\u{9}\\u{7f}";

TEST(PrintableText, PrintableUtf8StaysByteForByte) {
  for (const std::string text : {"", "concrete", "Holz.001", "C:\\levels\\a \"b\".gltf", "\xe6\x9c\xa8\xe6\x9d\x90",
                                 "\xf0\x9f\x94\x8a", "caf\xc3\xa9", "\xc2\xa0", "\xef\xbf\xbd"})
    EXPECT_EQ(printable_text(text), text);
}

TEST(PrintableText, ControlCodePointsAreWrittenAsCodePoints) {
  EXPECT_EQ(printable_text(kHostileLayer), kHostileLayerEscaped);
  EXPECT_EQ(printable_text(std::string("a\0b", 3)), "a\\u{0}b");
  EXPECT_EQ(printable_text("\x1f"), "\\u{1f}");
  EXPECT_EQ(printable_text("\xc2\x80\xc2\x85\xc2\x9b\xc2\x9f"), "\\u{80}\\u{85}\\u{9b}\\u{9f}");  // C1: PAD, NEL, CSI
  EXPECT_EQ(printable_text("a\xe2\x80\xa8"
                           "b\xe2\x80\xa9"),
            "a\\u{2028}b\\u{2029}");                                     // line, paragraph separators
  EXPECT_EQ(printable_text("\xe2\x80\xaegnp.exe"), "\\u{202e}gnp.exe");  // right-to-left override
  EXPECT_EQ(printable_text("\xe2\x81\xa6\xe2\x81\xa9\xd8\x9c\xe2\x80\x8e"), "\\u{2066}\\u{2069}\\u{61c}\\u{200e}");
}

TEST(PrintableText, BytesOfInvalidUtf8AreWrittenAsBytes) {
  EXPECT_EQ(printable_text("\xff"), "\\xff");
  EXPECT_EQ(printable_text("a\x80z"), "a\\x80z");  // a lone continuation byte
  EXPECT_EQ(printable_text("\x9b"
                           "31m"),
            "\\x9b31m");                                                  // raw 8-bit CSI
  EXPECT_EQ(printable_text("\xc0\xaf"), "\\xc0\\xaf");                    // overlong '/'
  EXPECT_EQ(printable_text("\xe0\x80\xaf"), "\\xe0\\x80\\xaf");           // overlong, three bytes
  EXPECT_EQ(printable_text("\xed\xa0\x80"), "\\xed\\xa0\\x80");           // a surrogate
  EXPECT_EQ(printable_text("\xf4\x90\x80\x80"), "\\xf4\\x90\\x80\\x80");  // above U+10FFFF
  EXPECT_EQ(printable_text("ab\xe6\x9c"), "ab\\xe6\\x9c");                // cut short at the end
  EXPECT_EQ(printable_text("\xe6\x9c"
                           "a"),
            "\\xe6\\x9ca");                                           // cut short by an ASCII byte
  EXPECT_EQ(printable_text("\xf4\x8f\xbf\xbf"), "\xf4\x8f\xbf\xbf");  // U+10FFFF itself is well-formed
}

TEST(PrintableText, QuotingEscapesQuotesAndBackslashesOnlyWhenAsked) {
  EXPECT_EQ(printable_text("a\"b\\c\n", TextQuoting::DoubleQuoted), "a\\\"b\\\\c\\u{a}");
  EXPECT_EQ(printable_text("a\"b\\c\n"), "a\"b\\c\\u{a}");
  // Bare escaping is idempotent: a message whose names were escaped can be
  // passed through again, unchanged.
  for (const std::string& text : {kHostileLayer, std::string("\xff\xc2\x9b\\u{1b}\\x41")})
    EXPECT_EQ(printable_text(printable_text(text)), printable_text(text)) << text;
}

TEST(Check, LayerNamesAreEscapedInMessagesAndExactInTheReport) {
  Scene scene;
  add_box_faces(scene, {0, 0, 0}, {1, 1, 1}, kHostileLayer, test::kAllFaces & ~test::kMinusY);
  Config config;
  config.listener_position = glm::vec3(0.5f, 3, 0.5f);
  const CheckReport report = check(scene, config);
  const CheckFinding* open = test::find_finding(report, "open_edges");
  ASSERT_NE(open, nullptr) << codes(report);
  EXPECT_NE(open->message.find(" (" + kHostileLayerEscaped + " 4)"), std::string::npos) << open->message;
  EXPECT_EQ(open->message.find_first_of("\x1b\x07\r\n\t\x7f"), std::string::npos) << open->message;
  ASSERT_EQ(open->layers.size(), 1u);
  EXPECT_EQ(open->layers[0].name, kHostileLayer);
  EXPECT_EQ(open->layers[0].count, 4u);
}

TEST(Check, JsonReportKeepsValidNamesExactAndMarksInvalidBytes) {
  const std::string not_utf8 = "brick\xff\xc0\xaf";
  Scene scene;
  add_box_faces(scene, {0, 0, 0}, {1, 1, 1}, kHostileLayer, test::kAllFaces & ~test::kMinusY);
  add_box_faces(scene, {3, 0, 0}, {4, 1, 1}, not_utf8, test::kAllFaces & ~test::kMinusY & ~test::kPlusY);
  Config config;
  config.listener_position = glm::vec3(2, 3, 0.5f);
  const CheckReport report = check(scene, config);
  std::string text;
  ASSERT_NO_THROW(text = check_report_json(report));
  const nlohmann::json json = nlohmann::json::parse(text);
  const nlohmann::json* open = nullptr;
  for (const nlohmann::json& f : json["findings"])
    if (f["code"] == "open_edges") open = &f;
  ASSERT_NE(open, nullptr) << text;
  ASSERT_EQ((*open)["layers"].size(), 2u) << text;
  // The most edges first: 8 round the two open sides, then 4.
  EXPECT_EQ((*open)["layers"][0]["name"], "brick\xef\xbf\xbd\xef\xbf\xbd\xef\xbf\xbd") << text;
  EXPECT_EQ((*open)["layers"][0]["count"], 8u);
  EXPECT_EQ((*open)["layers"][1]["name"], kHostileLayer);
  EXPECT_EQ((*open)["layers"][1]["count"], 4u);
  EXPECT_EQ((*open)["message"], test::find_finding(report, "open_edges")->message);
}

TEST(Check, ConfigOverTheMemoryBudgetIsAFindingWithTheConfigsOwnValues) {
  Config config;
  config.max_indicators = kMaxIndicatorsLimit;
  config.listener_position = glm::vec3(0, 1.5f, 0);
  CheckSettings settings;
  settings.probe_steps = 2;
  settings.threads = 2;
  const Result<CheckReport> checked = check_scene(closed_room(), config, settings);
  ASSERT_TRUE(checked) << checked.error().message;
  const CheckReport& report = checked.value();
  const CheckFinding* budget = test::find_finding(report, "memory_budget");
  ASSERT_NE(budget, nullptr) << codes(report);
  const std::uint64_t needed =
      std::max(estimate_memory(config, Backend::Cpu).total(), estimate_memory(config, Backend::Gpu).total());
  EXPECT_GT(needed, kDefaultMemoryBudgetBytes);
  EXPECT_EQ(budget->count, needed);
  for (const char* part : {"max_indicators 16777216", "ray_budget 500 with max_bounces 4",
                           "over the memory budget of 2.0 GiB", "--memory-budget "})
    EXPECT_NE(budget->message.find(part), std::string::npos) << part << " in " << budget->message;
  EXPECT_EQ(budget->message.find("ray_budget 2000"), std::string::npos) << budget->message;  // the probe's own

  // The budget the finding advises is enough.
  const std::size_t at = budget->message.find("--memory-budget ") + 16;
  const std::uint64_t advised_gib = std::stoull(budget->message.substr(at));
  EXPECT_EQ(budget->message.substr(at + std::to_string(advised_gib).size(), 1), "G") << budget->message;
  settings.memory_budget_bytes = advised_gib << 30;
  EXPECT_GE(settings.memory_budget_bytes, needed);
  EXPECT_EQ(test::find_finding(check_scene(closed_room(), config, settings).value(), "memory_budget"), nullptr);
  // And a small config fits the default budget.
  EXPECT_EQ(test::find_finding(check(closed_room()), "memory_budget"), nullptr);
}

TEST(Check, LevelBeyondFloatRangeHasASaneScaleCount) {
  // -3e38 to 3e38 is 6e38 across: more than a float holds, and than a
  // 64-bit count. The count stops at 2^53, which JSON carries exactly.
  Scene scene;
  test::add_triangle(scene, {-3e38f, 0, 0}, {3e38f, 0, 0}, {0, 3e38f, 0}, "concrete");
  const CheckReport report = check(scene);
  const CheckFinding* scale = test::find_finding(report, "scale");
  ASSERT_NE(scale, nullptr) << codes(report);
  EXPECT_EQ(scale->count, std::uint64_t{1} << 53);
  EXPECT_NE(scale->message.find("the level is 6e+38 units across"), std::string::npos) << scale->message;
}

TEST(Check, ProbeStartsInsideALevelFarFromTheOrigin) {
  // No source, listener or camera: the probe starts at the bounds' centre,
  // (2e38 + 3e38) / 2, which must not overflow on the way.
  Scene scene;
  test::add_triangle(scene, {2e38f, 0, 0}, {3e38f, 0, 0}, {2e38f, 3e38f, 0}, "concrete");
  CheckSettings settings;
  settings.probe_steps = 1;
  settings.threads = 2;
  const Result<CheckReport> report = check_scene(scene, Config{}, settings);
  ASSERT_TRUE(report) << report.error().message;
  EXPECT_NE(test::find_finding(report.value(), "scale"), nullptr);
}

}  // namespace
}  // namespace sp
