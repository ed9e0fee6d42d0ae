#include "host_sim/scenario/scenario.hpp"

#include <cmath>
#include <numbers>

#include "hal/config/calibration_file.hpp"
#include "hal/config/config_file.hpp"
#include "hal/config/map_file.hpp"
#include "hal/config/yaml_reader.hpp"
#include "hal/input_error.hpp"

namespace irloc::sim {
namespace {

using hal::YamlMap;

constexpr double kPi = std::numbers::pi;
constexpr double kOnCeilingTolerance = 1e-3;  // metres

double positive(YamlMap& map, const std::string& key, double default_value) {
  const double value = map.optional_number(key).value_or(default_value);
  if (!(value > 0)) map.fail_key(key, "must be positive");
  return value;
}

double non_negative(YamlMap& map, const std::string& key, double default_value) {
  const double value = map.optional_number(key).value_or(default_value);
  if (!(value >= 0)) map.fail_key(key, "must not be negative");
  return value;
}

double in_range(YamlMap& map, const std::string& key, double default_value, double low, double high) {
  const double value = map.optional_number(key).value_or(default_value);
  if (!(value >= low && value <= high)) {
    map.fail_key(key, "must be in [" + std::to_string(low) + ", " + std::to_string(high) + "]");
  }
  return value;
}

// An optional whole number in 1..high.
int count(YamlMap& map, const std::string& key, int default_value, int high) {
  if (!map.has(key)) {
    map.ignore(key);
    return default_value;
  }
  const long long value = map.integer(key);
  if (value < 1 || value > high) map.fail_key(key, "must be 1.." + std::to_string(high));
  return static_cast<int>(value);
}

bool flag(YamlMap& map, const std::string& key, bool default_value) {
  if (!map.has(key)) {
    map.ignore(key);
    return default_value;
  }
  const std::string value = map.text(key);
  if (value == "true") return true;
  if (value == "false") return false;
  map.fail_key(key, "expected true or false, got '" + value + "'");
}

Eigen::Vector2d vector2(YamlMap& map, const std::string& key) {
  const std::vector<double> v = map.numbers(key, 2);
  return {v[0], v[1]};
}

Eigen::Vector3d vector3(YamlMap& map, const std::string& key) {
  const std::vector<double> v = map.numbers(key, 3);
  return {v[0], v[1], v[2]};
}

Eigen::Vector4d rectangle(YamlMap& map, const std::string& key) {
  const std::vector<double> v = map.numbers(key, 4);
  if (!(v[2] > v[0] && v[3] > v[1])) map.fail_key(key, "expected [x0, y0, x1, y1] with x1 > x0 and y1 > y0");
  return {v[0], v[1], v[2], v[3]};
}

std::vector<Eigen::Vector2d> points2(YamlMap& map, const std::string& key) {
  std::vector<Eigen::Vector2d> points;
  for (const YAML::Node& node : map.items(key)) {
    if (!node.IsSequence() || node.size() != 2) map.fail(node, key, "expected a list of [x, y] points");
    points.emplace_back(hal::as_number(map, node[0], key), hal::as_number(map, node[1], key));
  }
  return points;
}

// Calls read(item) for every mapping in the list `key`, each checked strictly.
template <typename Read>
void for_each_item(YamlMap& parent, const std::string& key, Read read) {
  const std::vector<YAML::Node> items = parent.items(key);
  for (std::size_t i = 0; i < items.size(); ++i) {
    YamlMap item(items[i], parent.file(), parent.field(key) + "[" + std::to_string(i) + "]");
    read(item);
    item.reject_unknown_keys();
  }
}

CameraSpec read_camera(YamlMap& camera, const std::filesystem::path& base_dir) {
  CameraSpec spec;
  const bool inline_calibration = camera.has("calibration");
  if (inline_calibration == camera.has("calibration_file")) {
    camera.fail("give exactly one of 'calibration' (camera_info keys inline) and 'calibration_file'");
  }
  if (inline_calibration) {
    YamlMap calibration = camera.map("calibration");
    spec.intrinsics = hal::read_camera_info(calibration);
    camera.ignore("calibration_file");
  } else {
    const std::filesystem::path file(camera.text("calibration_file"));
    spec.intrinsics = hal::load_camera_info(file.is_absolute() ? file : base_dir / file);
    camera.ignore("calibration");
  }
  YamlMap mount = camera.map("mount");
  spec.mount = to_isometry(hal::read_mount(mount));

  const double bit_depth = camera.optional_number("bit_depth").value_or(8);
  if (bit_depth != 8 && bit_depth != 10 && bit_depth != 12) camera.fail_key("bit_depth", "must be 8, 10 or 12");
  spec.bit_depth = static_cast<int>(bit_depth);
  spec.frame_rate = in_range(camera, "frame_rate", spec.frame_rate, 1, 1000);
  spec.exposure = positive(camera, "exposure", spec.exposure);
  if (spec.exposure > 1 / spec.frame_rate) camera.fail_key("exposure", "longer than one frame period");
  spec.sensitivity = positive(camera, "sensitivity", spec.sensitivity);
  spec.full_well = positive(camera, "full_well", spec.full_well);
  spec.read_noise = non_negative(camera, "read_noise", spec.read_noise);
  spec.black_level = in_range(camera, "black_level", spec.black_level, 0, 0.5);
  spec.noise = flag(camera, "noise", spec.noise);
  return spec;
}

Dof read_dof(YamlMap& robot) {
  const long long dof = robot.integer("dof");
  if (dof == 3) return Dof::planar3;
  if (dof == 4) return Dof::height4;
  if (dof == 6) return Dof::full6;
  robot.fail_key("dof", "must be 3, 4 or 6");
}

TrajectorySpec read_trajectory(YamlMap& map) {
  TrajectorySpec spec;
  const std::string type = map.text("type");
  if (type == "static") {
    spec.kind = TrajectoryKind::static_pose;
    spec.pose = vector3(map, "pose");
  } else if (type == "waypoints") {
    spec.kind = TrajectoryKind::waypoints;
    spec.points = points2(map, "points");
    if (spec.points.size() < 2) map.fail_key("points", "expected at least 2 points [x, y]");
    const bool per_leg = map.has("speeds");
    if (per_leg == map.has("speed")) map.fail("give exactly one of 'speed' and 'speeds' (one per point after the first)");
    spec.closed = flag(map, "closed", false);
    const std::size_t legs = spec.points.size() - (spec.closed ? 0 : 1);
    if (per_leg) {
      spec.speeds = map.numbers("speeds", legs);
      map.ignore("speed");
    } else {
      spec.speeds.assign(legs, map.number("speed"));
      map.ignore("speeds");
    }
    for (double speed : spec.speeds) {
      if (!(speed > 0)) map.fail_key(per_leg ? "speeds" : "speed", "speeds must be positive");
    }
    for (std::size_t i = 0; i + 1 < spec.points.size(); ++i) {
      if ((spec.points[i + 1] - spec.points[i]).norm() < 1e-6) map.fail_key("points", "two consecutive points coincide");
    }
    spec.turn_rate = positive(map, "turn_rate", spec.turn_rate);
  } else if (type == "loop") {
    spec.kind = TrajectoryKind::loop;
    spec.centre = vector2(map, "centre");
    spec.radius = positive(map, "radius", spec.radius);
    spec.speed = positive(map, "speed", spec.speed);
    spec.clockwise = flag(map, "clockwise", false);
  } else if (type == "lawn_mower") {
    spec.kind = TrajectoryKind::lawn_mower;
    spec.area = rectangle(map, "area");
    spec.spacing = positive(map, "spacing", spec.spacing);
    spec.speed = positive(map, "speed", spec.speed);
    spec.turn_rate = positive(map, "turn_rate", spec.turn_rate);
  } else if (type == "spin") {
    spec.kind = TrajectoryKind::spin;
    const Eigen::Vector2d centre = vector2(map, "centre");
    spec.pose = {centre.x(), centre.y(), map.optional_number("yaw").value_or(0)};
    spec.rate = map.optional_number("rate").value_or(spec.rate);
  } else {
    map.fail_key("type", "unknown trajectory '" + type + "' (expected static, waypoints, loop, lawn_mower or spin)");
  }
  return spec;
}

Eigen::Vector3d unit(YamlMap& map, const std::string& key) {
  const Eigen::Vector3d v = vector3(map, key);
  if (v.norm() < 1e-9) map.fail_key(key, "must not be the zero vector");
  return v.normalized();
}

// The beam axis of an LED at `position` tilted outward, away from the optical axis, by `tilt`
// towards azimuth `azimuth` (camera x toward y).
Eigen::Vector3d tilted_axis(double tilt, double azimuth) {
  return {std::sin(tilt) * std::cos(azimuth), std::sin(tilt) * std::sin(azimuth), std::cos(tilt)};
}

std::size_t led_type_index(YamlMap& item, const LedRing& ring) {
  const std::string name = item.text("type");
  for (std::size_t i = 0; i < ring.types.size(); ++i) {
    if (ring.types[i].name == name) return i;
  }
  item.fail_key("type", "no LED type named '" + name + "' in led_ring.types");
}

LedRing read_ring(YamlMap& map) {
  LedRing ring;
  for_each_item(map, "types", [&](YamlMap& item) {
    LedType type;
    type.name = item.text("name");
    type.intensity = positive(item, "intensity", type.intensity);
    type.half_angle = in_range(item, "half_angle", type.half_angle, 1e-3, kPi / 2 - 1e-3);
    ring.types.push_back(type);
  });
  if (ring.types.empty()) map.fail_key("types", "expected at least one LED type");
  for_each_item(map, "leds", [&](YamlMap& item) {
    RingLed led;
    led.type = led_type_index(item, ring);
    led.position = vector3(item, "position");
    if (item.has("axis")) {
      led.axis = unit(item, "axis");
      item.ignore("tilt");
      item.ignore("azimuth");
    } else {
      item.ignore("axis");
      const double tilt = in_range(item, "tilt", 0, 0, kPi / 2);
      const double azimuth = item.optional_number("azimuth").value_or(std::atan2(led.position.y(), led.position.x()));
      led.axis = tilted_axis(tilt, azimuth);
    }
    ring.leds.push_back(led);
  });
  for_each_item(map, "rings", [&](YamlMap& item) {
    const std::size_t type = led_type_index(item, ring);
    const long long count = item.integer("count");
    if (count < 1 || count > 64) item.fail_key("count", "must be 1..64");
    const double radius = non_negative(item, "radius", 0.02);
    const double tilt = in_range(item, "tilt", 0, 0, kPi / 2);
    const double phase = item.optional_number("phase").value_or(0);
    const double z = item.optional_number("z").value_or(0);
    for (long long i = 0; i < count; ++i) {
      const double azimuth = phase + 2 * kPi * static_cast<double>(i) / static_cast<double>(count);
      ring.leds.push_back({type, {radius * std::cos(azimuth), radius * std::sin(azimuth), z}, tilted_axis(tilt, azimuth)});
    }
  });
  if (ring.leds.empty()) map.fail("expected at least one LED in 'leds' or 'rings'");
  return ring;
}

RetroReflector read_retro(YamlMap& map) {
  RetroReflector retro;
  retro.coefficient = positive(map, "coefficient", retro.coefficient);
  retro.observation_width = positive(map, "observation_width", retro.observation_width);
  retro.entrance_limit = in_range(map, "entrance_limit", retro.entrance_limit, 0.01, kPi / 2);
  return retro;
}

Room read_room(YamlMap& map) {
  Room room;
  room.ceiling_height = map.number("ceiling_height");
  if (map.has("bounds")) {
    room.bounds = rectangle(map, "bounds");
  } else {
    map.ignore("bounds");
  }
  room.ambient = non_negative(map, "ambient", room.ambient);
  room.ceiling_reflectance = in_range(map, "ceiling_reflectance", room.ceiling_reflectance, 0, 1);
  room.wall_reflectance = in_range(map, "wall_reflectance", room.wall_reflectance, 0, 1);
  for_each_item(map, "lamps", [&](YamlMap& item) {
    Lamp lamp;
    lamp.centre = vector2(item, "centre");
    if (item.has("radius") == item.has("size")) item.fail("give exactly one of 'radius' (a disc) and 'size' [sx, sy]");
    if (item.has("radius")) {
      lamp.radius = positive(item, "radius", 0);
      item.ignore("size");
    } else {
      lamp.size = vector2(item, "size");
      if (!(lamp.size.x() > 0 && lamp.size.y() > 0)) item.fail_key("size", "must be positive");
      item.ignore("radius");
    }
    lamp.radiance = non_negative(item, "radiance", lamp.radiance);
    room.lamps.push_back(lamp);
  });
  for_each_item(map, "windows", [&](YamlMap& item) {
    Window window;
    window.corner_a = vector3(item, "corner_a");
    window.corner_b = vector3(item, "corner_b");
    window.radiance = non_negative(item, "radiance", window.radiance);
    if (!room.bounds) item.fail("windows need room.bounds (the walls they are in)");
    const Eigen::Vector4d& b = *room.bounds;
    const auto on = [](double a, double c, double wall) {
      return std::abs(a - wall) < kOnCeilingTolerance && std::abs(c - wall) < kOnCeilingTolerance;
    };
    const Eigen::Vector3d& a = window.corner_a;
    const Eigen::Vector3d& c = window.corner_b;
    if (!(on(a.x(), c.x(), b[0]) || on(a.x(), c.x(), b[2]) || on(a.y(), c.y(), b[1]) || on(a.y(), c.y(), b[3]))) {
      item.fail("both corners must lie on the same wall of room.bounds");
    }
    room.windows.push_back(window);
  });
  return room;
}

void check_on_ceiling(YamlMap& root, const MarkerMap& map, double ceiling) {
  for (const DotMarker& marker : map.dot_markers) {
    if (std::abs(marker.origin.z() - ceiling) > kOnCeilingTolerance) {
      root.fail_key("map", "dot marker " + std::to_string(marker.id) + " is not on the ceiling (z = room.ceiling_height)");
    }
  }
  for (const SquareMarker& marker : map.square_markers) {
    for (const Eigen::Vector3d& corner : marker.corners) {
      if (std::abs(corner.z() - ceiling) > kOnCeilingTolerance) {
        root.fail_key("map", "square marker '" + marker.name + "' is not on the ceiling (z = room.ceiling_height)");
      }
    }
  }
}

std::vector<Occluder> read_people(YamlMap& root) {
  std::vector<Occluder> people;
  for_each_item(root, "people", [&](YamlMap& item) {
    Occluder person;
    person.path = points2(item, "path");
    if (person.path.empty()) item.fail_key("path", "expected at least one point [x, y]");
    person.speed = non_negative(item, "speed", person.speed);
    person.radius = positive(item, "radius", person.radius);
    person.height = positive(item, "height", person.height);
    person.reflectance = in_range(item, "reflectance", person.reflectance, 0, 1);
    people.push_back(person);
  });
  return people;
}

Scenario read_scenario(YamlMap& root, const std::filesystem::path& base_dir) {
  Scenario scenario;
  scenario.name = root.file();
  const long long seed = root.optional_number("seed") ? root.integer("seed") : 1;
  if (seed < 0) root.fail_key("seed", "must not be negative");
  scenario.seed = static_cast<std::uint64_t>(seed);
  const long long frames = root.integer("frames");
  if (frames < 1 || frames > 1'000'000) root.fail_key("frames", "must be 1..1000000");
  scenario.frames = static_cast<int>(frames);

  YamlMap camera = root.map("camera");
  scenario.camera = read_camera(camera, base_dir);
  camera.reject_unknown_keys();

  if (root.has("robot")) {
    YamlMap robot = root.map("robot");
    scenario.dof = read_dof(robot);
    robot.reject_unknown_keys();
  } else {
    root.ignore("robot");
  }

  YamlMap trajectory = root.map("trajectory");
  scenario.trajectory = read_trajectory(trajectory);
  trajectory.reject_unknown_keys();

  YamlMap ring = root.map("led_ring");
  scenario.ring = read_ring(ring);
  ring.reject_unknown_keys();

  if (root.has("retro_reflector")) {
    YamlMap retro = root.map("retro_reflector");
    scenario.retro = read_retro(retro);
    retro.reject_unknown_keys();
  } else {
    root.ignore("retro_reflector");
  }

  YamlMap room = root.map("room");
  scenario.room = read_room(room);
  room.reject_unknown_keys();

  if (root.has("map")) {
    YamlMap map = root.map("map");
    scenario.map = hal::read_marker_map(map);
    check_on_ceiling(root, scenario.map, scenario.room.ceiling_height);
  } else {
    root.ignore("map");
  }

  if (root.has("landmark_emitters")) {
    YamlMap emitters = root.map("landmark_emitters");
    scenario.landmark_emitters.intensity = positive(emitters, "intensity", scenario.landmark_emitters.intensity);
    scenario.landmark_emitters.radius = positive(emitters, "radius", scenario.landmark_emitters.radius);
    emitters.reject_unknown_keys();
  } else {
    root.ignore("landmark_emitters");
  }

  scenario.people = read_people(root);

  if (root.has("dropped_frames")) {
    YamlMap dropped = root.map("dropped_frames");
    for (const YAML::Node& node : dropped.items("seqs")) {
      const double seq = hal::as_number(dropped, node, "seqs");
      if (seq < 0 || seq != std::floor(seq)) dropped.fail(node, "seqs", "expected frame sequence numbers");
      scenario.dropped_frames.push_back(static_cast<std::uint64_t>(seq));
    }
    scenario.drop_probability = in_range(dropped, "probability", 0, 0, 0.5);
    dropped.reject_unknown_keys();
  } else {
    root.ignore("dropped_frames");
  }

  if (root.has("render")) {
    YamlMap render = root.map("render");
    scenario.supersampling = count(render, "supersampling", scenario.supersampling, 16);
    scenario.motion_blur_samples = count(render, "motion_blur_samples", 1, 16);
    render.reject_unknown_keys();
  } else {
    root.ignore("render");
  }

  if (root.has("metrics")) {
    YamlMap metrics = root.map("metrics");
    scenario.metrics.gross_position = positive(metrics, "gross_position", scenario.metrics.gross_position);
    scenario.metrics.gross_yaw = positive(metrics, "gross_yaw", scenario.metrics.gross_yaw);
    metrics.reject_unknown_keys();
  } else {
    root.ignore("metrics");
  }
  root.reject_unknown_keys();
  return scenario;
}

}  // namespace

Scenario load_scenario(const std::filesystem::path& path) {
  YamlMap root(hal::load_yaml_file(path), path.string(), "");
  return read_scenario(root, path.parent_path());
}

Scenario parse_scenario(const std::string& yaml_text, const std::string& name, const std::filesystem::path& base_dir) {
  YAML::Node node;
  try {
    node = YAML::Load(yaml_text);
  } catch (const YAML::ParserException& e) {
    throw hal::InputError(name + ":" + std::to_string(e.mark.line + 1) + ": malformed YAML: " + e.msg);
  }
  if (!node.IsMap()) throw hal::InputError(name + ": expected a YAML mapping at the top level");
  YamlMap root(node, name, "");
  return read_scenario(root, base_dir);
}

}  // namespace irloc::sim
