#pragma once
// dof 6: the frame's tape points on the ceiling plane as a level camera would have mapped them,
// at a small tilt of the robot (SquareDetector reads the dash patterns there). Sized at start-up;
// level() allocates nothing.

#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "algo/geometry/pose.hpp"

namespace irloc::square {

class LevelledTape {
 public:
  // A tilt whose roll or pitch differs from the levelled one's by more than this (radians, 0.1
  // degrees) is levelled anew: a tilt difference of a few tenths of a degree can decide between two
  // hypotheses of one frame (docs/square_markers.md, "A tilting robot").
  static constexpr double kTiltAgreement = 0.00175;

  // ceiling_above_camera: the plane's height above the camera (CeilingPlaneMap), metres;
  // capacity: the most points level() is given (0: never used).
  LevelledTape(double ceiling_above_camera, std::size_t capacity);

  // A new frame: nothing levelled.
  void forget() { levelled_ = false; }
  // Levelled this frame at a tilt within kTiltAgreement of this one (roll and pitch).
  bool levelled_near(const RollPitchYaw& tilt) const;
  // points (metres on the plane, at most capacity) as the level camera at this tilt maps them.
  void level(const RollPitchYaw& tilt, std::span<const Eigen::Vector2d> points);
  std::span<const Eigen::Vector2d> points() const { return {points_.data(), count_}; }
  // One point, or a quadrilateral's corners, as the level camera at the last tilt maps them.
  Eigen::Vector2d levelled(const Eigen::Vector2d& point) const;
  std::array<Eigen::Vector2d, 4> levelled(const std::array<Eigen::Vector2d, 4>& corners) const;

 private:
  double ceiling_above_camera_;
  std::vector<Eigen::Vector2d> points_;
  std::size_t count_ = 0;
  bool levelled_ = false;
  RollPitchYaw tilt_;
  Eigen::Matrix3d level_from_base_ = Eigen::Matrix3d::Identity();
};

}  // namespace irloc::square
