// The C API given hostile scenes and configs (README "Security"): where a
// host process used to die (stack overflow in the glTF parser, bad_alloc on
// a worker), it now gets an error code and a one-line message.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "soundpaint/soundpaint.h"
#include "sp_types.h"
#include "support/gltf_builder.h"
#include "support/test_directory.h"

namespace {

namespace fs = std::filesystem;

std::string last_error() { return sp_last_error_message(); }

class CapiUntrusted : public sp::test::TestDirectory {
 protected:
  void SetUp() override {
    TestDirectory::SetUp();
    fs::create_directories(dir_ / "level");
    // The unit triangle and a camera; its buffer in outside.bin, next to
    // the level folder rather than in it.
    b_.root(b_.node({{"mesh", b_.unit_triangle_mesh()}}));
    b_.doc["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.05}}}}};
    b_.root(b_.node({{"camera", 0}, {"translation", {0.2, 0.2, 2}}}));
    write("outside.bin", b_.bin);
    write("level/escape.gltf", b_.gltf_with_buffer_uri("../outside.bin"));
    write("level/embedded.gltf", b_.gltf());
  }
  std::string path(const std::string& name) const { return (dir_ / "level" / name).string(); }

  sp::test::GltfBuilder b_;
};

TEST_F(CapiUntrusted, DeepJsonSceneIsAnErrorNotACrash) {
  std::ofstream(path("deep.gltf")) << "{\"asset\": {\"version\": \"2.0\"}, \"extras\": " << std::string(20000, '[')
                                   << std::string(20000, ']') << "}";
  sp_scene* scene = nullptr;
  EXPECT_EQ(sp_scene_load(path("deep.gltf").c_str(), &scene), SP_ERROR_INVALID_SCENE);
  EXPECT_EQ(scene, nullptr);
  EXPECT_EQ(last_error(), path("deep.gltf") + ": cannot load glTF: JSON nested deeper than 128 levels");
}

TEST_F(CapiUntrusted, SceneLoadOptionsLiftTheFolderRuleOnlyWhenAsked) {
  sp_scene* scene = nullptr;
  EXPECT_EQ(sp_scene_load(path("escape.gltf").c_str(), &scene), SP_ERROR_INVALID_SCENE);
  EXPECT_NE(last_error().find("buffer URI \"../outside.bin\": leads out of the scene's folder"), std::string::npos)
      << last_error();

  sp_scene_load_options options;
  sp_scene_load_options_init(&options);
  EXPECT_EQ(options.flags, 0u);
  EXPECT_EQ(options.max_triangles, 2000000u);
  EXPECT_EQ(sp_scene_load_with_options(path("escape.gltf").c_str(), &options, &scene), SP_ERROR_INVALID_SCENE);
  options.flags = SP_SCENE_LOAD_ALLOW_EXTERNAL_URIS;
  ASSERT_EQ(sp_scene_load_with_options(path("escape.gltf").c_str(), &options, &scene), SP_OK) << last_error();
  EXPECT_EQ(sp_scene_destroy(scene), SP_OK);
}

TEST_F(CapiUntrusted, SceneLoadOptionsAreChecked) {
  sp_scene* scene = nullptr;
  sp_scene_load_options options;
  sp_scene_load_options_init(&options);
  EXPECT_EQ(sp_scene_load_with_options(path("embedded.gltf").c_str(), nullptr, &scene), SP_ERROR_INVALID_ARGUMENT);
  options.flags = 6;
  EXPECT_EQ(sp_scene_load_with_options(path("embedded.gltf").c_str(), &options, &scene), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("unknown bits"), std::string::npos) << last_error();
  options.flags = 0;
  options.max_triangles = 0;
  EXPECT_EQ(sp_scene_load_with_options(path("embedded.gltf").c_str(), &options, &scene), SP_ERROR_INVALID_ARGUMENT);
  options.max_triangles = 1;
  ASSERT_EQ(sp_scene_load_with_options(path("embedded.gltf").c_str(), &options, &scene), SP_OK) << last_error();
  EXPECT_EQ(sp_scene_destroy(scene), SP_OK);
  b_.root(b_.node({{"mesh", 0}, {"translation", {0, 0, -1}}}));  // a second instance: 2 triangles
  std::ofstream(path("two.gltf")) << b_.gltf();
  EXPECT_EQ(sp_scene_load_with_options(path("two.gltf").c_str(), &options, &scene), SP_ERROR_INVALID_SCENE);
  EXPECT_NE(last_error().find("more than 1 triangles"), std::string::npos) << last_error();
  sp_scene_load_options_init(nullptr);  // a no-op
}

// The README's maxima used to abort the host with std::bad_alloc after a
// minute; now creation refuses them at once.
TEST_F(CapiUntrusted, ImpossibleConfigsAreRefusedAtCreation) {
  sp_scene* scene = nullptr;
  ASSERT_EQ(sp_scene_load(path("embedded.gltf").c_str(), &scene), SP_OK) << last_error();
  sp_simulation* sim = nullptr;
  const char* maximal = R"({"max_bounces": 64, "ray_budget": 16777216, "max_indicators": 16777216})";
  EXPECT_EQ(sp_simulation_create(scene, maximal, SP_BACKEND_CPU, &sim), SP_ERROR_LIMIT_EXCEEDED);
  EXPECT_EQ(sim, nullptr);
  EXPECT_NE(last_error().find("over the memory budget of 2.0 GiB"), std::string::npos) << last_error();

  const std::string deep = "{\"listener\": " + std::string(70000, '[') + std::string(70000, ']') + "}";
  EXPECT_EQ(sp_simulation_create(scene, deep.c_str(), SP_BACKEND_CPU, &sim), SP_ERROR_INVALID_CONFIG);
  EXPECT_NE(last_error().find("JSON nested deeper than 128 levels"), std::string::npos) << last_error();

  sp_simulation_options options;
  sp_simulation_options_init(&options);
  EXPECT_EQ(options.backend, SP_BACKEND_AUTO);
  EXPECT_EQ(options.memory_budget_bytes, std::uint64_t{2} << 30);
  options.backend = SP_BACKEND_CPU;
  options.memory_budget_bytes = 1024;
  EXPECT_EQ(sp_simulation_create_with_options(scene, nullptr, &options, &sim), SP_ERROR_LIMIT_EXCEEDED);
  EXPECT_NE(last_error().find("memory budget of 1.0 KiB"), std::string::npos) << last_error();
  options.memory_budget_bytes = 0;
  EXPECT_EQ(sp_simulation_create_with_options(scene, nullptr, &options, &sim), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_simulation_create_with_options(scene, nullptr, nullptr, &sim), SP_ERROR_INVALID_ARGUMENT);
  options.memory_budget_bytes = std::uint64_t{64} << 20;
  ASSERT_EQ(sp_simulation_create_with_options(scene, nullptr, &options, &sim), SP_OK) << last_error();
  EXPECT_EQ(sp_simulation_step(sim), SP_OK) << last_error();
  EXPECT_EQ(sp_simulation_destroy(sim), SP_OK);
  EXPECT_EQ(sp_scene_destroy(scene), SP_OK);
}

}  // namespace
