// The map writer against the map reader: what is written reads back as the same map (the
// survey's `fixed` and `sigma` included), the file is replaced whole, and failures name the file.

#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/config/map_file.hpp"
#include "io/files/map_file_writer.hpp"
#include "tests/support/input_error_message.hpp"
#include "tests/support/temp_dir.hpp"

namespace irloc::io {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

MarkerMap example_map() {
  MarkerMap map;
  DotMarker reference;
  reference.id = 1782;
  reference.origin = {0.1, 0.2, 2.6};
  reference.yaw = 0.1;
  reference.fixed = true;
  DotMarker surveyed;
  surveyed.id = 7;
  surveyed.origin = {1.8000001234567, -0.0031, 2.6012};
  surveyed.yaw = -3.0999999;
  surveyed.pitch = 0.05;
  surveyed.radius = 0.012;
  surveyed.sigma = Eigen::Vector4d(0.0011, 0.0009, 0.0021, 0.00033);
  map.dot_markers = {reference, surveyed};
  SquareMarker square;
  square.name = "hall: east";  // needs quoting
  square.corners = {Eigen::Vector3d(0, 0, 2.5), Eigen::Vector3d(2, 0, 2.5), Eigen::Vector3d(2, 2, 2.5),
                    Eigen::Vector3d(0, 2, 2.5)};
  map.square_markers = {square};
  LedLandmark led;
  led.name = "L1";
  led.position = {0, 5, 1.5};
  led.direction = Eigen::Vector3d(0, -1, 0);
  led.half_angle = 0.5;
  map.led_landmarks = {led, LedLandmark{"L2", {1, 1, 1}, std::nullopt, std::nullopt}};
  return map;
}

TEST(MapFileWriter, WhatIsWrittenReadsBackExactly) {
  const test::TempDir folder;
  const MarkerMap map = example_map();
  write_marker_map(folder / "map.yaml", map);
  const MarkerMap read = load_marker_map(folder / "map.yaml");

  ASSERT_EQ(read.dot_markers.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(read.dot_markers[i].id, map.dot_markers[i].id);
    EXPECT_EQ(read.dot_markers[i].origin, map.dot_markers[i].origin);
    EXPECT_EQ(read.dot_markers[i].yaw, map.dot_markers[i].yaw);
    EXPECT_EQ(read.dot_markers[i].pitch, map.dot_markers[i].pitch);
    EXPECT_EQ(read.dot_markers[i].radius, map.dot_markers[i].radius);
    EXPECT_EQ(read.dot_markers[i].fixed, map.dot_markers[i].fixed);
    EXPECT_EQ(read.dot_markers[i].sigma, map.dot_markers[i].sigma);
  }
  ASSERT_EQ(read.square_markers.size(), 1u);
  EXPECT_EQ(read.square_markers[0].name, "hall: east");
  EXPECT_EQ(read.square_markers[0].corners, map.square_markers[0].corners);
  ASSERT_EQ(read.led_landmarks.size(), 2u);
  EXPECT_EQ(read.led_landmarks[0].direction, map.led_landmarks[0].direction);
  EXPECT_EQ(read.led_landmarks[0].half_angle, map.led_landmarks[0].half_angle);
  EXPECT_FALSE(read.led_landmarks[1].direction.has_value());
}

TEST(MapFileWriter, ReplacesTheOldFileAndLeavesNoTemporaryBehind) {
  const test::TempDir folder;
  {
    std::ofstream old(folder / "map.yaml");
    old << "old: map\n";
  }
  write_marker_map(folder / "map.yaml", example_map());
  EXPECT_EQ(load_marker_map(folder / "map.yaml").dot_markers.size(), 2u);
  int files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(folder.path())) ++files;
  EXPECT_EQ(files, 1);
}

TEST(MapFileWriter, AFolderThatDoesNotExistIsAnErrorNamingTheFile) {
  const test::TempDir folder;
  const std::filesystem::path path = folder / "missing" / "map.yaml";
  EXPECT_THAT(test::input_error_message([&] { write_marker_map(path, example_map()); }),
              StartsWith(path.string() + ": cannot write the map"));
}

TEST(MapFile, FixedAndSigmaAreChecked) {
  const test::TempDir folder;
  const auto error_of = [&](const std::string& marker_keys) {
    std::ofstream(folder / "map.yaml") << "dot_markers:\n  - id: 3\n    origin: [0, 0, 2.6]\n    yaw: 0\n" << marker_keys;
    return test::input_error_message([&] { load_marker_map(folder / "map.yaml"); });
  };
  EXPECT_THAT(error_of("    fixed: yes\n"), HasSubstr("dot_markers[0].fixed: expected true or false, got 'yes'"));
  EXPECT_THAT(error_of("    sigma: [0.1, 0.1, 0.1]\n"), HasSubstr("dot_markers[0].sigma"));
  EXPECT_THAT(error_of("    sigma: [0.1, 0.1, -0.1, 0.1]\n"), HasSubstr("dot_markers[0].sigma: must be in [0, 1000], got -0.1"));
}

}  // namespace
}  // namespace irloc::io
