// LargeArray (src/bvh/large_array.h): the BVH build's arrays, which ask for
// transparent huge pages once they span several of them.
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <numeric>
#include <sstream>
#include <string>

#include "bvh/large_array.h"

namespace {

// The VmFlags of the mapping that holds `address`, from /proc/self/smaps;
// empty if it is not found (not Linux, or no such file).
std::string vm_flags_of(const void* address) {
  std::ifstream smaps("/proc/self/smaps");
  const auto target = reinterpret_cast<std::uintptr_t>(address);
  std::string line;
  bool inside = false;
  while (std::getline(smaps, line)) {
    std::uintptr_t lo = 0, hi = 0;
    char dash = 0;
    std::istringstream header(line);
    if (header >> std::hex >> lo >> dash >> hi && dash == '-') {
      inside = lo <= target && target < hi;
    } else if (inside && line.rfind("VmFlags:", 0) == 0) {
      return line;
    }
  }
  return {};
}

TEST(LargeArray, SmallArraysBehaveAsVectors) {
  sp::LargeArray<std::uint32_t> a;
  for (std::uint32_t i = 0; i < 1000; ++i) a.push_back(i * 3u);
  const sp::LargeArray<std::uint32_t> b = a;
  EXPECT_EQ(a, b);
  EXPECT_EQ(std::accumulate(b.begin(), b.end(), std::uint64_t{0}), 3u * (999u * 1000u / 2u));
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(a.data()) % alignof(std::uint32_t), 0u);
}

TEST(LargeArray, LargeArraysStartOnAHugePage) {
  // 16 MiB of 32-byte records, grown by push_back through every capacity
  // from small to large: the values survive each move between the two kinds.
  struct Record {
    float v[8];
  };
  sp::LargeArray<Record> records;
  const std::size_t count = (std::size_t{16} << 20) / sizeof(Record);
  for (std::size_t i = 0; i < count; ++i) records.push_back(Record{{static_cast<float>(i)}});
  for (std::size_t i = 0; i < count; i += 997) ASSERT_EQ(records[i].v[0], static_cast<float>(i));
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(records.data()) % sp::kHugePageBytes, 0u);

#if defined(__linux__)
  std::ifstream thp("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string mode;
  std::getline(thp, mode);
  if (mode.empty() || mode.find("[never]") != std::string::npos) GTEST_SKIP() << "no transparent huge pages here";
  // "hg": the kernel was told MADV_HUGEPAGE for this range.
  const std::string flags = vm_flags_of(records.data());
  ASSERT_FALSE(flags.empty()) << "no mapping found for the array in /proc/self/smaps";
  EXPECT_NE(flags.find(" hg"), std::string::npos) << flags;
#endif
}

}  // namespace
