// Camera models against OpenCV: cv::projectPoints (plumb_bob) and cv::fisheye::projectPoints
// (equidistant) on random points in front of the camera, to 1e-6 px.

#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>

#include "algo/geometry/camera_model.hpp"
#include "tests/geometry/calibrations.hpp"

namespace irloc {
namespace {

// Random points in front of the camera, within a cone of the given half-angle.
std::vector<cv::Point3d> random_points(double half_angle, int count) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<cv::Point3d> points;
  for (int i = 0; i < count; ++i) {
    const double theta = half_angle * std::sqrt(unit(rng)), phi = 2 * M_PI * unit(rng);
    const double distance = 0.5 + 5 * unit(rng);
    points.emplace_back(distance * std::sin(theta) * std::cos(phi), distance * std::sin(theta) * std::sin(phi),
                        distance * std::cos(theta));
  }
  return points;
}

cv::Matx33d camera_matrix(const CameraIntrinsics& k) {
  return cv::Matx33d(k.fx, 0, k.cx, 0, k.fy, k.cy, 0, 0, 1);
}

void expect_agreement(const CameraModel& camera, const std::vector<cv::Point3d>& points,
                      const std::vector<cv::Point2d>& expected) {
  ASSERT_EQ(points.size(), expected.size());
  double worst = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    Eigen::Vector2d pixel;
    ASSERT_TRUE(camera.project(Eigen::Vector3d(points[i].x, points[i].y, points[i].z), pixel));
    worst = std::max(worst, std::hypot(pixel.x() - expected[i].x, pixel.y() - expected[i].y));
  }
  EXPECT_LT(worst, 1e-6);
}

TEST(CameraModelOracle, PlumbBobAgreesWithProjectPoints) {
  for (const CameraIntrinsics& k : {test::plumb_bob_lens(), test::wide_plumb_bob_lens()}) {
    const CameraModel camera(k);
    const auto points = random_points(0.95 * camera.max_field_angle(), 5000);
    std::vector<cv::Point2d> expected;
    const std::vector<double> distortion(k.distortion.begin(), k.distortion.end());
    cv::projectPoints(points, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), camera_matrix(k), distortion,
                      expected);
    expect_agreement(camera, points, expected);
  }
}

TEST(CameraModelOracle, EquidistantAgreesWithFisheyeProjectPoints) {
  const CameraIntrinsics k = test::equidistant_lens();
  const CameraModel camera(k);
  // OpenCV's fisheye divides by z, so it only covers the front half-space.
  const auto points = random_points(1.5, 5000);
  std::vector<cv::Point2d> expected;
  const cv::Vec4d distortion(k.distortion[0], k.distortion[1], k.distortion[2], k.distortion[3]);
  cv::fisheye::projectPoints(points, expected, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), camera_matrix(k),
                             distortion);
  expect_agreement(camera, points, expected);
}

// OpenCV's undistortPoints is an approximate iteration, so compare loosely: the oracle for
// unproject is the round trip in geometry_test; this checks the convention (pixel origin, axes).
TEST(CameraModelOracle, PlumbBobUnprojectAgreesWithUndistortPoints) {
  const CameraIntrinsics k = test::plumb_bob_lens();
  const CameraModel camera(k);
  const std::vector<cv::Point2d> pixels = {{0, 0}, {639, 0}, {0, 479}, {639, 479}, {320, 240}, {100, 400}};
  std::vector<cv::Point2d> normalized;
  const std::vector<double> distortion(k.distortion.begin(), k.distortion.end());
  cv::undistortPoints(pixels, normalized, camera_matrix(k), distortion, cv::noArray(),
                      cv::noArray(), cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 200, 1e-14));
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    Eigen::Vector3d bearing;
    ASSERT_TRUE(camera.unproject(Eigen::Vector2d(pixels[i].x, pixels[i].y), bearing));
    EXPECT_NEAR(bearing.x() / bearing.z(), normalized[i].x, 1e-6);
    EXPECT_NEAR(bearing.y() / bearing.z(), normalized[i].y, 1e-6);
  }
}

}  // namespace
}  // namespace irloc
