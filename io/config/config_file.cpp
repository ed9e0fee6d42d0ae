#include "io/config/config_file.hpp"

#include <optional>
#include <span>

#include "io/config/calibration_file.hpp"
#include "io/config/dot_config_file.hpp"
#include "io/config/led_config_file.hpp"
#include "io/config/mount_watch_config_file.hpp"
#include "io/config/outside_in_config_file.hpp"
#include "io/config/map_file.hpp"
#include "io/config/square_config_file.hpp"
#include "io/config/yaml_reader.hpp"

namespace irloc::io {
namespace {

// Camera axes in base coordinates for the `up` preset: optical axis along base +z, image top
// toward the robot's front.
const Eigen::Matrix3d kRotationUp = (Eigen::Matrix3d() << 0, -1, 0, 1, 0, 0, 0, 0, 1).finished();

// Ranges of docs/formats.md: a camera within 10 m of the base origin, angles within a turn.
constexpr Range kMountOffset{-10, 10};
constexpr Range kMountAngle{-7, 7};
// A row read out in at most 1 ms: a thousand rows a second, slower than any sensor irloc can use.
constexpr long long kMaxLineTimeNs = 1'000'000;

// The fastest robot: what a rolling-shutter pose without a track allows for in its covariance, and
// how far from the last pose a track's motion reaches (algo/source/rolling_shutter.hpp).
const Setting<MotionLimits> kRobotMotionSettings[] = {
    {"max_speed", &MotionLimits::speed, 0.01, 100, "m/s", "fastest drive, for the rolling shutter (docs/rolling_shutter.md)"},
    {"max_yaw_rate", &MotionLimits::yaw_rate, 0.01, 100, "rad/s", "fastest turn (90 deg/s), for the same"},
};

// robot.max_side_speed (optional, at most max_speed): the base origin's fastest sideways drive.
constexpr Range kRobotSideSpeed{0.01, 100};

// `dot:` still takes the keys that moved to `camera:` and `front_end:` under their old names, but
// not a key given in both places.
void reject_moved_keys_given_twice(const YamlMap& dot, std::span<const Setting<dot::DotSourceConfig>> moved,
                                   const YamlMap& new_place) {
  for (const Setting<dot::DotSourceConfig>& setting : moved) {
    if (dot.has(setting.key) && new_place.has(setting.key)) {
      dot.fail_key(setting.key, "moved to " + new_place.field(setting.key) + ", which the config gives too");
    }
  }
}

// The optional `front_end:` and `dot:` sections, both of which set the dot config.
void read_front_end_and_dot(YamlMap& root, const YamlMap& camera, dot::DotSourceConfig& config) {
  std::optional<YamlMap> front_end = root.optional_map("front_end");
  if (front_end) {
    read_settings(*front_end, front_end_settings(), config);
    front_end->reject_unknown_keys();
  }
  if (std::optional<YamlMap> dot = root.optional_map("dot")) {
    reject_moved_keys_given_twice(*dot, camera_pixel_settings(), camera);
    if (front_end) reject_moved_keys_given_twice(*dot, front_end_settings(), *front_end);
    read_dot_config(*dot, config);
  }
}

}  // namespace

RigidTransform read_mount(YamlMap& mount) {
  const bool has_preset = mount.has("preset");
  const bool has_rotation = mount.has("rotation");
  if (has_preset == has_rotation) mount.fail("give exactly one of 'preset' and 'rotation'");

  RigidTransform t_b_c;
  const std::vector<double> xyz = mount.numbers("xyz", 3, kMountOffset);
  t_b_c.translation = Eigen::Vector3d(xyz[0], xyz[1], xyz[2]);
  if (has_preset) {
    const std::string preset = mount.text("preset");
    if (preset != "up") mount.fail_key("preset", "unknown preset '" + preset + "' (expected up)");
    Eigen::Vector3d rpy = Eigen::Vector3d::Zero();
    if (mount.has("rpy")) rpy = mount.vector3("rpy", kMountAngle);
    t_b_c.rotation = rotation_from_rpy(rpy.x(), rpy.y(), rpy.z()) * kRotationUp;
  } else {
    const std::vector<double> r = mount.numbers("rotation", 9, {-2, 2});
    const Eigen::Matrix3d rotation = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(r.data());
    const double orthogonality_error = (rotation * rotation.transpose() - Eigen::Matrix3d::Identity()).norm();
    if (orthogonality_error > 1e-6 || rotation.determinant() < 0) {
      mount.fail_key("rotation", "not a rotation matrix (orthonormal, determinant +1) to 1e-6");
    }
    t_b_c.rotation = rotation;
  }
  mount.reject_unknown_keys();
  return t_b_c;
}

std::span<const Setting<MotionLimits>> robot_motion_settings() { return kRobotMotionSettings; }

std::optional<double> read_side_speed(YamlMap& robot) { return robot.optional_number("max_side_speed", kRobotSideSpeed); }

void read_robot_motion(YamlMap& robot, MotionLimits& limits) {
  read_settings(robot, robot_motion_settings(), limits);
  limits.side_speed = read_side_speed(robot);
  if (limits.side_speed && *limits.side_speed > limits.speed) {
    robot.fail_key("max_side_speed", "must be at most max_speed (" + number_text(limits.speed) + "), got " +
                                         number_text(*limits.side_speed));
  }
}

std::int64_t read_line_time(YamlMap& camera) { return camera.integer("line_time_ns", 0, kMaxLineTimeNs, 0); }

RobotConfig load_robot_config(const std::filesystem::path& path) {
  YamlMap root(load_yaml_file(path), path.string(), "");
  return read_robot_config(root);
}

namespace {

// The optional `mavlink:` section: the EKF origin to send and the pose message.
void read_mavlink_section(YamlMap& root, RobotConfig& config) {
  if (!root.has("mavlink")) return;
  YamlMap mavlink = root.map("mavlink");
  if (std::optional<YamlMap> origin = mavlink.optional_map("ekf_origin")) {
    config.ekf_origin = EkfOrigin{origin->number("latitude_deg", {-90, 90}), origin->number("longitude_deg", {-180, 180}),
                                  origin->number("altitude_m", {-1000, 10000})};
    origin->reject_unknown_keys();
  }
  if (mavlink.has("pose_message")) {
    const std::string message = mavlink.text("pose_message");
    if (message == "odometry") {
      config.odometry = true;
    } else if (message != "vision_position_estimate") {
      mavlink.fail_key("pose_message", "unknown message '" + message + "' (expected vision_position_estimate or odometry)");
    }
  }
  mavlink.reject_unknown_keys();
}

// The mount's tilt watch: on by default where the robot's dof leaves the tilt to the mount.
void read_mount_watch_section(YamlMap& root, RobotConfig& config) {
  config.mount_watch.enabled = config.setup.dof != Dof::full6;
  if (root.has("mount_watch")) {
    YamlMap watch = root.map("mount_watch");
    config.mount_watch = read_mount_watch_config(watch);
    if (config.mount_watch.enabled && config.setup.dof == Dof::full6) {
      watch.fail_key("enabled", "the mount's tilt cannot be watched with robot.dof 6 (it is the robot's own tilt too)");
    }
  }
}

}  // namespace

RobotConfig read_robot_config(YamlMap& root) {
  RobotConfig config;
  const std::string mode = root.has("mode") ? root.text("mode") : "on_robot";
  if (mode == "outside_in") {
    read_outside_in_config(root, config);
    return config;
  }
  if (mode != "on_robot") root.fail_key("mode", "expected on_robot or outside_in, got '" + mode + "'");

  YamlMap camera = root.map("camera");
  config.calibration_file = camera.path("calibration");
  YamlMap mount = camera.map("mount");
  config.setup.mount = read_mount(mount);
  config.setup.line_time_ns = read_line_time(camera);
  read_settings(camera, camera_pixel_settings(), config.setup.dot);
  camera.reject_unknown_keys();

  YamlMap robot = root.map("robot");
  config.setup.dof = robot.dof("dof");
  read_robot_motion(robot, config.setup.robot_limits);
  robot.reject_unknown_keys();

  config.map_file = root.path("map");
  read_front_end_and_dot(root, camera, config.setup.dot);
  if (root.has("square")) {
    YamlMap square = root.map("square");
    config.setup.square = read_square_config(square);
  }
  if (root.has("led")) {
    YamlMap led = root.map("led");
    config.setup.led = read_led_config(led);
  }
  if (root.has("outside_in")) root.fail_key("outside_in", "only read with mode: outside_in");
  read_mount_watch_section(root, config);
  read_mavlink_section(root, config);
  root.reject_unknown_keys();

  // The files it names, each reporting its own problems.
  config.setup.camera = load_camera_info(config.calibration_file);
  config.setup.map = load_marker_map(config.map_file);
  return config;
}

}  // namespace irloc::io
