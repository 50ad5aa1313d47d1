// Tests for the Vulkan plumbing in src/vk: context, buffers and their
// host <-> device copies, compute pipelines, error checking, RAII owners.
// One Context (validation on) serves the whole binary; every test must leave
// the validation message count unchanged, and so must the final teardown,
// where the layer reports leaked objects.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "sp_types.h"
#include "support/vulkan_environment.h"
#include "test_fill.comp.spv.h"
#include "vk/barriers.h"
#include "vk/buffer.h"
#include "vk/compute_pipeline.h"
#include "vk/context.h"
#include "vk/debug_messenger.h"
#include "vk/device_selection.h"
#include "soundpaint/visualizer.h"
#include "vk/handle.h"
#include "vk/objects.h"
#include "vk/vk_check.h"

namespace {

using sp::ErrorCode;
using sp::vk::Buffer;
using sp::vk::ComputePipeline;
using sp::vk::Context;
using sp::vk::MemoryUsage;
using sp::vk::StorageBindings;

// ---------------------------------------------------------------------------
// The one Context of this binary: the shared GPU harness
// (support/vulkan_environment.h), registered here since this binary uses
// gtest_main.

[[maybe_unused]] ::testing::Environment* const kEnvironment =
    ::testing::AddGlobalTestEnvironment(new sp::test::GpuEnvironment);

class VkTest : public sp::test::VulkanTest {
 protected:
  Context& context() { return *sp::test::GpuEnvironment::context(); }
};

// Sets (or, with nullptr, unsets) an environment variable for one scope.
struct EnvOverride {
  const char* name;
  std::optional<std::string> saved;
  EnvOverride(const char* variable, const char* value) : name(variable) {
    if (const char* old = std::getenv(variable)) saved = old;
    if (value != nullptr) {
      setenv(variable, value, 1);
    } else {
      unsetenv(variable);
    }
  }
  ~EnvOverride() {
    if (saved) {
      setenv(name, saved->c_str(), 1);
    } else {
      unsetenv(name);
    }
  }
};

std::vector<std::uint32_t> pattern(std::size_t count, std::uint32_t seed) {
  std::vector<std::uint32_t> values(count);
  for (std::size_t i = 0; i < count; ++i) values[i] = (static_cast<std::uint32_t>(i) + seed) * 2654435761u;
  return values;
}

// ---------------------------------------------------------------------------
// The test_fill kernel: data[i] = value + i for i < count.

constexpr std::uint32_t kFillGroupSize = SP_WORKGROUP_SIZE;  // tests/shaders/test_fill.comp's local_size_x

struct FillPush {
  std::uint32_t count;
  std::uint32_t value;
};

struct FillKernel {
  StorageBindings bindings;
  ComputePipeline pipeline;

  explicit FillKernel(const Context& context)
      : bindings(context, 1, "test_fill bindings"),
        pipeline(context, sp_spirv_test_fill_comp, bindings.layout(), sizeof(FillPush), "test_fill") {}

  void bind_and_push(VkCommandBuffer cmd, FillPush push) const {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.get());
    const VkDescriptorSet set = bindings.set();
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.layout(), 0, 1, &set, 0, nullptr);
    vkCmdPushConstants(cmd, pipeline.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
  }

  void dispatch(VkCommandBuffer cmd, FillPush push) const {
    bind_and_push(cmd, push);
    vkCmdDispatch(cmd, (push.count + kFillGroupSize - 1) / kFillGroupSize, 1, 1);
  }
};

constexpr VkBufferUsageFlags kStorageCopyable =
    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
constexpr std::uint32_t kUntouched = 0xdeadbeefu;

std::vector<std::uint32_t> download_all(Context& context, const Buffer& buffer) {
  std::vector<std::uint32_t> values(buffer.size() / sizeof(std::uint32_t));
  sp::vk::download(context, buffer, values.data(), buffer.size());
  return values;
}

// ---------------------------------------------------------------------------
// Context

