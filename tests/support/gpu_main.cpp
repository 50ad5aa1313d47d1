// main() of the test binaries that need Vulkan: one validation-enabled
// context per binary, held by the GpuEnvironment (support/vulkan_environment.h).
#include <gtest/gtest.h>

#include <cstdlib>

#include "support/vulkan_environment.h"

int main(int argc, char** argv) {
  // The validation layer checks synchronization too (hazards between
  // commands, such as a shader stage reading what a barrier did not cover),
  // here and in the soundpaint processes the tests start, which inherit it.
  // A value already set by whoever runs the tests is kept.
  setenv("VK_LAYER_ENABLES", "VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT", 0);
  ::testing::InitGoogleTest(&argc, argv);
  ::testing::AddGlobalTestEnvironment(new sp::test::GpuEnvironment);
  return RUN_ALL_TESTS();
}
