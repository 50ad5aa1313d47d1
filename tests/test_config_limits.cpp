// Configs come from players (README "Security"): nesting is bounded before
// anything recurses over it, values in messages are printed without
// recursion past a few dozen characters, and a config file must be a
// regular file of sane size, checked before a byte is read; the display's
// category lists are bounded in length and in their names' length.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

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

// "c<i>", built by appending: GCC 12's -Wrestrict misfires on "c" + std::to_string(i).
std::string numbered_name(std::size_t i) {
  std::string name = "c";
  name += std::to_string(i);
  return name;
}

// `count` distinct category names, "c0", "c1", ..., each padded with 'x'
// to at least `min_bytes` bytes.
std::vector<std::string> category_names(std::size_t count, std::size_t min_bytes = 0) {
  std::vector<std::string> names;
  for (std::size_t i = 0; i < count; ++i) {
    std::string name = numbered_name(i);
    if (name.size() < min_bytes) name.resize(min_bytes, 'x');
    names.push_back(std::move(name));
  }
  return names;
}

std::string hide_config(const std::vector<std::string>& names) {
  return nlohmann::json{{"display", {{"hide_categories", names}}}}.dump();
}

std::string shapes_config(const std::vector<std::string>& names) {
  nlohmann::json shapes = nlohmann::json::object();
  for (const std::string& name : names) shapes[name] = "star";
  return nlohmann::json{{"display", {{"shapes", shapes}}}}.dump();
}

// Issue 38: 1e6 hide_categories over 10,000 sources took 35 s to draw.
// The display's lists are bounded (include/soundpaint/display.h), and the
// error names the list before a name in it is read.
TEST(ConfigLimits, DisplayListsHoldAtMostTheirLimit) {
  ASSERT_EQ(sp::kMaxDisplayCategories, 4096u);
  const auto at_limit = sp::parse_config(hide_config(category_names(4096)), "d.json");
  ASSERT_TRUE(at_limit.ok()) << at_limit.error().message;
  EXPECT_EQ(at_limit->display.hide_categories.size(), 4096u);
  for (const std::size_t count : {std::size_t{4097}, std::size_t{100000}}) {
    const auto over = sp::parse_config(hide_config(category_names(count)), "d.json");
    ASSERT_FALSE(over.ok());
    EXPECT_EQ(over.error().code, sp::ErrorCode::InvalidConfig);
    EXPECT_EQ(over.error().message,
              "d.json: key \"display.hide_categories\": must hold at most 4096 category names, has " +
                  std::to_string(count));
  }

  const auto shapes = sp::parse_config(shapes_config(category_names(4096)), "d.json");
  ASSERT_TRUE(shapes.ok()) << shapes.error().message;
  EXPECT_EQ(shapes->display.shapes.size(), 4096u);
  const auto too_many_shapes = sp::parse_config(shapes_config(category_names(4097)), "d.json");
  ASSERT_FALSE(too_many_shapes.ok());
  EXPECT_EQ(too_many_shapes.error().message,
            "d.json: key \"display.shapes\": must hold at most 4096 categories, has 4097");
}

TEST(ConfigLimits, DisplayCategoryNamesHaveAtMost256Bytes) {
  ASSERT_EQ(sp::kMaxCategoryNameBytes, 256u);
  const std::vector<std::string> longest = category_names(2, 256);
  const auto hide = sp::parse_config(hide_config(longest), "d.json");
  ASSERT_TRUE(hide.ok()) << hide.error().message;
  EXPECT_EQ(hide->display.hide_categories, longest);
  const auto shapes = sp::parse_config(shapes_config(longest), "d.json");
  ASSERT_TRUE(shapes.ok()) << shapes.error().message;
  EXPECT_EQ(shapes->display.shapes.size(), 2u);

  // The name too long is not printed: the message stays one short line.
  const std::vector<std::string> too_long = {"footsteps", std::string(257, 'x')};
  const auto long_hide = sp::parse_config(hide_config(too_long), "d.json");
  ASSERT_FALSE(long_hide.ok());
  EXPECT_EQ(long_hide.error().message,
            "d.json: key \"display.hide_categories[1]\": must be at most 256 bytes long, is 257");
  const auto long_shape = sp::parse_config(shapes_config({std::string(100000, 'y')}), "d.json");
  ASSERT_FALSE(long_shape.ok());
  EXPECT_EQ(long_shape.error().message,
            "d.json: key \"display.shapes\": category names must be at most 256 bytes long, one is 100000");
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