TEST_F(VkTest, ContextDescribesDeviceAndDriver) {
  EXPECT_TRUE(context().validation_enabled());
  EXPECT_NE(context().device(), VK_NULL_HANDLE);
  EXPECT_NE(context().queue(), VK_NULL_HANDLE);
  const std::string description = context().description();
  EXPECT_EQ(description.rfind(context().properties().deviceName, 0), 0u) << description;
  EXPECT_NE(description.find(", driver "), std::string::npos) << description;
  EXPECT_GE(VK_API_VERSION_MINOR(context().properties().apiVersion), 3u);
  const std::uint32_t subgroup = context().subgroup_size();
  EXPECT_GE(subgroup, 1u);
  EXPECT_EQ(subgroup & (subgroup - 1), 0u) << "subgroup size " << subgroup << " is not a power of two";
}

TEST_F(VkTest, MemoryTypeHonoursRequiredFlagsAndThrowsWhenNoneFits) {
  const std::uint32_t host = context().memory_type(~0u, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT);
  EXPECT_LT(host, 32u);
  try {
    (void)context().memory_type(0u, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT);
    FAIL() << "memory_type accepted an empty type mask";
  } catch (const sp::Exception& e) {
    EXPECT_EQ(e.error().code, ErrorCode::Vulkan);
  }
}

TEST_F(VkTest, InvalidDeviceNameListsAvailableDevices) {
  // A second context, only because this negative case needs one; no validation.
  sp::vk::ContextSettings settings;
  settings.device_name = "no-such-device-42";
  const auto result = Context::create(settings);
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.error().code, ErrorCode::Vulkan);
  EXPECT_NE(result.error().message.find("no-such-device-42"), std::string::npos) << result.error().message;
  EXPECT_NE(result.error().message.find(context().properties().deviceName), std::string::npos)
      << result.error().message;
}

TEST_F(VkTest, DeviceNameComesFromTheEnvironmentWhenNotSet) {
  const EnvOverride device("SOUNDPAINT_DEVICE", "no-such-env-device");
  const auto result = Context::create(sp::vk::ContextSettings{});
  ASSERT_FALSE(result.ok());
  EXPECT_NE(result.error().message.find("\"no-such-env-device\""), std::string::npos) << result.error().message;
}

// Fails before any instance exists.
TEST_F(VkTest, MissingValidationLayerNamesThePackage) {
  const EnvOverride layer_path("VK_LAYER_PATH", "/nonexistent/soundpaint_no_layers");
  const EnvOverride add_layer_path("VK_ADD_LAYER_PATH", nullptr);
  sp::vk::ContextSettings settings;
  settings.validation = true;
  const auto result = Context::create(settings);
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.error().code, ErrorCode::Vulkan);
  EXPECT_NE(result.error().message.find("VK_LAYER_KHRONOS_validation"), std::string::npos) << result.error().message;
  EXPECT_NE(result.error().message.find("vulkan-validationlayers"), std::string::npos) << result.error().message;
}

// With the loader pointed at a driver manifest that does not exist, create()
// returns the "install mesa-vulkan-drivers" error instead of crashing. Creates
// no device.
TEST_F(VkTest, NoDriverGivesInstallHint) {
  const EnvOverride driver_files("VK_DRIVER_FILES", "/nonexistent/soundpaint_no_driver.json");
  const EnvOverride icd_filenames("VK_ICD_FILENAMES", "/nonexistent/soundpaint_no_driver.json");
  const EnvOverride add_driver_files("VK_ADD_DRIVER_FILES", nullptr);
  const auto result = Context::create(sp::vk::ContextSettings{});
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.error().code, ErrorCode::Vulkan);
  EXPECT_EQ(result.error().message, sp::vk::kNoDeviceMessage);
}

// ---------------------------------------------------------------------------
// VK_CHECK (no device needed)

