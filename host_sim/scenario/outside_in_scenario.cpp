#include "host_sim/scenario/outside_in_scenario.hpp"

#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "host_sim/render/outside_in_scene.hpp"
#include "host_sim/scenario/scenario_fields.hpp"

namespace irloc::sim {
namespace {

using io::Range;
using io::YamlMap;

constexpr double kPi = std::numbers::pi;

constexpr double kWallCameraFrameRate = 10;   // outside-in: a webcam's default, frames per second
constexpr std::size_t kMostWallCameras = 8;  // outside-in: each is a rendered dataset and an irlocd run

// The four tile corners of a wall camera's floor reference (`key` of `map`).
std::array<Eigen::Vector2d, 4> read_floor_reference(YamlMap& map, const std::string& key) {
  const std::vector<Eigen::Vector2d> corners = read_points2(map, key);
  if (corners.size() != 4) map.fail_key(key, "expected 4 tile corners [x, y], in order round a rectangle");
  std::array<Eigen::Vector2d, 4> reference;
  for (std::size_t i = 0; i < 4; ++i) {
    for (const double c : {corners[i].x(), corners[i].y()}) {
      if (std::abs(c / kFloorTile - std::round(c / kFloorTile)) > 1e-9) {
        map.fail_key(key, "corner " + std::to_string(i) + " is not a tile corner (multiples of 0.5 m)");
      }
    }
    reference[i] = corners[i];
  }
  return reference;
}

// One wall camera (`camera:`, or an item of `cameras:`) but its floor reference; `frame_rate` is
// the fallback in, the camera's out. The camera is a distortion-free pinhole (the ray caster draws
// no distortion).
WallCameraSpec read_wall_camera(YamlMap& camera, const std::filesystem::path& base_dir, double& frame_rate) {
  WallCameraSpec spec;
  spec.intrinsics = read_camera_calibration(camera, base_dir, spec.calibration_file);
  for (const double k : spec.intrinsics.distortion) {
    if (k != 0) camera.fail_key("calibration", "the outside-in renderer draws a pinhole: distortion must be zero");
  }
  frame_rate = camera.number("frame_rate", {1, 1000}, frame_rate);
  spec.line_time_ns = read_rolling_shutter(camera, spec.intrinsics.height, frame_rate);
  YamlMap wall = camera.map("wall");
  spec.wall_position = wall.vector2("position", kWorldCoordinate);
  spec.wall_height = wall.number("height", {0.3, 20});
  spec.pitch_deg = wall.number("pitch_deg", {1, 89});
  spec.yaw_deg = wall.number("yaw_deg", {-360, 360}, 0);
  wall.reject_unknown_keys();
  spec.auto_exposure = camera.boolean("auto_exposure", spec.auto_exposure);
  spec.noise_sigma = camera.number("noise_sigma", {0, 50}, spec.noise_sigma);
  return spec;
}

// One item of `cameras:`; every camera has the first one's frame rate and an ID of its own.
void add_listed_camera(YamlMap& item, const std::filesystem::path& base_dir, Scenario& scenario, OutsideInSpec& spec) {
  double frame_rate = spec.cameras.empty() ? kWallCameraFrameRate : scenario.camera.frame_rate;
  WallCameraSpec camera = read_wall_camera(item, base_dir, frame_rate);
  camera.floor_reference = read_floor_reference(item, "floor_reference");
  camera.component_id = static_cast<int>(item.integer("component_id", 1, 255, 201 + static_cast<long long>(spec.cameras.size())));
  if (spec.cameras.empty()) {
    scenario.camera.frame_rate = frame_rate;
  } else if (frame_rate != scenario.camera.frame_rate) {
    item.fail_key("frame_rate", "every camera must have the first one's frame rate (they see the same instants)");
  }
  for (const WallCameraSpec& other : spec.cameras) {
    if (other.component_id == camera.component_id) {
      item.fail_key("component_id", std::to_string(camera.component_id) + " is another camera's: each irlocd needs its own");
    }
  }
  spec.cameras.push_back(camera);
}

// The wall cameras: `camera:` and the top-level `floor_reference:` (one camera), or `cameras:`,
// each with its own floor reference and MAVLink component ID (several); the frame rate is theirs.
void read_cameras(YamlMap& root, const std::filesystem::path& base_dir, Scenario& scenario, OutsideInSpec& spec) {
  if (root.has("camera") == root.has("cameras")) {
    root.fail("give exactly one of 'camera' (one wall camera, with a top-level 'floor_reference') and 'cameras' (a list)");
  }
  if (root.has("camera")) {
    YamlMap camera = root.map("camera");
    scenario.camera.frame_rate = kWallCameraFrameRate;
    spec.cameras.push_back(read_wall_camera(camera, base_dir, scenario.camera.frame_rate));
    camera.reject_unknown_keys();
    spec.cameras.back().floor_reference = read_floor_reference(root, "floor_reference");
  } else {
    if (root.has("floor_reference")) root.fail_key("floor_reference", "with 'cameras', each camera has its own floor_reference");
    root.for_each_item("cameras", [&](YamlMap& item) { add_listed_camera(item, base_dir, scenario, spec); });
    if (spec.cameras.empty()) root.fail_key("cameras", "expected at least one camera");
    if (spec.cameras.size() > kMostWallCameras) {
      root.fail_key("cameras", "at most " + std::to_string(kMostWallCameras) + " cameras");
    }
  }
}

// robot.look: each face's shade (grey levels, the dark robot's where absent) and an optional
// strip across the front face between two fractions of the box's height.
RobotLook read_robot_look(YamlMap& look) {
  constexpr Range kShade{0, 255};
  RobotLook read;
  read.top = look.number("top", kShade, read.top);
  read.front = look.number("front", kShade, read.front);
  read.back = look.number("back", kShade, read.back);
  read.sides = look.number("sides", kShade, read.sides);
  if (std::optional<YamlMap> strip = look.optional_map("front_strip")) {
    read.strip_shade = strip->number("shade", kShade);
    read.strip_from = strip->number("from", {0, 1});
    read.strip_to = strip->number("to", {0, 1});
    if (read.strip_to <= read.strip_from) strip->fail_key("to", "must be above 'from' (fractions of the body's height)");
    strip->reject_unknown_keys();
  }
  look.reject_unknown_keys();
  return read;
}

// The robot's box and look, the lamp's steps and the sun patch drifting over the floor.
void read_robot_and_light(YamlMap& root, const Scenario& scenario, OutsideInSpec& spec) {
  YamlMap robot = root.map("robot");
  YamlMap body = robot.map("body");
  spec.body_length = body.number("length", {0.05, 10});
  spec.body_width = body.number("width", {0.05, 10});
  spec.body_height = body.number("height", {0.02, 5});
  body.reject_unknown_keys();
  if (std::optional<YamlMap> look = robot.optional_map("look")) spec.look = read_robot_look(*look);
  robot.reject_unknown_keys();

  root.for_each_item("light_steps", [&](YamlMap& item) {
    LightStep step;
    step.frame = static_cast<int>(item.integer("frame", 0, scenario.frames - 1));
    step.lamp = item.number("lamp", {0.05, 20});
    if (!spec.light_steps.empty() && step.frame <= spec.light_steps.back().frame) item.fail_key("frame", "light steps must be in frame order");
    spec.light_steps.push_back(step);
  });
  if (std::optional<YamlMap> sun = root.optional_map("sun")) {
    spec.sun_from = sun->vector2("from", kWorldCoordinate);
    spec.sun_to = sun->has("to") ? sun->vector2("to", kWorldCoordinate) : spec.sun_from;
    spec.sun_strength = sun->number("strength", {0, 10}, spec.sun_strength);
    sun->reject_unknown_keys();
  }
}

}  // namespace

void read_outside_in_scenario(YamlMap& root, const std::filesystem::path& base_dir, Scenario& scenario) {
  OutsideInSpec spec;
  read_cameras(root, base_dir, scenario, spec);
  scenario.camera.intrinsics = spec.cameras.front().intrinsics;
  read_robot_and_light(root, scenario, spec);
  scenario.outside_in = spec;
  YamlMap trajectory = root.map("trajectory");
  scenario.trajectory = read_trajectory(trajectory);
  trajectory.reject_unknown_keys();
  scenario.people = read_people(root);
  if (scenario.people.size() > 1) root.fail_key("people", "the outside-in renderer draws at most one person");
  if (std::optional<YamlMap> metrics = root.optional_map("metrics")) {
    scenario.metrics.gross_position = metrics->number("gross_position", {1e-6, 1e4}, 0.15);
    scenario.metrics.gross_yaw = metrics->number("gross_yaw", {1e-6, kPi}, kPi / 2);
    scenario.metrics.warm_up_frames = static_cast<int>(metrics->integer("warm_up_frames", 0, scenario.frames - 1, 0));
    metrics->reject_unknown_keys();
  } else {
    scenario.metrics.gross_position = 0.15;
    scenario.metrics.gross_yaw = kPi / 2;
  }
  root.reject_unknown_keys();
}

}  // namespace irloc::sim
