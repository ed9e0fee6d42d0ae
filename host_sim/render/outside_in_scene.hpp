#pragma once
// What an outside-in frame shows (the box robot, a person, the lamp, the sun patch) and the truth
// the renderer measures while drawing it.
#include <optional>

#include <Eigen/Core>

#include "algo/markers/outside_in/box_silhouette.hpp"

namespace irloc::sim {

// The floor is laid with square tiles of this side (m), their corners on multiples of it.
inline constexpr double kFloorTile = 0.5;

struct Person {
  Eigen::Vector2d position;
  double radius = 0.22, height = 1.75;
};

// How the box robot looks: each face's shade (grey level of its radiance at lamp 1 and exposure 1;
// the floor's tiles are 150 and 175), and a strip across the front (+x) face between two fractions
// of the box's height, in its own shade (none where they are equal). The default is a dark robot,
// its top lit most, a lighter bumper band in front.
struct RobotLook {
  double top = 70, front = 55, back = 40, sides = 48;
  double strip_shade = 0;
  double strip_from = 0, strip_to = 0;  // of the height, 0 (floor) to 1 (top); from <= to
};

struct SceneState {
  std::optional<outside_in::FloorPose> robot;
  std::optional<Person> person;
  double lamp = 1.0;                        // global illumination factor
  Eigen::Vector2d sun{3.0, 1.2};            // centre of the sun patch on the floor
  double sun_strength = 0.5;                // added irradiance at its centre, relative
};

struct FrameTruth {
  bool robot_whole_in_view = false;  // every corner of the box inside the image
  int robot_pixels = 0;              // where the box would be seen without the person
  int robot_hidden_pixels = 0;       // of those, behind the person
  double hidden_fraction() const { return robot_pixels ? double(robot_hidden_pixels) / robot_pixels : 0; }
};

}  // namespace irloc::sim