TEST(VkCheck, FailureThrowsWithCallResultAndLocation) {
  const int line = __LINE__ + 2;
  try {
    SP_VK_CHECK(VK_ERROR_DEVICE_LOST);
    FAIL() << "SP_VK_CHECK did not throw";
  } catch (const sp::Exception& e) {
    EXPECT_EQ(e.error().code, ErrorCode::Vulkan);
    EXPECT_EQ(e.error().vk_result, static_cast<int>(VK_ERROR_DEVICE_LOST));
    EXPECT_EQ(e.error().message,
              "VK_ERROR_DEVICE_LOST failed: VK_ERROR_DEVICE_LOST (test_vk.cpp:" + std::to_string(line) + ")");
  }
}

TEST(VkCheck, SuccessCodesPass) {
  EXPECT_NO_THROW(SP_VK_CHECK(VK_SUCCESS));
  EXPECT_NO_THROW(SP_VK_CHECK(VK_INCOMPLETE));
  EXPECT_NO_THROW(SP_VK_CHECK(VK_SUBOPTIMAL_KHR));
}

TEST(VkCheck, ResultNames) {
  EXPECT_STREQ(sp::vk::result_name(VK_SUCCESS), "VK_SUCCESS");
  EXPECT_STREQ(sp::vk::result_name(VK_ERROR_OUT_OF_DEVICE_MEMORY), "VK_ERROR_OUT_OF_DEVICE_MEMORY");
  EXPECT_STREQ(sp::vk::result_name(VK_ERROR_INCOMPATIBLE_DRIVER), "VK_ERROR_INCOMPATIBLE_DRIVER");
  EXPECT_STREQ(sp::vk::result_name(static_cast<VkResult>(-123456)), "VK_RESULT_UNKNOWN");
  try {
    sp::vk::check_result(static_cast<VkResult>(-123456), "vkFoo()", "/a/b/c.cpp", 7);
    FAIL() << "check_result did not throw";
  } catch (const sp::Exception& e) {
    EXPECT_EQ(e.error().message, "vkFoo() failed: VK_RESULT_UNKNOWN -123456 (c.cpp:7)");
  }
}

// ---------------------------------------------------------------------------
// Buffers

TEST_F(VkTest, DeviceLocalUploadDownloadRoundTrip) {
  const std::vector<std::uint32_t> values = pattern(16 * 1024, 1);
  const VkDeviceSize bytes = values.size() * sizeof(values[0]);
  Buffer buffer(context(), bytes, kStorageCopyable, MemoryUsage::DeviceLocal, "round trip");
  ASSERT_TRUE(buffer);
  EXPECT_EQ(buffer.size(), bytes);
  EXPECT_EQ(buffer.mapped(), nullptr);

  sp::vk::upload(context(), buffer, values.data(), bytes);
  EXPECT_EQ(download_all(context(), buffer), values);

  // Partial copies at an offset, both ways.
  const std::vector<std::uint32_t> patch = pattern(10, 99);
  sp::vk::upload(context(), buffer, patch.data(), patch.size() * 4, 400 * 4);
  std::vector<std::uint32_t> window(12);
  sp::vk::download(context(), buffer, window.data(), window.size() * 4, 399 * 4);
  EXPECT_EQ(window.front(), values[399]);
  EXPECT_EQ(std::vector<std::uint32_t>(window.begin() + 1, window.end() - 1), patch);
  EXPECT_EQ(window.back(), values[410]);
}

TEST_F(VkTest, MappedBuffersCopyThroughTheirMapping) {
  const std::vector<std::uint32_t> values = pattern(256, 7);
  const VkDeviceSize bytes = values.size() * 4;
  for (const MemoryUsage usage : {MemoryUsage::HostVisible, MemoryUsage::Readback}) {
    Buffer buffer(context(), bytes, kStorageCopyable, usage, "mapped");
    ASSERT_NE(buffer.mapped(), nullptr);
    sp::vk::upload(context(), buffer, values.data(), bytes);
    EXPECT_EQ(std::memcmp(buffer.mapped(), values.data(), bytes), 0);
    EXPECT_EQ(download_all(context(), buffer), values);
  }
}

