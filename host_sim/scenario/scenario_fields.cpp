#include "host_sim/scenario/scenario_fields.hpp"

#include "io/config/calibration_file.hpp"
#include "io/config/config_file.hpp"

namespace irloc::sim {

using io::YamlMap;

Eigen::Vector4d read_rectangle(YamlMap& map, const std::string& key) {
  const std::vector<double> v = map.numbers(key, 4, kWorldCoordinate);
  if (!(v[2] > v[0] && v[3] > v[1])) map.fail_key(key, "expected [x0, y0, x1, y1] with x1 > x0 and y1 > y0");
  return {v[0], v[1], v[2], v[3]};
}

std::vector<Eigen::Vector2d> read_points2(YamlMap& map, const std::string& key) {
  std::vector<Eigen::Vector2d> points;
  for (const std::vector<double>& point : map.points(key, 2, kWorldCoordinate)) points.emplace_back(point[0], point[1]);
  return points;
}

std::int64_t read_rolling_shutter(YamlMap& camera, int height, double frame_rate) {
  const std::int64_t line_time_ns = io::read_line_time(camera);
  if (static_cast<double>(line_time_ns) * 1e-9 * height > 1 / frame_rate) {
    camera.fail_key("line_time_ns", "reading the rows out takes longer than one frame period");
  }
  return line_time_ns;
}

CameraIntrinsics read_camera_calibration(YamlMap& camera, const std::filesystem::path& base_dir, std::filesystem::path& file) {
  const bool inline_calibration = camera.has("calibration");
  if (inline_calibration == camera.has("calibration_file")) {
    camera.fail("give exactly one of 'calibration' (camera_info keys inline) and 'calibration_file'");
  }
  if (inline_calibration) {
    YamlMap calibration = camera.map("calibration");
    return io::read_camera_info(calibration);
  }
  const std::filesystem::path given(camera.text("calibration_file"));
  file = given.is_absolute() ? given : base_dir / given;
  return io::load_camera_info(file);
}

TrajectorySpec read_trajectory(YamlMap& map) {
  TrajectorySpec spec;
  const std::string type = map.text("type");
  if (type == "static") {
    spec.kind = TrajectoryKind::static_pose;
    spec.pose = map.vector3("pose", kWorldCoordinate);
  } else if (type == "waypoints") {
    spec.kind = TrajectoryKind::waypoints;
    spec.points = read_points2(map, "points");
    if (spec.points.size() < 2) map.fail_key("points", "expected at least 2 points [x, y]");
    const bool per_leg = map.has("speeds");
    if (per_leg == map.has("speed")) map.fail("give exactly one of 'speed' and 'speeds' (one per point after the first)");
    spec.closed = map.boolean("closed", false);
    const std::size_t legs = spec.points.size() - (spec.closed ? 0 : 1);
    if (per_leg) {
      spec.speeds = map.numbers("speeds", legs, kSpeed);
    } else {
      spec.speeds.assign(legs, map.number("speed", kSpeed));
    }
    for (std::size_t i = 0; i + 1 < spec.points.size(); ++i) {
      if ((spec.points[i + 1] - spec.points[i]).norm() < 1e-6) map.fail_key("points", "two consecutive points coincide");
    }
    spec.turn_rate = map.number("turn_rate", kSpeed, spec.turn_rate);
  } else if (type == "loop") {
    spec.kind = TrajectoryKind::loop;
    spec.centre = map.vector2("centre", kWorldCoordinate);
    spec.radius = map.number("radius", kSize, spec.radius);
    spec.speed = map.number("speed", kSpeed, spec.speed);
    spec.clockwise = map.boolean("clockwise", false);
  } else if (type == "lawn_mower") {
    spec.kind = TrajectoryKind::lawn_mower;
    spec.area = read_rectangle(map, "area");
    spec.spacing = map.number("spacing", kSize, spec.spacing);
    spec.speed = map.number("speed", kSpeed, spec.speed);
    spec.turn_rate = map.number("turn_rate", kSpeed, spec.turn_rate);
  } else if (type == "spin") {
    spec.kind = TrajectoryKind::spin;
    const Eigen::Vector2d centre = map.vector2("centre", kWorldCoordinate);
    spec.pose = {centre.x(), centre.y(), map.number("yaw", kAngle, 0)};
    spec.rate = map.number("rate", {-100, 100}, spec.rate);
  } else {
    map.fail_key("type", "unknown trajectory '" + type + "' (expected static, waypoints, loop, lawn_mower or spin)");
  }
  if (std::optional<YamlMap> sway = map.optional_map("sway")) {
    spec.sway_roll = sway->number("roll", {0, 0.5}, 0);
    spec.sway_pitch = sway->number("pitch", {0, 0.5}, 0);
    spec.sway_heave = sway->number("heave", {0, 1}, 0);
    spec.sway_period = sway->number("period", {0.01, 1000}, spec.sway_period);
    sway->reject_unknown_keys();
  }
  return spec;
}

std::vector<Occluder> read_people(YamlMap& root) {
  std::vector<Occluder> people;
  root.for_each_item("people", [&](YamlMap& item) {
    Occluder person;
    person.path = read_points2(item, "path");
    if (person.path.empty()) item.fail_key("path", "expected at least one point [x, y]");
    person.speed = item.number("speed", {0, 100}, person.speed);
    person.radius = item.number("radius", kSize, person.radius);
    person.height = item.number("height", kSize, person.height);
    person.reflectance = item.number("reflectance", kFraction, person.reflectance);
    people.push_back(person);
  });
  return people;
}

}  // namespace irloc::sim
