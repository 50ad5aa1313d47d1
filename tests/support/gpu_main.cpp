// main() of the test binaries that need Vulkan: one validation-enabled
// context per binary, held by the GpuEnvironment (support/vulkan_environment.h).
#include <gtest/gtest.h>

#include "support/vulkan_environment.h"

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ::testing::AddGlobalTestEnvironment(new sp::test::GpuEnvironment);
  return RUN_ALL_TESTS();
}
