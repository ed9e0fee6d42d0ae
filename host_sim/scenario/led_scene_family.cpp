#include "host_sim/scenario/led_scene_family.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <string>

namespace irloc::sim {
namespace {

constexpr double kDegree = std::numbers::pi / 180;
constexpr int kAttempts = 10;            // pose attempts per drive
constexpr double kPairRate = 30;         // strobe pairs per second (60 frames per second)
constexpr int kStride = 6;               // strided drives keep every sixth pair: 0.2 s apart
constexpr double kMinLedSpacing = 0.12;  // metres between two LEDs of an installation
// The sensor's response at its defaults (CameraSpec): full scale per radiance x seconds, exposure.
constexpr double kSensitivity = 6, kExposure = 0.002;

class Draw {
 public:
  Draw(std::uint64_t seed, LedFamilyClass family_class, int index) {
    std::seed_seq sequence{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32),
                           static_cast<std::uint32_t>(family_class), static_cast<std::uint32_t>(index)};
    rng_.seed(sequence);
  }
  double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng_); }
  int integer(int a, int b) { return std::uniform_int_distribution<int>(a, b)(rng_); }
  bool chance(double p) { return uniform(0, 1) < p; }
  std::uint64_t bits() { return rng_(); }

 private:
  std::mt19937_64 rng_;
};

// T_B_C of a camera looking along the base's +x, image top up.
RigidTransform forward_mount(double height) {
  RigidTransform mount;
  mount.rotation << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  mount.translation = {0.1, 0, height};
  return mount;
}

// T_B_C of a camera looking up along the base's +z, image x along the base's -y.
RigidTransform upward_mount(double height) {
  RigidTransform mount;
  mount.rotation << 0, 1, 0, -1, 0, 0, 0, 0, 1;
  mount.translation = {0, 0, height};
  return mount;
}

CameraIntrinsics image_640x480() {
  CameraIntrinsics camera;
  camera.width = 640;
  camera.height = 480;
  camera.cx = 319.5;
  camera.cy = 239.5;
  return camera;
}

// A pinhole of the given horizontal field, mild barrel distortion.
CameraIntrinsics pinhole(double horizontal_field, double k1) {
  CameraIntrinsics camera = image_640x480();
  camera.fx = camera.fy = 320 / std::tan(horizontal_field / 2);
  camera.distortion = {k1, 0, 0, 0, 0};
  return camera;
}

// A fisheye whose horizontal field spans the image width.
CameraIntrinsics fisheye(LensModel model, double horizontal_field) {
  CameraIntrinsics camera = image_640x480();
  camera.model = model;
  const double half = horizontal_field / 2;
  camera.fx = camera.fy = model == LensModel::equisolid ? 320 / (2 * std::sin(half / 2)) : 320 / half;
  return camera;
}

// A direction within `max_angle` of `axis` (unit), uniform in angle and azimuth.
Eigen::Vector3d tilted(const Eigen::Vector3d& axis, double max_angle, Draw& draw) {
  const Eigen::Vector3d e1 = axis.unitOrthogonal(), e2 = axis.cross(e1);
  const double angle = draw.uniform(0, max_angle), azimuth = draw.uniform(0, 2 * std::numbers::pi);
  return (std::cos(angle) * axis + std::sin(angle) * (std::cos(azimuth) * e1 + std::sin(azimuth) * e2)).normalized();
}

// "L0", "L1", ... (appended, not concatenated: GCC 12 warns falsely on "L" + std::to_string).
std::string led_name(std::size_t index) {
  std::string name(1, 'L');
  name += std::to_string(index);
  return name;
}

bool far_from_all(const std::vector<LedLandmark>& leds, const Eigen::Vector3d& position) {
  return std::all_of(leds.begin(), leds.end(), [&](const LedLandmark& led) {
    return (led.position - position).norm() >= kMinLedSpacing;
  });
}

// Where on a wall the LEDs go: u along the wall, height z.
enum class WallLayout { spread, clustered, camera_height, high, collinear };