TEST_F(VkTest, CopiesOutsideTheBufferAreRejected) {
  Buffer buffer(context(), 64, kStorageCopyable, MemoryUsage::DeviceLocal, "small");
  std::vector<std::uint8_t> bytes(65);
  for (const auto& [size, offset] : {std::pair<VkDeviceSize, VkDeviceSize>{65, 0}, {1, 64}, {8, ~VkDeviceSize{0}}}) {
    try {
      sp::vk::upload(context(), buffer, bytes.data(), size, offset);
      ADD_FAILURE() << "upload of " << size << " bytes at " << offset << " accepted";
    } catch (const sp::Exception& e) {
      EXPECT_EQ(e.error().code, ErrorCode::InvalidArgument) << e.what();
    }
    EXPECT_THROW(sp::vk::download(context(), buffer, bytes.data(), size, offset), sp::Exception);
  }
}

TEST_F(VkTest, StorageBufferLargerThanTheDeviceAllowsIsLimitExceeded) {
  const VkDeviceSize too_big = VkDeviceSize{context().properties().limits.maxStorageBufferRange} + 4;
  const auto result = sp::capture_errors([&] {
    const Buffer buffer(context(), too_big, kStorageCopyable, MemoryUsage::DeviceLocal, "huge rays");
    return buffer.size();
  });
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.error().code, ErrorCode::LimitExceeded);
  const std::string& message = result.error().message;
  EXPECT_EQ(message.rfind("huge rays: " + std::to_string(too_big) + " bytes", 0), 0u) << message;
  EXPECT_NE(message.find("maxStorageBufferRange"), std::string::npos) << message;
}

TEST_F(VkTest, EmptyBufferIsInvalidArgument) {
  try {
    const Buffer buffer(context(), 0, kStorageCopyable, MemoryUsage::DeviceLocal, "empty");
    FAIL() << "a zero-sized buffer was created";
  } catch (const sp::Exception& e) {
    EXPECT_EQ(e.error().code, ErrorCode::InvalidArgument);
  }
}

// ---------------------------------------------------------------------------
// Compute

TEST_F(VkTest, FillKernelWritesValuePlusIndex) {
  constexpr std::uint32_t kCount = 1000;  // not a multiple of the group size
  constexpr std::uint32_t kCapacity = 1024;
  Buffer data(context(), kCapacity * 4, kStorageCopyable, MemoryUsage::DeviceLocal, "fill data");
  const std::vector<std::uint32_t> initial(kCapacity, kUntouched);
  sp::vk::upload(context(), data, initial.data(), data.size());

  FillKernel kernel(context());
  kernel.bindings.bind(context(), 0, data);
  context().submit_and_wait([&](VkCommandBuffer cmd) { kernel.dispatch(cmd, {kCount, 7}); });

  const std::vector<std::uint32_t> result = download_all(context(), data);
  for (std::uint32_t i = 0; i < kCapacity; ++i) {
    ASSERT_EQ(result[i], i < kCount ? 7 + i : kUntouched) << "index " << i;
  }
}

TEST_F(VkTest, BarrierOrdersTwoDispatchesWritingOneBuffer) {
  constexpr std::uint32_t kCount = 4096;
  Buffer data(context(), kCount * 4, kStorageCopyable, MemoryUsage::DeviceLocal, "overwritten data");
  FillKernel kernel(context());
  kernel.bindings.bind(context(), 0, data);
  context().submit_and_wait([&](VkCommandBuffer cmd) {
    kernel.dispatch(cmd, {kCount, 1});
    sp::vk::compute_to_compute(cmd);  // WAW: the second fill lands last
    kernel.dispatch(cmd, {kCount / 2, 100000});
  });
  const std::vector<std::uint32_t> result = download_all(context(), data);
  for (std::uint32_t i = 0; i < kCount; ++i) {
    ASSERT_EQ(result[i], i < kCount / 2 ? 100000 + i : 1 + i) << "index " << i;
  }
}

