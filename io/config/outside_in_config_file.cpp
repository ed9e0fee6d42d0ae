#include "io/config/outside_in_config_file.hpp"

#include <optional>
#include <string>

#include "algo/markers/outside_in/floor_geometry.hpp"
#include "io/config/calibration_file.hpp"
#include "io/config/map_file.hpp"

namespace irloc::io {
namespace {

const Setting<outside_in::OutsideInConfig> kOutsideInSettings[] = {
    {"min_blob_area_px", &outside_in::OutsideInConfig::min_blob_area_px, 1, 1000000, "px", "smaller foreground is noise"},
    {"max_fits_per_frame", &outside_in::OutsideInConfig::max_fits_per_frame, 1, 64, "", "the largest plausible blobs fitted per frame"},
    {"max_shape_residual", &outside_in::OutsideInConfig::max_shape_residual, 0.001, 1, "",
     "moment residual RMS of the box fit, fraction of sqrt(blob area)"},
    {"min_area_ratio", &outside_in::OutsideInConfig::min_area_ratio, 0.1, 1, "", "observed / fitted area at least this"},
    {"max_area_ratio", &outside_in::OutsideInConfig::max_area_ratio, 1, 10, "", "observed / fitted area at most this"},
    {"border_margin_px", &outside_in::OutsideInConfig::border_margin_px, 0, 1000, "px", "a blob this near the image edge is not whole"},
    {"max_coast_s", &outside_in::OutsideInConfig::max_coast_s, 0, 10, "s", "the track survives this long without a fit"},
    {"track_gate_m", &outside_in::OutsideInConfig::track_gate_m, 0.01, 10, "m", "a fit further from the prediction starts a new track"},
    {"heading_motion_m", &outside_in::OutsideInConfig::heading_motion_m, 0.001, 10, "m", "travel that tells forward from backward"},
    {"heading_prior_rad", &outside_in::OutsideInConfig::heading_prior_rad, 0.001, 3.15, "rad",
     "the track's predicted heading picks among the box fit's minima within this"},
};

// 4 to FloorReference::kMaxPoints points, each a list of two numbers in range.
std::vector<Eigen::Vector2d> floor_points(YamlMap& reference, const std::string& key, Range range) {
  const std::vector<std::vector<double>> points = reference.points(key, 2, range);
  if (points.size() < 4 || points.size() > outside_in::FloorReference::kMaxPoints) {
    reference.fail_key(key, "expected 4 to " + std::to_string(outside_in::FloorReference::kMaxPoints) + " floor points, got " +
                                std::to_string(points.size()));
  }
  std::vector<Eigen::Vector2d> result;
  for (const std::vector<double>& point : points) result.emplace_back(point[0], point[1]);
  return result;
}

}  // namespace

std::span<const Setting<outside_in::OutsideInConfig>> outside_in_settings() { return kOutsideInSettings; }

void read_outside_in_config(YamlMap& root, RobotConfig& config) {
  config.mode = RobotMode::outside_in;
  config.mount_watch.enabled = false;
  outside_in::OutsideInConfig outside;

  YamlMap camera = root.map("camera");
  config.calibration_file = camera.path("calibration");
  config.setup.line_time_ns = read_line_time(camera);
  YamlMap reference = camera.map("floor_reference");
  outside.floor_reference.world = floor_points(reference, "world", {-1000, 1000});
  outside.floor_reference.pixels = floor_points(reference, "pixels", {-100000, 100000});
  if (outside.floor_reference.pixels.size() != outside.floor_reference.world.size()) {
    reference.fail_key("pixels", "expected one pixel per world point (" +
                                     std::to_string(outside.floor_reference.world.size()) + "), got " +
                                     std::to_string(outside.floor_reference.pixels.size()));
  }
  outside.floor_reference.pixel_sigma = reference.number("pixel_sigma", {0.01, 20}, outside.floor_reference.pixel_sigma);
  reference.reject_unknown_keys();
  camera.reject_unknown_keys();

  YamlMap robot = root.map("robot");
  config.setup.dof = robot.dof("dof");
  if (config.setup.dof != Dof::planar3) {
    robot.fail_key("dof", "outside-in mode gives the robot's x, y and heading: robot.dof must be 3");
  }
  YamlMap body = robot.map("body");
  outside.body.length = body.number("length", {0.05, 10});
  outside.body.width = body.number("width", {0.05, 10});
  outside.body.height = body.number("height", {0.02, 5});
  body.reject_unknown_keys();
  read_robot_motion(robot, config.setup.robot_limits);
  robot.reject_unknown_keys();

  if (root.has("map")) config.map_file = root.path("map");
  if (std::optional<YamlMap> section = root.optional_map("outside_in")) {
    read_settings(*section, outside_in_settings(), outside);
    section->reject_unknown_keys();
  }
  root.reject_unknown_keys();

  config.setup.camera = load_camera_info(config.calibration_file);
  if (!config.map_file.empty()) config.setup.map = load_marker_map(config.map_file);
  const outside_in::FloorGeometry floor = outside_in::solve_floor_geometry(config.setup.camera, outside.floor_reference);
  if (!floor.ok) {
    camera.fail_key("floor_reference", floor.error + " (camera as calibrated in " + config.calibration_file.string() + ")");
  }
  config.setup.outside_in = outside;
}

}  // namespace irloc::io
