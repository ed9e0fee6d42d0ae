#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/config/dot_config_file.hpp"
#include "io/input_error.hpp"
#include "tests/support/temp_dir.hpp"

namespace irloc::io {
namespace {

using ::testing::HasSubstr;

dot::DotSourceConfig read(const std::string& text, const std::filesystem::path& dir) {
  const std::filesystem::path file = dir / "dot.yaml";
  std::ofstream(file) << text;
  YamlMap root(load_yaml_file(file), file.string(), "");
  YamlMap section = root.map("dot");
  dot::DotSourceConfig config;
  read_dot_config(section, config);
  root.reject_unknown_keys();
  return config;
}

TEST(DotConfigFile, EveryKeyIsOptional) {
  test::TempDir dir;
  const dot::DotSourceConfig config = read("dot: {}\n", dir.path());
  const dot::DotSourceConfig defaults;
  EXPECT_EQ(config.threshold, defaults.threshold);
  EXPECT_EQ(config.confidence_floor, defaults.confidence_floor);
  EXPECT_EQ(config.grey_levels.dot.mean, defaults.grey_levels.dot.mean);
}

TEST(DotConfigFile, ReadsValues) {
  test::TempDir dir;
  const dot::DotSourceConfig config = read(R"(dot:
  threshold: 40
  pixel_bits: 12
  ceiling_distance: 2.3
  confidence_floor: 0.7
  grey_levels:
    dot: {weight: 0.8, mean: 140, sigma: 25}
    clutter: {weight: 0.2, mean: 20, sigma: 9}
)",
                                         dir.path());
  EXPECT_EQ(config.threshold, 40u);
  EXPECT_EQ(config.pixel_bits, 12);
  EXPECT_DOUBLE_EQ(config.ceiling_distance, 2.3);
  EXPECT_DOUBLE_EQ(config.confidence_floor, 0.7);
  EXPECT_DOUBLE_EQ(config.grey_levels.dot.mean, 140);
  EXPECT_DOUBLE_EQ(config.grey_levels.clutter.sigma, 9);
}

TEST(DotConfigFile, UnknownKeysAndBadValuesNameTheField) {
  test::TempDir dir;
  try {
    read("dot:\n  treshold: 40\n", dir.path());
    FAIL() << "a typo was accepted";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("dot.yaml:2"));
    EXPECT_THAT(e.what(), HasSubstr("dot.treshold"));
    EXPECT_THAT(e.what(), HasSubstr("unknown key"));
  }
  try {
    read("dot:\n  confidence_floor: 1.5\n", dir.path());
    FAIL() << "an out-of-range floor was accepted";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("dot.confidence_floor"));
  }
  EXPECT_THROW(read("dot:\n  grey_levels: {dot: {mean: 100, colour: 3}}\n", dir.path()), InputError);
}

}  // namespace
}  // namespace irloc::io
