#include "host_sim/scenario/scenario.hpp"

#include <cmath>
#include <limits>
#include <optional>
#include <numbers>

#include "io/config/config_file.hpp"
#include "io/config/map_file.hpp"
#include "io/config/yaml_reader.hpp"
#include "host_sim/scenario/outside_in_scenario.hpp"
#include "host_sim/scenario/scenario_fields.hpp"

namespace irloc::sim {
namespace {

using io::YamlMap;

constexpr double kPi = std::numbers::pi;
constexpr double kOnCeilingTolerance = 1e-3;  // metres

CameraSpec read_camera(YamlMap& camera, const std::filesystem::path& base_dir) {
  CameraSpec spec;
  spec.intrinsics = read_camera_calibration(camera, base_dir, spec.calibration_file);
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
  if (map.has("bounds")) room.bounds = read_rectangle(map, "bounds");
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

// The optional sections of a ceiling scenario that set how it is rendered and scored: the
// landmark emitters, the people, dropped frames, supersampling and motion blur, the metrics.
void read_render_settings(YamlMap& root, Scenario& scenario) {
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
}

Scenario read_scenario(YamlMap& root, const std::filesystem::path& base_dir) {
  Scenario scenario;
  scenario.name = root.file();
  scenario.seed = static_cast<std::uint64_t>(root.integer("seed", 0, std::numeric_limits<long long>::max(), 1));
  scenario.frames = static_cast<int>(root.integer("frames", 1, 1'000'000));
  const std::string kind = root.has("kind") ? root.text("kind") : "ceiling";
  if (kind != "ceiling" && kind != "outside_in") root.fail_key("kind", "unknown kind '" + kind + "' (expected ceiling or outside_in)");
  if (kind == "outside_in") {
    read_outside_in_scenario(root, base_dir, scenario);
    return scenario;
  }

  YamlMap camera = root.map("camera");
  scenario.camera = read_camera(camera, base_dir);
  camera.reject_unknown_keys();

  if (std::optional<YamlMap> robot = root.optional_map("robot")) {
    scenario.dof = robot->dof("dof");
    scenario.max_side_speed = io::read_side_speed(*robot);
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

  read_render_settings(root, scenario);
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
