// The truth behind the square path's eligible frames (metrics.json): a square wholly in view, and
// the share of its most hidden side, against geometry worked out by hand.

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "host_sim/render/marker_view.hpp"

namespace irloc::sim {
namespace {

// The 2 m square 2 m above a camera 0.3 m above the floor at the origin.
SquareMarker square_above() {
  SquareMarker square;
  square.name = "hall";
  square.corners = {Eigen::Vector3d(-1, -1, 2.3), Eigen::Vector3d(1, -1, 2.3), Eigen::Vector3d(1, 1, 2.3), Eigen::Vector3d(-1, 1, 2.3)};
  return square;
}

TEST(MarkerView, APersonBesideTheCameraHidesTheWedgeOfItsTangents) {
  const Eigen::Vector3d camera(0, 0, 0.3);
  Occluder person;
  person.radius = 0.25;
  person.height = 1.8;
  // 0.5 m toward side c0 -> c1 (1 m away): its tangents from the camera are 30 degrees either
  // side, so it hides 2 tan(30 deg) m of that side's 2 m and nothing of the others. The lines
  // enter it at most 2 x 0.5 m above the camera: below its 1.8 m.
  EXPECT_NEAR(most_hidden_side_fraction(camera, square_above(), {person}, {Eigen::Vector2d(0, -0.5)}),
              std::tan(std::numbers::pi / 6), 0.015);
  EXPECT_EQ(most_hidden_side_fraction(camera, square_above(), {}, {}), 0);
  // A child of 0.5 m: every line passes over (they reach 0.8 m where they enter its cylinder).
  person.height = 0.5;
  EXPECT_EQ(most_hidden_side_fraction(camera, square_above(), {person}, {Eigen::Vector2d(0, -0.5)}), 0);
}

TEST(MarkerView, ASquareIsWhollyInViewWhenAllItsTapeProjectsOntoTheSensor) {
  // Equisolid, f = 362 px, 640 x 512: the sensor reaches 2 asin(256 / 724) = 41 degrees off axis
  // at its narrowest. Under the centre the tape's outer corners are 36 degrees off; from 2 m to the
  // side the far side is 56 degrees off (r = 336 px, beyond both half sizes).
  CameraIntrinsics k;
  k.width = 640;
  k.height = 512;
  k.fx = k.fy = 362;
  k.cx = 319.5;
  k.cy = 255.5;
  k.model = LensModel::equisolid;
  const CameraModel camera(k);
  Eigen::Isometry3d mount = Eigen::Isometry3d::Identity();  // the optical axis (camera z) straight up
  mount.translation() = Eigen::Vector3d(0, 0, 0.3);
  Eigen::Isometry3d robot = Eigen::Isometry3d::Identity();
  EXPECT_TRUE(square_wholly_in_view(camera, robot, mount, square_above()));
  robot.translation().x() = 2.0;
  EXPECT_FALSE(square_wholly_in_view(camera, robot, mount, square_above()));
}

}  // namespace
}  // namespace irloc::sim