// `count` LED positions on the wall through `origin` along `along` (unit, horizontal), around
// `centre_u` along it, for a camera `camera_height` above the floor.
void place_on_wall(int count, WallLayout layout, const Eigen::Vector3d& origin, const Eigen::Vector3d& along,
                   double centre_u, double camera_height, Draw& draw, std::vector<LedLandmark>& leds) {
  const double width = layout == WallLayout::clustered ? draw.uniform(0.4, 1.6) : draw.uniform(1.5, 4.0);
  // collinear: a straight line across the wall, each LED a centimetre or two off it.
  const double line_z = draw.uniform(0.3, 2.2), line_slope = draw.uniform(-0.3, 0.3);
  for (int attempt = 0; static_cast<int>(leds.size()) < count && attempt < 200; ++attempt) {
    const double u = centre_u + draw.uniform(-width / 2, width / 2);
    double z = 0;
    switch (layout) {
      case WallLayout::spread: z = draw.uniform(0.2, 2.5); break;
      case WallLayout::clustered: z = draw.uniform(0.2, 0.9); break;
      case WallLayout::camera_height: z = camera_height + draw.uniform(-0.15, 0.15); break;
      case WallLayout::high: z = draw.uniform(1.8, 2.6); break;
      case WallLayout::collinear: z = line_z + line_slope * (u - centre_u) + draw.uniform(-0.02, 0.02); break;
    }
    const Eigen::Vector3d position = origin + u * along + Eigen::Vector3d(0, 0, z);
    if (!far_from_all(leds, position)) continue;
    LedLandmark led;
    led.name = led_name(leds.size());
    led.position = position;
    leds.push_back(led);
  }
}

WallLayout draw_layout(Draw& draw) {
  return static_cast<WallLayout>(draw.integer(0, 4));
}

// The map's cones along the normal, the installed ones tilted off it.
void set_cones(std::vector<LedLandmark>& leds, std::size_t from, const Eigen::Vector3d& normal, double half_angle,
               double max_axis_tilt, Draw& draw, std::vector<LedLandmark>& installed) {
  for (std::size_t k = from; k < leds.size(); ++k) {
    leds[k].direction = normal;
    leds[k].half_angle = half_angle;
    LedLandmark real = leds[k];
    real.direction = tilted(normal, max_axis_tilt, draw);
    installed.push_back(real);
  }
}

void add_clutter(LedFamilyScene& scene, const Eigen::Vector3d& wall_origin, const Eigen::Vector3d& along,
                 const Eigen::Vector3d& normal, Draw& draw) {
  auto on_wall = [&](double spread) {
    const Eigen::Vector3d up = std::abs(normal.z()) > 0.5 ? along.cross(normal) : Eigen::Vector3d::UnitZ();
    const double height = std::abs(normal.z()) > 0.5 ? draw.uniform(-spread, spread) : draw.uniform(0.2, 2.6);
    return Eigen::Vector3d(wall_origin + draw.uniform(-spread, spread) * along +
                           (std::abs(normal.z()) > 0.5 ? height * up : Eigen::Vector3d(0, 0, height)) + 0.01 * normal);
  };
  if (draw.chance(0.5)) scene.clutter.push_back({LedClutter::Kind::lamp, on_wall(3), draw.uniform(0.1, 0.4)});
  if (draw.chance(0.3)) scene.clutter.push_back({LedClutter::Kind::window, on_wall(3), draw.uniform(0.8, 1.5)});
  const int retros = draw.chance(0.4) ? draw.integer(1, 3) : 0;
  for (int k = 0; k < retros; ++k) scene.clutter.push_back({LedClutter::Kind::retro, on_wall(3), draw.uniform(0.03, 0.1)});
  if (draw.chance(0.3)) scene.clutter.push_back({LedClutter::Kind::spurious, on_wall(2), 0.0});
}

