// The pose at a frame's t_ns under a rolling shutter, against an independent projection: the
// default board's camera (820x616, 37.8 us a row) on a robot driving an arc at 1 m/s and 90 deg/s
// under three markers' dots; each dot's pixel is OpenCV's projectPoints from the camera at the time
// of the row it lands in (row v exposed v * line_time after t_ns, conventions.md), found row by
// row, the robot's pose at that time integrated here in closed form (not rolling_shutter.hpp's
// arc). From those pixels the correction's two paths give the pose at t_ns: the mapped points
// moved by a known motion (a track) and refined, and the pose and motion fitted together (no
// track); a plain fit, which takes the frame for a global shutter's, is centimetres off.

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "algo/geometry/camera_model.hpp"
#include "algo/geometry/pose.hpp"
#include "algo/geometry/pose_refinement.hpp"
#include "algo/source/pose_motion_fit.hpp"
#include "algo/source/rolling_shutter.hpp"
#include "tests/algo/board_camera.hpp"
#include "tests/support/opencv_projection.hpp"

namespace irloc {
namespace {

constexpr double kLineTime = 37.8e-6;  // s
constexpr std::int64_t kLineTimeNs = 37'800;

// The robot at t_ns and its constant motion: velocity (vx, vy) in its heading frame, yaw rate w.
struct Drive {
  double x0, y0, yaw0, vx, vy, w;

  // T_W_B t seconds later: yaw0 + w t, and the position integrated in closed form,
  // integral of Rz(yaw0 + w s) (vx, vy) ds from 0 to t.
  Eigen::Isometry3d world_from_base(double t) const {
    const double a0 = yaw0, a1 = yaw0 + w * t;
    const double sin_integral = (std::cos(a0) - std::cos(a1)) / w;  // integral of sin(a)
    const double cos_integral = (std::sin(a1) - std::sin(a0)) / w;  // integral of cos(a)
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = Eigen::AngleAxisd(a1, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    pose.translation() = Eigen::Vector3d(x0 + vx * cos_integral - vy * sin_integral, y0 + vx * sin_integral + vy * cos_integral, 0);
    return pose;
  }
};

Eigen::Isometry3d mount() {
  const RigidTransform m = test::up_mount();
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = m.rotation;
  t.translation() = m.translation;
  return t;
}

struct Error {
  double position, yaw;
};

Error error_of(const RigidTransform& found, const Drive& drive) {
  return {std::hypot(found.translation.x() - drive.x0, found.translation.y() - drive.y0),
          std::abs(wrap_angle(heading(found) - drive.yaw0))};
}

class RollingShutterOracle : public ::testing::Test {
 protected:
  void SetUp() override {
    // Three markers' 3x3 dots (8 cm apart) on the 2.6 m ceiling, ahead, overhead and behind:
    // seen near the image's top, middle and bottom rows.
    const Eigen::Matrix2d heading = Eigen::Rotation2Dd(drive_.yaw0).toRotationMatrix();
    const Eigen::Vector2d robot(drive_.x0, drive_.y0);
    for (const Eigen::Vector2d& offset : {Eigen::Vector2d(0.75, 0.45), Eigen::Vector2d(0.05, -0.35), Eigen::Vector2d(-0.7, 0.4)}) {
      const Eigen::Vector2d centre = robot + heading * offset;
      for (int i = -1; i <= 1; ++i) {
        for (int j = -1; j <= 1; ++j) {
          world_.emplace_back(centre.x() + 0.08 * i, centre.y() + 0.08 * j, 2.6);
          pixels_.push_back(test::opencv_rolling_projection(world_.back(), camera_.intrinsics(), kLineTime,
                                                            [&](double t) { return drive_.world_from_base(t) * mount(); }));
          ASSERT_TRUE(pixels_.back().allFinite());
          row_times_.push_back(row_time(pixels_.back(), kLineTimeNs));
        }
      }
    }
    options_.loss = RobustLoss::none;
    // A plain fit: the frame taken for a global shutter's.
    plain_ = refine_pose(world_, pixels_, camera_, test::up_mount(), start_, options_);
    ASSERT_TRUE(plain_.ok);
  }

  const Drive drive_{0.4, -0.3, 0.6, 1.0, 0.0, 1.5708};  // 1 m/s, 90 deg/s
  const CameraModel camera_{test::board_camera()};
  // Where a search would start: 3 cm and 2 degrees off.
  const RigidTransform start_{rotation_from_rpy(0, 0, 0.6 + 0.035), Eigen::Vector3d(0.42, -0.28, 0)};
  RefinementOptions options_;
  std::vector<Eigen::Vector3d> world_;
  std::vector<Eigen::Vector2d> pixels_;
  std::vector<double> row_times_;
  PoseFit plain_;
};

TEST_F(RollingShutterOracle, APlainFitIsOffByCentimetres) {
  const Error plain = error_of(plain_.world_from_base, drive_);
  EXPECT_GT(plain.position, 0.005);
}

TEST_F(RollingShutterOracle, TheMappedPointsMovedByTheTracksMotionGiveThePoseAtTheFrameTime) {
  const FrameMotion motion{{drive_.vx, drive_.vy, 0}, drive_.w};
  RigidTransform pose = plain_.world_from_base;
  for (int pass = 0; pass < 3; ++pass) {  // the moved points depend on the pose through the turn
    std::vector<Eigen::Vector3d> moved;
    for (std::size_t k = 0; k < world_.size(); ++k) moved.push_back(point_seen_at_frame_time(world_[k], row_times_[k], motion, pose));
    const PoseFit fit = refine_pose(moved, pixels_, camera_, test::up_mount(), pose, options_);
    ASSERT_TRUE(fit.ok);
    pose = fit.world_from_base;
  }
  const Error error = error_of(pose, drive_);
  EXPECT_LT(error.position, 2e-5);
  EXPECT_LT(error.yaw, 2e-5);
}

TEST_F(RollingShutterOracle, ThePoseAndTheMotionFittedTogetherGiveThePoseAtTheFrameTime) {
  const PoseMotionFit fit = fit_pose_and_motion(world_, pixels_, row_times_, camera_, test::up_mount(),
                                                plain_.world_from_base, Dof::planar3, 0.05, std::nullopt);
  ASSERT_TRUE(fit.ok);
  const Error error = error_of(fit.world_from_base, drive_);
  EXPECT_LT(error.position, 2e-5);
  EXPECT_LT(error.yaw, 2e-5);
  EXPECT_NEAR(fit.motion.velocity.x(), drive_.vx, 2e-3);
  EXPECT_NEAR(fit.motion.velocity.y(), drive_.vy, 2e-3);
  EXPECT_NEAR(fit.motion.yaw_rate, drive_.w, 2e-3);
}

}  // namespace
}  // namespace irloc
