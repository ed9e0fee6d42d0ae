// estimate_pose under dof 6 against OpenCV: with plain least squares both minimize the same
// reprojection error. OpenCV's answer (SOLVEPNP_SQPNP, then its Levenberg-Marquardt, which stops
// at a loose tolerance) must agree with ours to 2e-5 m / rad, and never have a lower cost.

#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>

#include "algo/geometry/pose_solver.hpp"
#include "tests/geometry/calibrations.hpp"
#include "tests/geometry/ceiling_scene.hpp"

namespace irloc {
namespace {

RigidTransform from_opencv(const cv::Vec3d& rvec, const cv::Vec3d& tvec) {
  cv::Matx33d r;
  cv::Rodrigues(rvec, r);
  RigidTransform t;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) t.rotation(i, j) = r(i, j);
    t.translation(i) = tvec(i);
  }
  return t;
}

TEST(PoseSolverOracle, MatchesOpenCvSolvePnPUnderDof6) {
  const CameraIntrinsics k = test::plumb_bob_lens();
  const CameraModel camera(k);
  const cv::Matx33d matrix(k.fx, 0, k.cx, 0, k.fy, k.cy, 0, 0, 1);
  const std::vector<double> distortion(k.distortion.begin(), k.distortion.end());
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> unit(-1, 1);
  int compared = 0;
  for (int trial = 0; trial < 50; ++trial) {
    // Two dot markers: 32 well-spread points, so that the minimum is unique.
    auto points = test::dot_grid(0.4 * unit(rng), 0.4 * unit(rng), unit(rng));
    for (const auto& p : test::dot_grid(0.8 + 0.2 * unit(rng), -0.5, unit(rng))) points.push_back(p);
    const RigidTransform truth{rotation_from_rpy(0.05 * unit(rng), 0.05 * unit(rng), 3 * unit(rng)),
                               Eigen::Vector3d(0.3 * unit(rng), 0.3 * unit(rng), 0.1 * unit(rng))};
    std::vector<Eigen::Vector2d> pixels;
    if (!test::observe(points, camera, truth, test::up_mount(), 0.5, rng, pixels)) continue;
    RefinementOptions options;
    options.dof = Dof::full6;
    options.loss = RobustLoss::none;
    const PoseFit fit = estimate_pose(points, pixels, camera, test::up_mount(), options);
    ASSERT_TRUE(fit.ok);
    const RigidTransform ours = (fit.world_from_base * test::up_mount()).inverse();  // T_C_W

    std::vector<cv::Point3d> object;
    std::vector<cv::Point2d> image;
    for (std::size_t i = 0; i < points.size(); ++i) {
      object.emplace_back(points[i].x(), points[i].y(), points[i].z());
      image.emplace_back(pixels[i].x(), pixels[i].y());
    }
    cv::Vec3d rvec, tvec;
    ASSERT_TRUE(cv::solvePnP(object, image, matrix, distortion, rvec, tvec, false, cv::SOLVEPNP_SQPNP));
    ASSERT_TRUE(cv::solvePnP(object, image, matrix, distortion, rvec, tvec, true, cv::SOLVEPNP_ITERATIVE));
    const RigidTransform theirs = from_opencv(rvec, tvec);
    EXPECT_LT((ours.translation - theirs.translation).norm(), 2e-5);
    EXPECT_LT(test::rotation_error(ours, theirs), 2e-5);
    auto squared_error_sum = [&](const RigidTransform& camera_from_world) {
      double sum = 0;
      for (std::size_t i = 0; i < points.size(); ++i) {
        Eigen::Vector2d pixel;
        EXPECT_TRUE(camera.project(camera_from_world * points[i], pixel));
        sum += (pixel - pixels[i]).squaredNorm();
      }
      return sum;
    };
    EXPECT_LE(squared_error_sum(ours), squared_error_sum(theirs) * (1 + 1e-9));
    ++compared;
  }
  EXPECT_GT(compared, 30);
}

}  // namespace
}  // namespace irloc