// The camera, its mount and the sensor. The scene's fields are drawn in the order of these steps
// (a scene is its seed's: the order is part of the family).
void draw_camera(Draw& draw, LedFamilyScene& scene, double camera_height) {
  const bool clustered = scene.family_class == LedFamilyClass::clustered_dof6;
  const bool ceiling = scene.family_class == LedFamilyClass::ceiling_dof3;
  if (clustered) {
    scene.camera = pinhole(2 * std::atan(320.0 / 600), -0.05);
  } else if (ceiling) {
    scene.camera = draw.chance(0.7) ? fisheye(draw.chance(0.5) ? LensModel::equisolid : LensModel::equidistant,
                                              draw.uniform(150, 190) * kDegree)
                                    : pinhole(draw.uniform(70, 90) * kDegree, draw.uniform(-0.12, 0));
  } else {
    scene.camera = draw.chance(0.2) ? fisheye(LensModel::equidistant, draw.uniform(110, 160) * kDegree)
                                    : pinhole(draw.uniform(50, 90) * kDegree, draw.uniform(-0.12, 0));
  }
  scene.mount = ceiling ? upward_mount(camera_height) : forward_mount(camera_height);
  scene.bit_depth = draw.chance(0.5) ? 8 : 12;
  scene.psf_sigma = clustered ? draw.uniform(0.5, 0.8) : draw.uniform(0.35, 1.3);
}

struct DriveExtent {
  double speed = 0;     // m/s
  double duration = 0;  // s, first to last attempt
};

// The attempt times, the yaw swing and the tilt.
DriveExtent draw_drive(Draw& draw, LedFamilyScene& scene) {
  const bool clustered = scene.family_class == LedFamilyClass::clustered_dof6;
  scene.strided = clustered || draw.chance(0.5);
  const double step = scene.strided ? kStride / kPairRate : 1 / kPairRate;
  for (int k = 0; k < kAttempts; ++k) scene.attempt_times.push_back(k * step);
  DriveExtent drive;
  drive.duration = scene.attempt_times.back();
  drive.speed = clustered ? draw.uniform(0.1, 0.5) : draw.uniform(0, 1.0);
  const double yaw_rate = clustered ? draw.uniform(0, 20) * kDegree : draw.uniform(0, 90) * kDegree;
  scene.swing_period = draw.uniform(1.5, 4.0);
  scene.yaw_swing = std::min(yaw_rate * scene.swing_period / (2 * std::numbers::pi), 30 * kDegree);
  if (scene.dof == Dof::full6) {
    const double max_tilt = 5 * kDegree;
    scene.roll_amplitude = draw.uniform(0, max_tilt);
    scene.pitch_amplitude = draw.uniform(0, max_tilt);
    scene.tilt_period = draw.uniform(1.0, 3.0);
  }
  scene.start.z() = scene.dof == Dof::planar3 ? 0 : draw.uniform(-0.1, 0.1);
  return drive;
}

struct LedKind {
  double half_angle = 0;  // of the emission cones, rad
  double axis_tilt = 0;   // the most a cone's axis leans off the wall's normal, rad
  int count = 0;          // LEDs installed
};

LedKind draw_led_kind(Draw& draw, const LedFamilyScene& scene) {
  const bool clustered = scene.family_class == LedFamilyClass::clustered_dof6;
  LedKind kind;
  kind.half_angle = clustered ? 30 * kDegree : draw.uniform(15, 80) * kDegree;
  kind.axis_tilt = clustered ? 5 * kDegree : 15 * kDegree;
  const int min_count = scene.dof == Dof::full6 ? 3 : 2;
  kind.count = clustered ? draw.integer(4, 6) : draw.integer(min_count, 8);
  return kind;
}

