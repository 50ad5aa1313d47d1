// The bounds a scene from a stranger meets (README "Security"): JSON nesting
// depth before tinygltf's recursive parse, the total triangle count before
// any triangle is built, and instancing that costs only its triangles.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "soundpaint/scene.h"
#include "support/gltf_builder.h"
#include "support/test_directory.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using sp::test::GltfBuilder;

using SceneLimits = sp::test::TestDirectory;

// The unit triangle with `levels` nested objects as its node's extras:
// {"a": {"a": ... 1}}. The file's nesting is then levels + 3: the root
// object, the "nodes" array and the node object come first.
GltfBuilder triangle_with_extras_depth(int levels) {
  GltfBuilder b;
  b.root(b.node({{"mesh", b.unit_triangle_mesh()}}));
  json extras = 1;
  for (int i = 0; i < levels; ++i) extras = json{{"a", std::move(extras)}};
  b.doc["nodes"][0]["extras"] = std::move(extras);
  return b;
}

// nlohmann's dump recurses too; writing text by hand keeps the test itself
// safe at 20,000 levels.
std::string deeply_nested_gltf(int levels) {
  const std::string valid = triangle_with_extras_depth(0).gltf();
  const std::string node = "\"mesh\": 0";
  std::string extras;
  for (int i = 0; i < levels; ++i) extras += "{\"a\":";
  extras += "1";
  extras.append(static_cast<std::size_t>(levels), '}');
  std::string text = valid;
  const std::size_t at = text.find(node);
  text.insert(at + node.size(), ", \"extras\": " + extras);
  return text;
}

// 20,000 levels of extras in a 40 KB file used to overflow the stack in
// tinygltf's recursive parse (a crash of the host, through sp_scene_load).
TEST_F(SceneLimits, RefusesDeepJsonBeforeParsingIt) {
  for (const std::string name : {"deep.gltf", "deep-twenty-thousand.gltf"}) {
    const int levels = name == "deep.gltf" ? 1000 : 20000;
    const fs::path path = write(name, deeply_nested_gltf(levels));
    const sp::Result<sp::Scene> scene = sp::load_scene(path);
    ASSERT_FALSE(scene.ok());
    EXPECT_EQ(scene.error().code, sp::ErrorCode::InvalidScene);
    EXPECT_EQ(scene.error().message, path.string() + ": cannot load glTF: JSON nested deeper than 128 levels");
  }
}

TEST_F(SceneLimits, DepthLimitIsExactlyTheDocumentedOne) {
  const sp::Result<sp::Scene> at_limit = sp::load_scene(write("128.gltf", triangle_with_extras_depth(125).gltf()));
  ASSERT_TRUE(at_limit.ok()) << at_limit.error().message;
  EXPECT_EQ(at_limit->triangle_count(), 1u);
  const sp::Result<sp::Scene> over = sp::load_scene(write("129.gltf", triangle_with_extras_depth(126).gltf()));
  ASSERT_FALSE(over.ok());
  EXPECT_NE(over.error().message.find("nested deeper than 128 levels"), std::string::npos) << over.error().message;
  // The JSON chunk of a binary file is scanned too.
  const sp::Result<sp::Scene> glb = sp::load_scene(write("129.glb", triangle_with_extras_depth(126).glb()));
  ASSERT_FALSE(glb.ok());
  EXPECT_NE(glb.error().message.find("cannot load binary glTF: JSON nested deeper than 128 levels"), std::string::npos)
      << glb.error().message;
}

TEST_F(SceneLimits, CountsEveryInstanceAgainstMaxTriangles) {
  const fs::path path = write("boxes.glb", sp::test::instanced_unit_boxes(20000).glb());
  sp::SceneLoadOptions options;
  options.max_triangles = 20000 * 12 - 1;
  const sp::Result<sp::Scene> refused = sp::load_scene(path, options);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().message,
            path.string() +
                ": more than 239999 triangles over its 20000 mesh instances (the limit max_triangles can "
                "be raised: --max-triangles, SceneLoadOptions)");
  options.max_triangles = 20000 * 12;
  const sp::Result<sp::Scene> loaded = sp::load_scene(path, options);
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  EXPECT_EQ(loaded->triangle_count(), 240000u);
  // The last instance sits at x = 3 * 19999; its first triangle is the
  // box's (0,0,0), (0,1,0), (1,1,0) moved there.
  const std::size_t last = 3 * 12 * 19999;
  EXPECT_EQ(loaded->vertices[last], glm::vec3(59997, 0, 0));
  EXPECT_EQ(loaded->vertices[last + 1], glm::vec3(59997, 1, 0));
  EXPECT_EQ(loaded->vertices[last + 2], glm::vec3(59998, 1, 0));
}

// A 50k-triangle strip mesh placed by `instances` nodes.
GltfBuilder instanced_strips(int instances) {
  GltfBuilder b;
  std::vector<glm::vec3> strip;
  for (int i = 0; i < 25001; ++i) {
    strip.push_back({0.01f * static_cast<float>(i), 0, 0});
    strip.push_back({0.01f * static_cast<float>(i), 1, 0});
  }
  const int mesh = b.mesh(json::array({{{"attributes", {{"POSITION", b.positions(strip)}}}, {"mode", 5}}}));
  for (int i = 0; i < instances; ++i) b.root(b.node({{"mesh", mesh}}));
  return b;
}

// The input: 20,000 nodes instancing one 50k-triangle mesh (10^9
// triangles) in a small file. Refused from the counts alone, at once.
TEST_F(SceneLimits, RefusesABillionInstancedTrianglesFromTheCounts) {
  const fs::path path = write("billion.glb", instanced_strips(20000).glb());
  const sp::Result<sp::Scene> scene = sp::load_scene(path);
  ASSERT_FALSE(scene.ok());
  EXPECT_NE(scene.error().message.find("more than 2000000 triangles over its 20000 mesh instances"), std::string::npos)
      << scene.error().message;
  // However high max_triangles is set, triangle ids stay 32-bit.
  sp::SceneLoadOptions unlimited;
  unlimited.max_triangles = UINT64_MAX;
  const sp::Result<sp::Scene> capped = sp::load_scene(write("1.5e9.glb", instanced_strips(30000).glb()), unlimited);
  ASSERT_FALSE(capped.ok());
  EXPECT_NE(capped.error().message.find("1431655765 triangles over its 30000 mesh instances, the most soundpaint"),
            std::string::npos)
      << capped.error().message;
}

}  // namespace
