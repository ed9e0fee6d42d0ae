#include "host_sim/scenario/scenario.hpp"

#include <cmath>
#include <limits>
#include <optional>
#include <numbers>

#include "io/config/calibration_file.hpp"
#include "io/config/config_file.hpp"
#include "io/config/map_file.hpp"
#include "io/config/yaml_reader.hpp"
#include "host_sim/render/outside_in_scene.hpp"

namespace irloc::sim {
namespace {

using io::YamlMap;

constexpr double kPi = std::numbers::pi;
constexpr double kOnCeilingTolerance = 1e-3;  // metres
constexpr double kWallCameraFrameRate = 10;     // outside-in: a webcam's default, frames per second
constexpr std::size_t kMostWallCameras = 8;    // outside-in: each is a rendered dataset and an irlocd run

// Ranges of docs/formats.md.
constexpr io::Range kWorldCoordinate{-10'000, 10'000};  // metres
constexpr io::Range kAngle{-7, 7};                      // radians, within a turn either way
constexpr io::Range kDirection{-1'000, 1'000};          // a direction vector's components
constexpr io::Range kRigOffset{-10, 10};                // metres from the camera
constexpr io::Range kSize{1e-3, 1'000};                 // metres
constexpr io::Range kSpeed{1e-3, 100};                  // m/s or rad/s
constexpr io::Range kRadiance{0, 1e9};                  // W sr^-1 m^-2, W/m^2
constexpr io::Range kIntensity{1e-9, 1e6};              // W/sr
constexpr io::Range kFraction{0, 1};
// Clutter sizes: from a sticker to a duct's length; below a millimetre it would render as nothing.
constexpr io::Range kStripLength{0.005, 20};  // metres
constexpr io::Range kStripWidth{0.002, 1};    // metres
constexpr io::Range kCrescentRadius{0.002, 1};  // metres

Eigen::Vector4d rectangle(YamlMap& map, const std::string& key) {
  const std::vector<double> v = map.numbers(key, 4, kWorldCoordinate);
  if (!(v[2] > v[0] && v[3] > v[1])) map.fail_key(key, "expected [x0, y0, x1, y1] with x1 > x0 and y1 > y0");
  return {v[0], v[1], v[2], v[3]};
}

std::vector<Eigen::Vector2d> points2(YamlMap& map, const std::string& key) {
  std::vector<Eigen::Vector2d> points;
  for (const std::vector<double>& point : map.points(key, 2, kWorldCoordinate)) points.emplace_back(point[0], point[1]);
  return points;
}

// The camera's `line_time_ns` (a rolling shutter; 0: global), whose rows must be read out within
// one frame period.
std::int64_t read_rolling_shutter(YamlMap& camera, int height, double frame_rate) {
  const std::int64_t line_time_ns = io::read_line_time(camera);
  if (static_cast<double>(line_time_ns) * 1e-9 * height > 1 / frame_rate) {
    camera.fail_key("line_time_ns", "reading the rows out takes longer than one frame period");
  }
  return line_time_ns;
}

CameraSpec read_camera(YamlMap& camera, const std::filesystem::path& base_dir) {
  CameraSpec spec;
  const bool inline_calibration = camera.has("calibration");
  if (inline_calibration == camera.has("calibration_file")) {
    camera.fail("give exactly one of 'calibration' (camera_info keys inline) and 'calibration_file'");
  }
  if (inline_calibration) {
    YamlMap calibration = camera.map("calibration");
    spec.intrinsics = io::read_camera_info(calibration);
  } else {
    const std::filesystem::path file(camera.text("calibration_file"));
    spec.calibration_file = file.is_absolute() ? file : base_dir / file;
    spec.intrinsics = io::load_camera_info(spec.calibration_file);
  }
  YamlMap mount = camera.map("mount");
  spec.mount = to_isometry(io::read_mount(mount));

  spec.bit_depth = static_cast<int>(camera.integer("bit_depth", 8, 12, spec.bit_depth));
  if (spec.bit_depth != 8 && spec.bit_depth != 10 && spec.bit_depth != 12) camera.fail_key("bit_depth", "must be 8, 10 or 12");
  spec.frame_rate = camera.number("frame_rate", {1, 1000}, spec.frame_rate);
  spec.exposure = camera.number("exposure", {1e-6, 1}, spec.exposure);
  if (spec.exposure > 1 / spec.frame_rate) camera.fail_key("exposure", "longer than one frame period");
  spec.sensitivity = camera.number("sensitivity", {1e-6, 1e6}, spec.sensitivity);
  spec.full_well = camera.number("full_well", {1, 1e7}, spec.full_well);
  spec.read_noise = camera.number("read_noise", {0, 1e4}, spec.read_noise);
  spec.black_level = camera.number("black_level", {0, 0.5}, spec.black_level);
  spec.noise = camera.boolean("noise", spec.noise);
  spec.line_time_ns = read_rolling_shutter(camera, spec.intrinsics.height, spec.frame_rate);
  return spec;
}

TrajectorySpec read_trajectory(YamlMap& map) {
  TrajectorySpec spec;
  const std::string type = map.text("type");
  if (type == "static") {
    spec.kind = TrajectoryKind::static_pose;
    spec.pose = map.vector3("pose", kWorldCoordinate);
  } else if (type == "waypoints") {
    spec.kind = TrajectoryKind::waypoints;
    spec.points = points2(map, "points");
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
    spec.area = rectangle(map, "area");
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

Eigen::Vector3d unit(YamlMap& map, const std::string& key) {
  const Eigen::Vector3d v = map.vector3(key, kDirection);
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
  map.for_each_item("types", [&](YamlMap& item) {
    LedType type;
    type.name = item.text("name");
    type.intensity = item.number("intensity", kIntensity, type.intensity);
    type.half_angle = item.number("half_angle", {1e-3, kPi / 2 - 1e-3}, type.half_angle);
    ring.types.push_back(type);
  });
  if (ring.types.empty()) map.fail_key("types", "expected at least one LED type");
  map.for_each_item("leds", [&](YamlMap& item) {
    RingLed led;
    led.type = led_type_index(item, ring);
    led.position = item.vector3("position", kRigOffset);
    if (item.has("axis")) {
      led.axis = unit(item, "axis");
    } else {
      const double tilt = item.number("tilt", {0, kPi / 2}, 0);
      const double azimuth = item.number("azimuth", kAngle, std::atan2(led.position.y(), led.position.x()));
      led.axis = tilted_axis(tilt, azimuth);
    }
    ring.leds.push_back(led);
  });
  map.for_each_item("rings", [&](YamlMap& item) {
    const std::size_t type = led_type_index(item, ring);
    const long long count = item.integer("count", 1, 64);
    const double radius = item.number("radius", {0, 10}, 0.02);
    const double tilt = item.number("tilt", {0, kPi / 2}, 0);
    const double phase = item.number("phase", kAngle, 0);
    const double z = item.number("z", kRigOffset, 0);
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
  retro.coefficient = map.number("coefficient", {1e-6, 1e9}, retro.coefficient);
  retro.observation_width = map.number("observation_width", {1e-6, kPi}, retro.observation_width);
  retro.entrance_limit = map.number("entrance_limit", {0.01, kPi / 2}, retro.entrance_limit);
  return retro;
}

Room read_room(YamlMap& map) {
  Room room;
  room.ceiling_height = map.number("ceiling_height", {0.1, 100});
  if (map.has("bounds")) room.bounds = rectangle(map, "bounds");
  room.ambient = map.number("ambient", kRadiance, room.ambient);
  room.ceiling_reflectance = map.number("ceiling_reflectance", kFraction, room.ceiling_reflectance);
  room.wall_reflectance = map.number("wall_reflectance", kFraction, room.wall_reflectance);
  map.for_each_item("lamps", [&](YamlMap& item) {
    Lamp lamp;
    lamp.centre = item.vector2("centre", kWorldCoordinate);
    if (item.has("radius") == item.has("size")) item.fail("give exactly one of 'radius' (a disc) and 'size' [sx, sy]");
    if (item.has("radius")) {
      lamp.radius = item.number("radius", kSize);
    } else {
      lamp.size = item.vector2("size", kSize);
    }
    lamp.radiance = item.number("radiance", kRadiance, lamp.radiance);
    room.lamps.push_back(lamp);
  });
  map.for_each_item("windows", [&](YamlMap& item) {
    Window window;
    window.corner_a = item.vector3("corner_a", kWorldCoordinate);
    window.corner_b = item.vector3("corner_b", kWorldCoordinate);
    window.radiance = item.number("radiance", kRadiance, window.radiance);
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
  map.for_each_item("clutter", [&](YamlMap& item) {
    CeilingClutter clutter;
    const std::string kind = item.text("kind");
    if (kind != "strip" && kind != "crescent") {
      item.fail_key("kind", "unknown clutter kind '" + kind + "' (expected strip or crescent)");
    }
    clutter.centre = item.vector2("centre", kWorldCoordinate);
    if (kind == "strip") {
      clutter.kind = CeilingClutter::Kind::strip;
      clutter.length = item.number("length", kStripLength);
      clutter.width = item.number("width", kStripWidth);
      clutter.yaw = item.number("yaw", kAngle);
    } else {
      clutter.kind = CeilingClutter::Kind::crescent;
      clutter.radius = item.number("radius", kCrescentRadius);
      clutter.yaw = item.number("facing", kAngle);
    }
    room.clutter.push_back(clutter);
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
  root.for_each_item("people", [&](YamlMap& item) {
    Occluder person;
    person.path = points2(item, "path");
    if (person.path.empty()) item.fail_key("path", "expected at least one point [x, y]");
    person.speed = item.number("speed", {0, 100}, person.speed);
    person.radius = item.number("radius", kSize, person.radius);
    person.height = item.number("height", kSize, person.height);
    person.reflectance = item.number("reflectance", kFraction, person.reflectance);
    people.push_back(person);
  });
  return people;
}

// The four tile corners of a wall camera's floor reference (`key` of `map`).
std::array<Eigen::Vector2d, 4> read_floor_reference(YamlMap& map, const std::string& key) {
  const std::vector<Eigen::Vector2d> corners = points2(map, key);
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
  const bool inline_calibration = camera.has("calibration");
  if (inline_calibration == camera.has("calibration_file")) {
    camera.fail("give exactly one of 'calibration' (camera_info keys inline) and 'calibration_file'");
  }
  if (inline_calibration) {
    YamlMap calibration = camera.map("calibration");
    spec.intrinsics = io::read_camera_info(calibration);
  } else {
    const std::filesystem::path file(camera.text("calibration_file"));
    spec.calibration_file = file.is_absolute() ? file : base_dir / file;
    spec.intrinsics = io::load_camera_info(spec.calibration_file);
  }
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

// kind: outside_in: `camera:` and the top-level `floor_reference:` (one camera), or `cameras:`,
// each with its own floor reference and MAVLink component ID (several; docs/outside_in.md).
void read_outside_in(YamlMap& root, const std::filesystem::path& base_dir, Scenario& scenario) {
  OutsideInSpec spec;
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
    root.for_each_item("cameras", [&](YamlMap& item) {
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
    });
    if (spec.cameras.empty()) root.fail_key("cameras", "expected at least one camera");
    if (spec.cameras.size() > kMostWallCameras) {
      root.fail_key("cameras", "at most " + std::to_string(kMostWallCameras) + " cameras");
    }
  }
  scenario.camera.intrinsics = spec.cameras.front().intrinsics;

  YamlMap robot = root.map("robot");
  YamlMap body = robot.map("body");
  spec.body_length = body.number("length", {0.05, 10});
  spec.body_width = body.number("width", {0.05, 10});
  spec.body_height = body.number("height", {0.02, 5});
  body.reject_unknown_keys();
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
  scenario.outside_in = spec;
}

Scenario read_scenario(YamlMap& root, const std::filesystem::path& base_dir) {
  Scenario scenario;
  scenario.name = root.file();
  scenario.seed = static_cast<std::uint64_t>(root.integer("seed", 0, std::numeric_limits<long long>::max(), 1));
  scenario.frames = static_cast<int>(root.integer("frames", 1, 1'000'000));
  const std::string kind = root.has("kind") ? root.text("kind") : "ceiling";
  if (kind != "ceiling" && kind != "outside_in") root.fail_key("kind", "unknown kind '" + kind + "' (expected ceiling or outside_in)");
  if (kind == "outside_in") {
    read_outside_in(root, base_dir, scenario);
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
    return scenario;
  }

  YamlMap camera = root.map("camera");
  scenario.camera = read_camera(camera, base_dir);
  camera.reject_unknown_keys();

  if (std::optional<YamlMap> robot = root.optional_map("robot")) {
    scenario.dof = robot->dof("dof");
    robot->reject_unknown_keys();
  }

  YamlMap trajectory = root.map("trajectory");
  scenario.trajectory = read_trajectory(trajectory);
  trajectory.reject_unknown_keys();

  YamlMap ring = root.map("led_ring");
  scenario.ring = read_ring(ring);
  ring.reject_unknown_keys();

  if (std::optional<YamlMap> retro = root.optional_map("retro_reflector")) {
    scenario.retro = read_retro(*retro);
    retro->reject_unknown_keys();
  }

  YamlMap room = root.map("room");
  scenario.room = read_room(room);
  room.reject_unknown_keys();

  if (std::optional<YamlMap> map = root.optional_map("map")) {
    scenario.map = io::read_marker_map(*map);
    check_on_ceiling(root, scenario.map, scenario.room.ceiling_height);
  }

  if (std::optional<YamlMap> emitters = root.optional_map("landmark_emitters")) {
    LandmarkEmitters& result = scenario.landmark_emitters;
    result.intensity = emitters->number("intensity", kIntensity, result.intensity);
    result.radius = emitters->number("radius", {1e-4, 1}, result.radius);
    result.psf_sigma = emitters->number("psf_sigma", {0, 20}, result.psf_sigma);
    emitters->reject_unknown_keys();
  }

  scenario.people = read_people(root);

  if (std::optional<YamlMap> dropped = root.optional_map("dropped_frames")) {
    // Sequence numbers of the frames the scenario renders: 0 .. frames - 1.
    for (const long long seq : dropped->integers("seqs", 0, scenario.frames - 1)) {
      scenario.dropped_frames.push_back(static_cast<std::uint64_t>(seq));
    }
    scenario.drop_probability = dropped->number("probability", {0, 0.5}, 0);
    scenario.pair_stride = static_cast<int>(dropped->integer("pair_stride", 1, 1000, 1));
    dropped->reject_unknown_keys();
  }

  if (std::optional<YamlMap> render = root.optional_map("render")) {
    scenario.supersampling = static_cast<int>(render->integer("supersampling", 1, 16, scenario.supersampling));
    scenario.motion_blur_samples = static_cast<int>(render->integer("motion_blur_samples", 1, 16, 1));
    render->reject_unknown_keys();
  }

  if (std::optional<YamlMap> metrics = root.optional_map("metrics")) {
    scenario.metrics.gross_position = metrics->number("gross_position", {1e-6, 1e4}, scenario.metrics.gross_position);
    scenario.metrics.gross_yaw = metrics->number("gross_yaw", {1e-6, kPi}, scenario.metrics.gross_yaw);
    metrics->reject_unknown_keys();
  }
  root.reject_unknown_keys();
  return scenario;
}

}  // namespace

std::vector<std::filesystem::path> referenced_files(const Scenario& scenario) {
  std::vector<std::filesystem::path> files;
  if (!scenario.camera.calibration_file.empty()) files.push_back(scenario.camera.calibration_file);
  if (scenario.outside_in) {
    for (const WallCameraSpec& camera : scenario.outside_in->cameras) {
      if (!camera.calibration_file.empty()) files.push_back(camera.calibration_file);
    }
  }
  return files;
}

Scenario load_scenario(const std::filesystem::path& path) {
  YamlMap root(io::load_yaml_file(path), path.string(), "");
  return read_scenario(root, path.parent_path());
}

Scenario parse_scenario(const std::string& yaml_text, const std::string& name, const std::filesystem::path& base_dir) {
  YamlMap root(io::parse_yaml_text(yaml_text, name), name, "");
  return read_scenario(root, base_dir);
}

}  // namespace irloc::sim
