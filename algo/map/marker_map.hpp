#pragma once
// The marker map: every landmark's place in the world frame W (docs/formats.md).
// Built at start-up; per-frame code only reads it.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace irloc {

struct DotMarker {
  int id = 0;                     // 0..4095
  Eigen::Vector3d origin;         // centre of direction dot O in W, metres
  double yaw = 0;                 // direction of the marker's x axis in the W x-y plane
  double pitch = 0.04;            // grid pitch, metres
  double radius = 0.01;           // dot radius, metres
  bool fixed = false;             // exact: defines the world frame; a survey never moves it
  // 1-sigma of (x, y, z, yaw), metres and radians, as a survey estimated it
  std::optional<Eigen::Vector4d> sigma = std::nullopt;
};

struct SquareMarker {
  std::string name;
  std::array<Eigen::Vector3d, 4> corners;  // c0..c3 in W; c0 -> c1 is the solid side
  double tape_width = 0.05;
  double dash = 0.10;
  double gap = 0.10;
};

struct LedLandmark {
  std::string name;
  Eigen::Vector3d position;
  std::optional<Eigen::Vector3d> direction;  // unit vector, when the emitter points somewhere
  std::optional<double> half_angle;          // radians, half-angle of the emission cone
};

struct MarkerMap {
  std::vector<DotMarker> dot_markers;
  std::vector<SquareMarker> square_markers;
  std::vector<LedLandmark> led_landmarks;

  const DotMarker* find_dot_marker(int id) const {
    for (const DotMarker& marker : dot_markers) {
      if (marker.id == id) return &marker;
    }
    return nullptr;
  }
};

}  // namespace irloc