TEST_F(VkTest, DispatchIndirectTakesGroupCountFromBuffer) {
  constexpr std::uint32_t kCapacity = 1024;
  constexpr std::uint32_t kGroups = 3;  // covers 192 of the `count` = 1024 elements
  Buffer data(context(), kCapacity * 4, kStorageCopyable, MemoryUsage::DeviceLocal, "indirect data");
  const std::vector<std::uint32_t> initial(kCapacity, kUntouched);
  sp::vk::upload(context(), data, initial.data(), data.size());
  Buffer arguments(context(), sizeof(VkDispatchIndirectCommand),
                   VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::DeviceLocal,
                   "dispatch arguments");
  const VkDispatchIndirectCommand command{kGroups, 1, 1};
  sp::vk::upload(context(), arguments, &command, sizeof(command));

  FillKernel kernel(context());
  kernel.bindings.bind(context(), 0, data);
  context().submit_and_wait([&](VkCommandBuffer cmd) {
    kernel.bind_and_push(cmd, {kCapacity, 5});
    vkCmdDispatchIndirect(cmd, arguments.get(), 0);
  });

  const std::vector<std::uint32_t> result = download_all(context(), data);
  for (std::uint32_t i = 0; i < kCapacity; ++i) {
    ASSERT_EQ(result[i], i < kGroups * kFillGroupSize ? 5 + i : kUntouched) << "index " << i;
  }
}

TEST_F(VkTest, InvalidPipelineArgumentsAreRejected) {
  const StorageBindings bindings(context(), 2, "two bindings");
  EXPECT_NE(bindings.layout(), VK_NULL_HANDLE);
  EXPECT_NE(bindings.set(), VK_NULL_HANDLE);
  try {
    const ComputePipeline pipeline(context(), std::span<const std::uint32_t>{}, bindings.layout(), 0, "empty");
    FAIL() << "a pipeline without code was created";
  } catch (const sp::Exception& e) {
    EXPECT_EQ(e.error().code, ErrorCode::InvalidArgument);
  }
  EXPECT_THROW(StorageBindings(context(), 0, "none"), sp::Exception);
}

// ---------------------------------------------------------------------------
// RAII owners

// Host allocation callbacks that track live allocations, so a test can see a
// Vulkan object being freed (lavapipe allocates its objects through them).
class CountingAllocator {
 public:
  VkAllocationCallbacks callbacks() {
    VkAllocationCallbacks result{};
    result.pUserData = this;
    result.pfnAllocation = &CountingAllocator::allocate;
    result.pfnReallocation = &CountingAllocator::reallocate;
    result.pfnFree = &CountingAllocator::release;
    return result;
  }

  std::size_t live() {
    const std::lock_guard lock(mutex_);
    return sizes_.size();
  }

 private:
  static void* VKAPI_CALL allocate(void* self, std::size_t size, std::size_t alignment, VkSystemAllocationScope) {
    if (size == 0) return nullptr;
    const std::size_t rounded = (size + alignment - 1) / alignment * alignment;
    void* memory = std::aligned_alloc(alignment, rounded);
    if (memory != nullptr) {
      auto* allocator = static_cast<CountingAllocator*>(self);
      const std::lock_guard lock(allocator->mutex_);
      allocator->sizes_[memory] = size;
    }
    return memory;
  }

  static void* VKAPI_CALL reallocate(void* self, void* original, std::size_t size, std::size_t alignment,
                                     VkSystemAllocationScope scope) {
    if (original == nullptr) return allocate(self, size, alignment, scope);
    if (size == 0) {
      release(self, original);
      return nullptr;
    }
    void* memory = allocate(self, size, alignment, scope);
    if (memory == nullptr) return nullptr;
    auto* allocator = static_cast<CountingAllocator*>(self);
    std::size_t old_size = 0;
    {
      const std::lock_guard lock(allocator->mutex_);
      old_size = allocator->sizes_.at(original);
    }
    std::memcpy(memory, original, std::min(old_size, size));
    release(self, original);
    return memory;
  }

