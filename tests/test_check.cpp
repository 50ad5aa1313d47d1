// sp::check_scene (`soundpaint check`) on scenes built to have exactly one
// problem each, with counts derived by hand, and on a closed room that must
// have none.
#include <algorithm>
#include <string>

#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include "bvh/mesh_topology.h"
#include "core/glm_interop.h"
#include "soundpaint/check.h"
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

const CheckFinding* find(const CheckReport& report, const std::string& code) {
  for (const CheckFinding& f : report.findings)
    if (f.code == code) return &f;
  return nullptr;
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
  const CheckFinding* open = find(report, "open_edges");
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

TEST(Check, FlippedFaceHasFourInconsistentEdges) {
  Scene scene;
  add_box_faces(scene, {0, 0, 0}, {1, 1, 1}, "wood", test::kAllFaces, test::kPlusZ);
  const CheckReport report = check(scene, [] {
    Config c;
    c.listener_position = glm::vec3(0.5f, 3, 0.5f);
    return c;
  }());
  const CheckFinding* flipped = find(report, "inconsistent_winding");
  ASSERT_NE(flipped, nullptr) << codes(report);
  EXPECT_EQ(flipped->count, 4u);  // the flipped face's outline; its diagonal is its own
  EXPECT_EQ(find(report, "open_edges"), nullptr) << codes(report);
}

TEST(Check, DegenerateTrianglesAreCounted) {
  Scene scene = closed_room();
  test::add_triangle(scene, {0, 0, 0}, {1, 1, 1}, {2, 2, 2}, "concrete");  // collinear
  test::add_triangle(scene, {5, 5, 5}, {5, 5, 5}, {5, 5, 5}, "concrete");  // a point
  const CheckReport report = check(scene);
  const CheckFinding* degenerate = find(report, "degenerate_triangles");
  ASSERT_NE(degenerate, nullptr) << codes(report);
  EXPECT_EQ(degenerate->count, 2u);
}

TEST(Check, LevelInQuakeUnitsIsProbablyNotInMetres) {
  Scene scene;
  test::add_closed_room(scene, {-1500, 0, -800}, {1500, 128, 800}, 16.0f, "concrete");
  scene.sources.push_back(test::source_at({0, 64, 0}, 3000.0f));
  const CheckReport report = check(scene);
  const CheckFinding* scale = find(report, "scale");
  ASSERT_NE(scale, nullptr) << codes(report);
  EXPECT_EQ(scale->count, 3032u);  // 3000 inside plus two 16-unit walls
  EXPECT_EQ(find(check(closed_room()), "scale"), nullptr);
}

TEST(Check, RenderMeshRoomLetsNoPenetrationOut) {
  // A sealed room's render mesh is a closed surface turned inside out (the
  // matter is everything outside): no open edge, but no way out either.
  const CheckReport report = check(render_mesh_room());
  EXPECT_EQ(find(report, "open_edges"), nullptr) << codes(report);
  const CheckFinding* misses = find(report, "penetration_misses");
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
  EXPECT_EQ(find(report, "penetration_misses"), nullptr) << codes(report);
  EXPECT_EQ(report.probe_at_config.no_way_out, report.probe_at_config.penetrations);
  ASSERT_NE(find(report, "wall_thickness"), nullptr) << codes(report);
}

TEST(Check, RoomWoundInsideOutIsStruckFromBehind) {
  // The render-mesh room with its fronts facing out: every hit from the
  // source inside strikes the back of a face.
  Scene scene;
  add_box_faces(scene, {-3, 0, -2.5f}, {3, 3, 2.5f}, "concrete", test::kAllFaces);
  scene.sources.push_back(test::source_at({0.5f, 1.5f, 0.2f}));
  const CheckReport report = check(scene);
  const CheckFinding* back = find(report, "back_faces");
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
  EXPECT_EQ(find(report, "penetration_misses"), nullptr) << codes(report);
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

}  // namespace
}  // namespace sp
