#pragma once
// A family of LED landmark installations and drives drawn from a seed (issue 26): what users
// install varies, so the LED source is measured on many scenes, not one. Each scene is one class's
// draw: 2 to 8 LEDs on one wall, two walls or the ceiling; spread or clustered, near the camera's
// height or high, or nearly collinear; emission half-angles 15 to 80 degrees with axes tilted up
// to 15 degrees off the wall's normal (the map says the normal); LED spots of 1 to 4 px; distances
// 1.5 to 8 m; pinhole 50 to 90 degrees or fisheye lenses; 8- or 16-bit frames; speeds up to 1 m/s
// and yaw rates up to 90 deg/s; tilt up to 5 degrees under dof 6; consecutive or strided pairs;
// lamps, windows, retro-reflective clutter, a dead LED, a spurious bright point.
//
// Plain data; led_family_frames.hpp renders its strobe pairs. The same (seed, class, index) always
// draws the same scene.

#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "algo/geometry/camera_intrinsics.hpp"
#include "algo/geometry/pose.hpp"
#include "algo/geometry/rigid_transform.hpp"
#include "algo/map/marker_map.hpp"

namespace irloc::sim {

enum class LedFamilyClass {
  wall_dof6,        // one wall ahead, rolling and pitching robot
  wall_dof4,        // one wall ahead, level robot, height free
  two_walls_dof3,   // LEDs on two walls of a corner, level robot
  ceiling_dof3,     // LEDs on the ceiling, upward camera
  clustered_dof6,   // the setting: a small cluster on one wall, narrow cones, strided pairs
};
inline constexpr std::array kLedFamilyClasses = {LedFamilyClass::wall_dof6, LedFamilyClass::wall_dof4,
                                                 LedFamilyClass::two_walls_dof3, LedFamilyClass::ceiling_dof3,
                                                 LedFamilyClass::clustered_dof6};
std::string_view to_string(LedFamilyClass family_class);

// Something bright that is not a mapped LED, fixed in the world.
struct LedClutter {
  enum class Kind {
    lamp,       // a large patch bright in both frames
    window,     // a larger one
    retro,      // a retro-reflector: bright only in the LED-on frame
    spurious,   // a small always-on point (an appliance's indicator): looks like an LED
  };
  Kind kind = Kind::lamp;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // W, its centre
  double size = 0;                                     // metres across
};

struct LedFamilyScene {
  LedFamilyClass family_class = LedFamilyClass::wall_dof6;
  std::uint64_t seed = 0;        // the sensor noise's seed
  CameraIntrinsics camera;
  RigidTransform mount;          // T_B_C
  Dof dof = Dof::full6;
  MarkerMap map;                 // what the robot is told: axes along the normals
  std::vector<LedLandmark> leds; // what is installed, same order as map.led_landmarks: true axes
  std::vector<bool> dead;        // per LED: mapped, but dark
  std::vector<LedClutter> clutter;
  double led_intensity = 0.01;   // W/sr on an LED's axis
  double psf_sigma = 0.7;        // pixels
  int bit_depth = 8;
  double frame_rate = 60;        // frames per second; a pair is an LED-on frame and the next one
  // The drive: one pose attempt at each time, seconds (strided pairs: larger steps).
  std::vector<double> attempt_times;
  bool strided = false;
  // Motion: T_W_B(t) from these (trajectory below).
  Eigen::Vector3d start = Eigen::Vector3d::Zero();  // x, y, z of the base at t = 0
  Eigen::Vector2d velocity = Eigen::Vector2d::Zero();  // m/s, W
  double yaw0 = 0, yaw_swing = 0, swing_period = 1;    // yaw(t) = yaw0 + yaw_swing sin(2 pi t / period)
  double roll_amplitude = 0, pitch_amplitude = 0, tilt_period = 1;

  RigidTransform world_from_base(double t) const;
};

// Scene `index` of class `family_class` of the family drawn from `seed`.
LedFamilyScene draw_led_family_scene(std::uint64_t seed, LedFamilyClass family_class, int index);

}  // namespace irloc::sim
