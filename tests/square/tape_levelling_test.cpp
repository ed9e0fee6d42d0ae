// LevelledTape: a tape point carried to a level camera at a tilt lands where the tilted ray through
// it meets the ceiling plane (an Eigen hyperplane intersection as the oracle), and the view is
// levelled anew only for a tilt beyond kTiltAgreement of the last one.

#include <gtest/gtest.h>

#include <array>
#include <vector>

#include <Eigen/Geometry>

#include "algo/geometry/pose.hpp"
#include "algo/markers/square/tape_levelling.hpp"

namespace irloc::test {
namespace {

using namespace irloc::square;  // the source under test

constexpr double kCeiling = 2.0;  // the plane's height above the camera, metres

TEST(LevelledTape, PointsMeetTheCeilingAlongTheTiltedRay) {
  const std::vector<Eigen::Vector2d> points = {{0, 0}, {1.2, -0.4}, {-0.7, 0.9}, {0.05, 1.6}};
  const RollPitchYaw tilt{0.04, -0.03, 0};
  LevelledTape tape(kCeiling, points.size());
  tape.level(tilt, points);
  ASSERT_EQ(tape.points().size(), points.size());
  const Eigen::Matrix3d level_from_base = rotation_from_rpy(tilt.roll, tilt.pitch, 0);
  const Eigen::Hyperplane<double, 3> ceiling(Eigen::Vector3d::UnitZ(), -kCeiling);
  for (std::size_t k = 0; k < points.size(); ++k) {
    const Eigen::ParametrizedLine<double, 3> ray(Eigen::Vector3d::Zero(),
                                                 level_from_base * Eigen::Vector3d(points[k].x(), points[k].y(), kCeiling));
    const Eigen::Vector3d hit = ray.intersectionPoint(ceiling);
    EXPECT_NEAR(tape.points()[k].x(), hit.x(), 1e-12) << k;
    EXPECT_NEAR(tape.points()[k].y(), hit.y(), 1e-12) << k;
    EXPECT_NEAR(tape.levelled(points[k]).x(), hit.x(), 1e-12) << k;
  }
  // The camera's own axis moves with the tilt: about h * tan(pitch) along x, h * tan(roll) along y.
  EXPECT_GT((tape.points()[0] - points[0]).norm(), 0.05);
}

TEST(LevelledTape, LevelsAnewOnlyBeyondTheAgreement) {
  const std::vector<Eigen::Vector2d> points = {{0.3, 0.2}};
  LevelledTape tape(kCeiling, 1);
  const RollPitchYaw tilt{0.02, 0.01, 0};
  EXPECT_FALSE(tape.levelled_near(tilt));  // nothing levelled yet
  tape.level(tilt, points);
  const double within = 0.9 * LevelledTape::kTiltAgreement, beyond = 1.1 * LevelledTape::kTiltAgreement;
  EXPECT_TRUE(tape.levelled_near({tilt.roll + within, tilt.pitch - within, 1.0}));  // yaw does not count
  EXPECT_FALSE(tape.levelled_near({tilt.roll + beyond, tilt.pitch, 0}));
  EXPECT_FALSE(tape.levelled_near({tilt.roll, tilt.pitch - beyond, 0}));
  tape.forget();  // a new frame
  EXPECT_FALSE(tape.levelled_near(tilt));
}

TEST(LevelledTape, LevelAtZeroTiltKeepsThePoints) {
  const std::array<Eigen::Vector2d, 4> corners = {Eigen::Vector2d(1, 1), Eigen::Vector2d(-1, 1), Eigen::Vector2d(-1, -1),
                                                  Eigen::Vector2d(1, -1)};
  LevelledTape tape(kCeiling, 0);
  tape.level({0, 0, 0}, {});
  const std::array<Eigen::Vector2d, 4> level = tape.levelled(corners);
  for (std::size_t k = 0; k < 4; ++k) EXPECT_EQ(level[k], corners[k]) << k;
}

}  // namespace
}  // namespace irloc::test