// LEDs on a ceiling over the middle of the drive, and its clutter.
void install_on_ceiling(Draw& draw, LedFamilyScene& scene, const LedKind& kind, const DriveExtent& drive) {
  const double ceiling_height = draw.uniform(2.2, 3.5);
  const double heading = draw.uniform(-std::numbers::pi, std::numbers::pi);
  scene.velocity = drive.speed * Eigen::Vector2d(std::cos(heading), std::sin(heading));
  scene.yaw0 = draw.uniform(-std::numbers::pi, std::numbers::pi);
  const Eigen::Vector3d middle(scene.velocity.x() * drive.duration / 2, scene.velocity.y() * drive.duration / 2,
                               ceiling_height);
  const double extent = draw.uniform(1.0, 3.0);
  for (int attempt = 0; static_cast<int>(scene.map.led_landmarks.size()) < kind.count && attempt < 200; ++attempt) {
    const Eigen::Vector3d position = middle + Eigen::Vector3d(draw.uniform(-extent, extent),
                                                              draw.uniform(-extent, extent), 0);
    if (!far_from_all(scene.map.led_landmarks, position)) continue;
    LedLandmark led;
    led.name = led_name(scene.map.led_landmarks.size());
    led.position = position;
    scene.map.led_landmarks.push_back(led);
  }
  set_cones(scene.map.led_landmarks, 0, -Eigen::Vector3d::UnitZ(), kind.half_angle, kind.axis_tilt, draw, scene.leds);
  add_clutter(scene, middle, Eigen::Vector3d::UnitX(), -Eigen::Vector3d::UnitZ(), draw);
}

// LEDs on the wall ahead (and a side wall for two_walls_dof3), and their clutter. The robot
// starts at the origin; the wall ahead is x = distance, its normal -x. Returns the nearest the
// robot comes to the wall ahead.
double install_on_walls(Draw& draw, LedFamilyScene& scene, const LedKind& kind, const DriveExtent& drive,
                        double camera_height) {
  const bool clustered = scene.family_class == LedFamilyClass::clustered_dof6;
  const double nearest_distance = 1.5;
  const double travel = drive.speed * drive.duration;
  const double min_start = nearest_distance + travel;
  const double distance = clustered ? draw.uniform(4.2, 5.0) : draw.uniform(min_start, std::max(min_start, 8.0));
  const double approach = draw.uniform(-45, 45) * kDegree;
  scene.velocity = drive.speed * Eigen::Vector2d(std::cos(approach), std::sin(approach));
  const Eigen::Vector3d front(distance, 0, 0), front_along = Eigen::Vector3d::UnitY();
  if (scene.family_class == LedFamilyClass::two_walls_dof3) {
    // A corner: the front wall and a side wall at y = side; the robot looks into the corner.
    const double side = draw.uniform(1.5, 4.0) * (draw.chance(0.5) ? 1 : -1);
    scene.yaw0 = std::atan2(side, distance) * draw.uniform(0.5, 1.0);
    const int on_front = draw.integer(1, kind.count - 1);
    place_on_wall(on_front, draw_layout(draw), front, front_along, side / 2, camera_height, draw,
                  scene.map.led_landmarks);
    set_cones(scene.map.led_landmarks, 0, -Eigen::Vector3d::UnitX(), kind.half_angle, kind.axis_tilt, draw, scene.leds);
    const std::size_t first_side = scene.map.led_landmarks.size();
    const Eigen::Vector3d side_origin(0, side, 0);
    place_on_wall(kind.count, draw_layout(draw), side_origin, Eigen::Vector3d::UnitX(), distance * 0.6, camera_height,
                  draw, scene.map.led_landmarks);
    set_cones(scene.map.led_landmarks, first_side, Eigen::Vector3d(0, side > 0 ? -1 : 1, 0), kind.half_angle,
              kind.axis_tilt, draw, scene.leds);
  } else {
    scene.yaw0 = draw.uniform(-20, 20) * kDegree;
    place_on_wall(kind.count, clustered ? WallLayout::clustered : draw_layout(draw), front, front_along,
                  draw.uniform(-0.5, 0.5), camera_height, draw, scene.map.led_landmarks);
    set_cones(scene.map.led_landmarks, 0, -Eigen::Vector3d::UnitX(), kind.half_angle, kind.axis_tilt, draw, scene.leds);
  }
  add_clutter(scene, front, front_along, -Eigen::Vector3d::UnitX(), draw);
  if (clustered && std::none_of(scene.clutter.begin(), scene.clutter.end(),
                                [](const LedClutter& c) { return c.kind == LedClutter::Kind::lamp; })) {
    scene.clutter.push_back({LedClutter::Kind::lamp, front + Eigen::Vector3d(-0.01, draw.uniform(-2, 2), 2.0),
                             draw.uniform(0.1, 0.3)});
  }
  return distance - travel;
}

