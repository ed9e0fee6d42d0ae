// solve_planar_pnp against OpenCV: solvePnP(SOLVEPNP_IPPE) on the same pixels and lens, then
// solvePnPRefineLM. Both minimize the same reprojection error; ours must agree and never be
// worse. Problems: a floor tile's four corners (the outside-in floor reference) and 3 x 3 grids.
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>

#include "algo/geometry/planar_pnp.hpp"
#include "tests/geometry/calibrations.hpp"
#include "tests/geometry/planar_scene.hpp"

namespace irloc {
namespace {

TEST(PlanarPnpOracle, MatchesOpenCvIppeRefined) {
  const CameraIntrinsics k = test::plumb_bob_lens();
  const CameraModel camera(k);
  const cv::Matx33d matrix(k.fx, 0, k.cx, 0, k.fy, k.cy, 0, 0, 1);
  const std::vector<double> distortion(k.distortion.begin(), k.distortion.end());
  std::mt19937 rng(7);
  int compared = 0;
  for (int trial = 0; trial < 200; ++trial) {
    test::PlanarProblem problem;
    const int side = trial % 2 ? 2 : 3;
    if (!test::make_planar_problem(camera, side, side, 0.3 * (4 - side), 0.3, rng, problem)) continue;
    const PlanarPose ours = solve_planar_pnp(problem.plane, problem.pixels, camera);
    ASSERT_TRUE(ours.ok);
    std::vector<cv::Point3d> object;
    std::vector<cv::Point2d> image;
    for (std::size_t i = 0; i < problem.plane.size(); ++i) {
      object.emplace_back(problem.plane[i].x(), problem.plane[i].y(), 0);
      image.emplace_back(problem.pixels[i].x(), problem.pixels[i].y());
    }
    cv::Mat rvec, tvec;
    ASSERT_TRUE(cv::solvePnP(object, image, matrix, distortion, rvec, tvec, false, cv::SOLVEPNP_IPPE));
    cv::solvePnPRefineLM(object, image, matrix, distortion, rvec, tvec,
                         cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 100, 1e-12));
    cv::Matx33d r;
    cv::Rodrigues(rvec, r);
    RigidTransform theirs;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) theirs.rotation(i, j) = r(i, j);
      theirs.translation(i) = tvec.at<double>(i);
    }
    double their_sum = 0;
    for (std::size_t i = 0; i < problem.plane.size(); ++i) {
      Eigen::Vector2d pixel;
      ASSERT_TRUE(camera.project(theirs * Eigen::Vector3d(problem.plane[i].x(), problem.plane[i].y(), 0), pixel));
      their_sum += (pixel - problem.pixels[i]).squaredNorm();
    }
    EXPECT_LE(ours.sum_squares_px2, their_sum * (1 + 1e-6) + 1e-12) << trial;
    // The same minimum unless OpenCV's IPPE chose the other of the two candidates (a worse one).
    if (their_sum <= ours.sum_squares_px2 * (1 + 1e-3) + 1e-9) {
      EXPECT_LT(test::centre_error(ours.camera_from_plane, theirs), 1e-4) << trial;
      EXPECT_LT(test::rotation_error(ours.camera_from_plane, theirs), 1e-5) << trial;
      ++compared;
    }
  }
  EXPECT_GT(compared, 100);
}

}  // namespace
}  // namespace irloc