  static void VKAPI_CALL release(void* self, void* memory) {
    if (memory == nullptr) return;
    auto* allocator = static_cast<CountingAllocator*>(self);
    {
      const std::lock_guard lock(allocator->mutex_);
      allocator->sizes_.erase(memory);
    }
    std::free(memory);
  }

  std::mutex mutex_;
  std::unordered_map<void*, std::size_t> sizes_;
};

TEST_F(VkTest, DeviceObjectMoveAssignDestroysTheOldHandle) {
  CountingAllocator allocator;  // outlives the buffers below
  const VkAllocationCallbacks callbacks = allocator.callbacks();
  const VkDevice device = context().device();
  const auto make_buffer = [&] {
    VkBufferCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
    info.size = 256;
    info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    VkBuffer buffer = VK_NULL_HANDLE;
    SP_VK_CHECK(vkCreateBuffer(device, &info, &callbacks, &buffer));
    return sp::vk::UniqueBuffer(device, buffer, &callbacks);
  };

  const std::size_t none = allocator.live();
  sp::vk::UniqueBuffer first = make_buffer();
  const std::size_t one = allocator.live();
  if (one == none) GTEST_SKIP() << "the driver does not allocate buffers through VkAllocationCallbacks";
  sp::vk::UniqueBuffer second = make_buffer();
  const VkBuffer second_handle = second.get();
  EXPECT_EQ(allocator.live(), none + 2 * (one - none));

  first = std::move(second);  // destroys first's buffer
  EXPECT_EQ(first.get(), second_handle);
  EXPECT_FALSE(second);
  EXPECT_EQ(allocator.live(), one);

  sp::vk::UniqueBuffer third(std::move(first));  // moves, destroys nothing
  EXPECT_FALSE(first);
  EXPECT_EQ(third.get(), second_handle);
  EXPECT_EQ(allocator.live(), one);

  third.reset();
  third.reset();  // a second reset is a no-op
  EXPECT_FALSE(third);
  EXPECT_EQ(allocator.live(), none);
}

// Every object helper of vk/objects.h, and the buffers and pipelines built on
// them, on a borrowed device: each is created through the host's allocator
// and freed through it (the validation layer reports a destroy whose
// allocator differs from the create's).
TEST_F(VkTest, BorrowedObjectsAreCreatedAndFreedThroughTheHostsAllocator) {
  CountingAllocator allocator;  // outlives the borrowed context and its objects
  const VkAllocationCallbacks callbacks = allocator.callbacks();
  sp::HostVulkan host;
  host.instance = context().instance();
  host.physical_device = context().physical_device();
  host.device = context().device();
  host.queue_family = context().queue_family();
  host.allocator = &callbacks;
  const std::unique_ptr<Context> borrowed = Context::borrow(host).value();
  ASSERT_EQ(borrowed->allocator(), &callbacks);
  const Context& c = *borrowed;

  const std::size_t none = allocator.live();
  // Creates one object, checks that it lives in the host's allocations, and
  // that they are gone again once the object is. Layouts are the exception
  // on Mesa: refcounted, they may outlive their handle and so are always
  // allocated from the device's allocator, whatever pAllocator says.
  const auto served = [&](const char* what, auto make, bool driver_uses_callbacks = true) {
    {
      const auto object = make();
      if (driver_uses_callbacks) {
        EXPECT_GT(allocator.live(), none) << what << " was not created through the host's allocator";
      }
    }
    EXPECT_EQ(allocator.live(), none) << what << " was not freed through the host's allocator";
  };
  {
    const auto probe = sp::vk::create_fence(c, "probe");
    if (allocator.live() == none) GTEST_SKIP() << "the driver does not allocate objects through VkAllocationCallbacks";
  }
  served("a shader module", [&] { return sp::vk::create_shader_module(c, sp_spirv_test_fill_comp, "fill"); });
  const VkDescriptorSetLayoutBinding binding{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT,
                                             nullptr};
  served(
      "a descriptor set layout",
      [&] {
        return sp::vk::create_descriptor_set_layout(c, {&binding, 1}, "layout");
      },
      false);
  served("a descriptor pool",
         [&] { return sp::vk::create_descriptor_pool(c, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, 1, "pool"); });
  served(
      "a pipeline layout",
      [&] { return sp::vk::create_pipeline_layout(c, {}, VK_SHADER_STAGE_COMPUTE_BIT, 16, "pipeline layout"); }, false);
  served("a command pool", [&] { return sp::vk::create_command_pool(c, c.queue_family(), 0, "commands"); });
  served("a fence", [&] { return sp::vk::create_fence(c, "fence"); });
  served("a timestamp pool", [&] { return sp::vk::create_timestamp_pool(c, 4, "timestamps"); });
  served("a buffer",
         [&] { return Buffer(c, 256, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::DeviceLocal, "buffer"); });
  served("storage bindings and a compute pipeline", [&] { return std::make_unique<FillKernel>(c); });
}