// Brightness: an LED on its axis at the nearest distance of the drive peaks at 0.6 to 2 x full
// scale (a near LED saturates, a far or off-axis one is dimmer, as in a real room).
void draw_led_intensity(Draw& draw, LedFamilyScene& scene, double nearest_distance) {
  const double peak = draw.uniform(0.6, 2.0);
  // The brightest pixel's share of a spot (at most all of it, for spots smaller than a pixel).
  const double spot_peak_share = std::min(0.8, 1 / (2 * std::numbers::pi * scene.psf_sigma * scene.psf_sigma));
  const double range = scene.family_class == LedFamilyClass::ceiling_dof3 ? 2.0 : std::max(nearest_distance, 1.5);
  scene.led_intensity = peak * range * range / (scene.camera.fx * scene.camera.fy * spot_peak_share * kSensitivity * kExposure);
}

}  // namespace

std::string_view to_string(LedFamilyClass family_class) {
  switch (family_class) {
    case LedFamilyClass::wall_dof6: return "wall, dof 6";
    case LedFamilyClass::wall_dof4: return "wall, dof 4";
    case LedFamilyClass::two_walls_dof3: return "two walls, dof 3";
    case LedFamilyClass::ceiling_dof3: return "ceiling, dof 3";
    case LedFamilyClass::clustered_dof6: return "cluster, narrow cones, strided, dof 6";
  }
  return "?";
}

RigidTransform LedFamilyScene::world_from_base(double t) const {
  const double phase = 2 * std::numbers::pi * t;
  RigidTransform pose;
  pose.rotation = rotation_from_rpy(roll_amplitude * std::sin(phase / tilt_period),
                                    pitch_amplitude * std::cos(1.3 * phase / tilt_period),
                                    yaw0 + yaw_swing * std::sin(phase / swing_period));
  pose.translation = start + Eigen::Vector3d(velocity.x() * t, velocity.y() * t, 0);
  return pose;
}

LedFamilyScene draw_led_family_scene(std::uint64_t seed, LedFamilyClass family_class, int index) {
  Draw draw(seed, family_class, index);
  LedFamilyScene scene;
  scene.family_class = family_class;
  scene.seed = draw.bits();
  scene.dof = family_class == LedFamilyClass::wall_dof6 || family_class == LedFamilyClass::clustered_dof6 ? Dof::full6
              : family_class == LedFamilyClass::wall_dof4 ? Dof::height4
                                                          : Dof::planar3;
  const double camera_height = draw.uniform(0.2, 0.6);
  draw_camera(draw, scene, camera_height);
  const DriveExtent drive = draw_drive(draw, scene);
  const LedKind kind = draw_led_kind(draw, scene);
  double nearest_distance = 1.5;
  if (family_class == LedFamilyClass::ceiling_dof3) {
    install_on_ceiling(draw, scene, kind, drive);
  } else {
    nearest_distance = install_on_walls(draw, scene, kind, drive, camera_height);
  }
  scene.dead.assign(scene.leds.size(), false);
  if (scene.leds.size() > 2 && draw.chance(0.2)) {
    scene.dead[static_cast<std::size_t>(draw.integer(0, static_cast<int>(scene.leds.size()) - 1))] = true;
  }
  draw_led_intensity(draw, scene, nearest_distance);
  return scene;
}

}  // namespace irloc::sim
