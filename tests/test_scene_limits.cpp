// The bounds a scene from a stranger meets (README "Security"): JSON nesting
// depth before tinygltf's recursive parse.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

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

}  // namespace