// What the kernels need of subgroups, checked from the device's properties.
TEST(SubgroupSupport, NamesEachMissingStageAndOperation) {
  VkPhysicalDeviceSubgroupProperties subgroup{};
  subgroup.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES;
  subgroup.subgroupSize = 32;
  subgroup.supportedStages = VK_SHADER_STAGE_COMPUTE_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
  subgroup.supportedOperations = VK_SUBGROUP_FEATURE_BASIC_BIT | VK_SUBGROUP_FEATURE_VOTE_BIT |
                                 VK_SUBGROUP_FEATURE_BALLOT_BIT | VK_SUBGROUP_FEATURE_ARITHMETIC_BIT;
  EXPECT_EQ(sp::vk::missing_subgroup_support(subgroup), "");

  VkPhysicalDeviceSubgroupProperties fragment_only = subgroup;
  fragment_only.supportedStages = VK_SHADER_STAGE_FRAGMENT_BIT;
  EXPECT_EQ(sp::vk::missing_subgroup_support(fragment_only), " compute-stage subgroups");

  VkPhysicalDeviceSubgroupProperties basic_only = subgroup;
  basic_only.supportedOperations = VK_SUBGROUP_FEATURE_BASIC_BIT;
  EXPECT_EQ(sp::vk::missing_subgroup_support(basic_only), " ballot subgroup operations arithmetic subgroup operations");

  const VkPhysicalDeviceSubgroupProperties none{};
  const std::string missing = sp::vk::missing_subgroup_support(none);
  for (const char* part : {"compute-stage", "basic", "ballot", "arithmetic"})
    EXPECT_NE(missing.find(part), std::string::npos) << missing;
}

// The device the tests run on has them, borrowed or owned.
TEST_F(VkTest, TheTestDeviceHasTheSubgroupOperationsTheKernelsUse) {
  sp::HostVulkan host;
  host.instance = context().instance();
  host.physical_device = context().physical_device();
  host.device = context().device();
  host.queue_family = context().queue_family();
  EXPECT_TRUE(Context::borrow(host).ok());
  EXPECT_GE(context().subgroup_size(), 1u);
}

// A buffer assigned over another must free the first buffer and its memory;
// the validation layer would report either leak when the context is destroyed.
TEST_F(VkTest, BufferMoveAssignReleasesThePreviousBuffer) {
  Buffer buffer(context(), 256, kStorageCopyable, MemoryUsage::HostVisible, "first");
  buffer = Buffer(context(), 512, kStorageCopyable, MemoryUsage::HostVisible, "second");
  EXPECT_NE(buffer.get(), VK_NULL_HANDLE);
  EXPECT_EQ(buffer.size(), 512u);
  ASSERT_NE(buffer.mapped(), nullptr);
  const std::vector<std::uint32_t> values = pattern(128, 3);
  sp::vk::upload(context(), buffer, values.data(), 512);
  EXPECT_EQ(download_all(context(), buffer), values);
}

}  // namespace
