// Configs come from players (README "Security"): nesting is bounded before
// anything recurses over it, values in messages are printed without
// recursion past a few dozen characters, and a config file must be a
// regular file of sane size, checked before a byte is read.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "soundpaint/config.h"

namespace {

std::string nested_arrays(std::size_t levels) { return std::string(levels, '[') + std::string(levels, ']'); }

// 70,000 levels used to crash the error path, which printed the value with
// a recursive dump.
TEST(ConfigLimits, RefusesDeepNestingBeforeUsingIt) {
  for (const std::size_t levels : {std::size_t{129}, std::size_t{70000}}) {
    SCOPED_TRACE(levels);
    const auto result = sp::parse_config("{\"listener\": " + nested_arrays(levels - 1) + "}", "deep.json");
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error().code, sp::ErrorCode::InvalidConfig);
    EXPECT_EQ(result.error().message.rfind("deep.json: JSON nested deeper than 128 levels at \"listener", 0), 0u)
        << result.error().message;
    EXPECT_LT(result.error().message.size(), 120u) << result.error().message;
  }
}

// At the limit the config parses and the type error prints its value cut
// short, however deep or long that value is.
TEST(ConfigLimits, PrintsValuesShortWithoutRecursion) {
  const auto deep = sp::parse_config("{\"listener\": " + nested_arrays(127) + "}", "deep.json");
  ASSERT_FALSE(deep.ok());
  EXPECT_EQ(deep.error().message,
            "deep.json: key \"listener\": must be an object, got [[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[...");
  std::string long_array = "[";
  for (int i = 0; i < 200000; ++i) long_array += (i ? ",1" : "1");
  long_array += "]";
  const auto wide = sp::parse_config("{\"seed\": " + long_array + "}", "wide.json");
  ASSERT_FALSE(wide.ok());
  // 40 characters at most: the first 37 of the value, then "...".
  std::string first_37 = "[";
  for (int i = 0; i < 18; ++i) first_37 += "1,";
  EXPECT_EQ(wide.error().message,
            "wide.json: key \"seed\": must be an integer in [0, 4294967295], got " + first_37 + "...");
  const auto text = sp::parse_config("{\"dt\": \"" + std::string(100000, 'x') + "\"}", "text.json");
  ASSERT_FALSE(text.ok());
  EXPECT_LT(text.error().message.size(), 120u);
  const auto object = sp::parse_config(R"({"listener": {"position": {"a": [1, {"b": 2}]}}})", "o.json");
  ASSERT_FALSE(object.ok());
  EXPECT_EQ(object.error().message,
            "o.json: key \"listener.position\": must be an array of 3 numbers, got {\"a\":[1,{\"b\":2}]}");
}

TEST(ConfigLimits, ReadsOnlyRegularFiles) {
  for (const char* device : {"/dev/zero", "/dev/null"}) {
    const auto result = sp::load_config(device);
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error().code, sp::ErrorCode::Io);
    EXPECT_EQ(result.error().message,
              std::string(device) + ": cannot read config file: is not a regular file (a device, FIFO or socket)");
  }
  const std::filesystem::path fifo =
      std::filesystem::temp_directory_path() / ("soundpaint-test_config_limits-" + std::to_string(::getpid()));
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const auto result = sp::load_config(fifo);  // would wait for a writer if opened
  std::filesystem::remove(fifo);
  ASSERT_FALSE(result.ok());
  EXPECT_NE(result.error().message.find("not a regular file"), std::string::npos);
}

}  // namespace
