// Scenario files: the embedded default parses, and bad input names the file, line and field.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "io/input_error.hpp"
#include "host_sim/scenario/default_scenario.hpp"
#include "host_sim/scenario/scenario.hpp"
#include "tests/support/scenario_text.hpp"

namespace irloc::sim {
namespace {

std::string error_of(const std::string& yaml) {
  try {
    parse_scenario(yaml, "test.yaml");
  } catch (const io::InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(Scenario, DefaultScenarioParses) {
  const Scenario scenario = parse_scenario(std::string(default_scenario_yaml()), "default");
  EXPECT_EQ(scenario.frames, 200);
  EXPECT_EQ(scenario.camera.intrinsics.width, 640);
  EXPECT_EQ(scenario.trajectory.kind, TrajectoryKind::loop);
  EXPECT_EQ(scenario.ring.leds.size(), 12u);
  EXPECT_EQ(scenario.map.dot_markers.size(), 3u);
  EXPECT_EQ(scenario.map.square_markers.size(), 1u);
  EXPECT_EQ(scenario.dropped_frames, std::vector<std::uint64_t>{57});
}

// The value ranges admit every scenario the project ships.
TEST(Scenario, ShippedScenariosParse) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(IRLOC_SCENARIOS_DIR)) {
    if (entry.path().extension() != ".yaml") continue;
    EXPECT_NO_THROW(load_scenario(entry.path())) << entry.path();
    ++count;
  }
  EXPECT_GE(count, 10);
}

TEST(Scenario, RingLedsAreTiltedOutward) {
  const Scenario scenario = parse_scenario(test::ScenarioText{}.yaml(), "test.yaml");
  ASSERT_EQ(scenario.ring.leds.size(), 8u);
  for (const RingLed& led : scenario.ring.leds) {
    EXPECT_NEAR(led.position.head<2>().norm(), 0.02, 1e-12);
    EXPECT_NEAR(std::acos(led.axis.z()), 0.2, 1e-12);
    // The axis leans away from the optical axis, toward the LED's own side.
    EXPECT_GT(led.axis.head<2>().dot(led.position.head<2>()), 0);
  }
}

TEST(Scenario, UnknownKeyNamesFileLineAndField) {
  test::ScenarioText text;
  text.room += "  ceilng_reflectance: 0.5\n";
  const std::string error = error_of(text.yaml());
  EXPECT_NE(error.find("test.yaml:"), std::string::npos) << error;
  EXPECT_NE(error.find("room.ceilng_reflectance: unknown key"), std::string::npos) << error;
  // The line of the typo: count it in the text.
  const std::string yaml = text.yaml();
  const auto line = 1 + std::count(yaml.begin(), yaml.begin() + static_cast<long>(yaml.find("ceilng")), '\n');
  EXPECT_NE(error.find("test.yaml:" + std::to_string(line) + ":"), std::string::npos) << error;
}

TEST(Scenario, UnknownTopLevelKeyIsAnError) {
  EXPECT_NE(error_of(test::ScenarioText{}.yaml() + "nosie: 3\n").find("nosie: unknown key"), std::string::npos);
}

TEST(Scenario, BadValuesAreErrors) {
  test::ScenarioText text;
  text.trajectory = "  type: figure_eight\n";
  EXPECT_NE(error_of(text.yaml()).find("trajectory.type: unknown trajectory 'figure_eight'"), std::string::npos);

  text = {};
  text.ring = "  types:\n    - {name: wide, intensity: 0.2, half_angle: 0.6}\n  leds:\n    - {type: narrow, position: [0, 0, 0]}\n";
  EXPECT_NE(error_of(text.yaml()).find("led_ring.leds[0].type: no LED type named 'narrow'"), std::string::npos);

  text = {};
  text.map = "  dot_markers:\n    - {id: 7, origin: [0, 0, 2.0], yaw: 0}\n";
  EXPECT_NE(error_of(text.yaml()).find("dot marker 7 is not on the ceiling"), std::string::npos);

  text = {};
  text.extra = "render:\n  supersampling: 2.5\n";
  EXPECT_NE(error_of(text.yaml()).find("render.supersampling: expected an integer"), std::string::npos) << error_of(text.yaml());

  text = {};
  text.extra = "camera_extra: 1\n";
  EXPECT_NE(error_of(text.yaml()).find("camera_extra: unknown key"), std::string::npos);

  EXPECT_NE(error_of("frames: [\n").find("test.yaml:"), std::string::npos);
  EXPECT_NE(error_of("seed: 1\n").find("frames: required but missing"), std::string::npos);
}

TEST(Scenario, MapErrorsComeFromTheMapReader) {
  test::ScenarioText text;
  text.map = "  dot_markers:\n    - {id: 5000, origin: [0, 0, 1.3], yaw: 0}\n";
  EXPECT_NE(error_of(text.yaml()).find("map.dot_markers[0].id: must be in [0, 4095], got 5000"), std::string::npos) << error_of(text.yaml());
}

// A dropped frame the scenario does not render was silently cast (1e20 -> frame 0): now refused.
TEST(Scenario, DroppedFramesOutsideTheScenarioAreErrors) {
  test::ScenarioText text;
  text.frames = 10;
  text.extra = "dropped_frames:\n  seqs: [3, 10]\n";
  EXPECT_EQ(error_of(text.yaml()), "test.yaml:28: dropped_frames.seqs: must be in [0, 9], got 10");
  text.extra = "dropped_frames:\n  seqs: [1e20]\n";
  EXPECT_EQ(error_of(text.yaml()), "test.yaml:28: dropped_frames.seqs: expected an integer, got '1e20'");
  text.extra = "dropped_frames:\n  seqs: [-1]\n";
  EXPECT_EQ(error_of(text.yaml()), "test.yaml:28: dropped_frames.seqs: must be in [0, 9], got -1");
  text.extra = "dropped_frames:\n  seqs: [0, 9]\n";
  const Scenario scenario = parse_scenario(text.yaml(), "test.yaml");
  EXPECT_EQ(scenario.dropped_frames, (std::vector<std::uint64_t>{0, 9}));
}

TEST(Scenario, DuplicateKeysAndAbsurdNumbersAreErrors) {
  test::ScenarioText text;
  text.extra = "frames: 5\n";
  EXPECT_EQ(error_of(text.yaml()), "test.yaml:27: frames: duplicate key (first given on line 2)");
  text = {};
  text.room = "  ceiling_height: 1e308\n";
  EXPECT_EQ(error_of(text.yaml()), "test.yaml:21: room.ceiling_height: must be in [0.1, 100], got 1e+308");
  text = {};
  text.trajectory = "  type: loop\n  centre: [0, 0]\n  speed: 1e308\n";
  EXPECT_EQ(error_of(text.yaml()), "test.yaml:15: trajectory.speed: must be in [0.001, 100], got 1e+308");
}

// Retro-reflective clutter on the ceiling (room.clutter): strips and crescents.
TEST(Scenario, CeilingClutterIsRead) {
  test::ScenarioText text;
  text.room += "  clutter:\n"
               "    - {kind: strip, centre: [0.5, -1.2], length: 1.8, width: 0.05, yaw: 0.1}\n"
               "    - {kind: crescent, centre: [-0.3, 1.15], radius: 0.1, facing: -1.5}\n";
  const Scenario scenario = parse_scenario(text.yaml(), "test.yaml");
  ASSERT_EQ(scenario.room.clutter.size(), 2u);
  const CeilingClutter& strip = scenario.room.clutter[0];
  EXPECT_EQ(strip.kind, CeilingClutter::Kind::strip);
  EXPECT_EQ(strip.centre, Eigen::Vector2d(0.5, -1.2));
  EXPECT_EQ(strip.length, 1.8);
  EXPECT_EQ(strip.width, 0.05);
  EXPECT_EQ(strip.yaw, 0.1);
  const CeilingClutter& crescent = scenario.room.clutter[1];
  EXPECT_EQ(crescent.kind, CeilingClutter::Kind::crescent);
  EXPECT_EQ(crescent.centre, Eigen::Vector2d(-0.3, 1.15));
  EXPECT_EQ(crescent.radius, 0.1);
  EXPECT_EQ(crescent.yaw, -1.5);
}

TEST(Scenario, BadClutterIsRefusedNamingTheFileLineAndField) {
  // The clutter item is on line 25 of the test text (the room's fifth line).
  const auto error_with = [](const std::string& item) {
    test::ScenarioText text;
    text.room += "  clutter:\n    - " + item + "\n";
    return error_of(text.yaml());
  };
  EXPECT_EQ(error_with("{kind: strip, centre: [0, 0], length: 0, width: 0.05, yaw: 0}"),
            "test.yaml:25: room.clutter[0].length: must be in [0.005, 20], got 0");
  EXPECT_EQ(error_with("{kind: strip, centre: [0, 0], length: 1, width: -0.05, yaw: 0}"),
            "test.yaml:25: room.clutter[0].width: must be in [0.002, 1], got -0.05");
  EXPECT_EQ(error_with("{kind: strip, centre: [0, 0], length: 1e6, width: 0.05, yaw: 0}"),
            "test.yaml:25: room.clutter[0].length: must be in [0.005, 20], got 1000000");
  EXPECT_EQ(error_with("{kind: crescent, centre: [0, 0], radius: 0, facing: 0}"),
            "test.yaml:25: room.clutter[0].radius: must be in [0.002, 1], got 0");
  EXPECT_EQ(error_with("{kind: crescent, centre: [0, 0], radius: 50, facing: 0}"),
            "test.yaml:25: room.clutter[0].radius: must be in [0.002, 1], got 50");
  EXPECT_EQ(error_with("{kind: blob, radius: 0.1}"),
            "test.yaml:25: room.clutter[0].kind: unknown clutter kind 'blob' (expected strip or crescent)");
  EXPECT_EQ(error_with("{kind: strip, centre: [0, 0], length: 1, width: 0.05}"),
            "test.yaml:25: room.clutter[0].yaw: required but missing");
  EXPECT_EQ(error_with("{centre: [0, 0], radius: 0.1, facing: 0}"), "test.yaml:25: room.clutter[0].kind: required but missing");
  // Repeated keys are caught by the YAML loader, before the reader knows the field's path.
  EXPECT_EQ(error_with("{kind: crescent, centre: [0, 0], radius: 0.1, facing: 0, radius: 0.2}"),
            "test.yaml:25: radius: duplicate key (first given on line 25)");
  // A strip's key on a crescent is not silently ignored.
  EXPECT_EQ(error_with("{kind: crescent, centre: [0, 0], radius: 0.1, facing: 0, width: 0.05}"),
            "test.yaml:25: room.clutter[0].width: unknown key");
}

}  // namespace
}  // namespace irloc::sim
