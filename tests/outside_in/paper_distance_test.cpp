// The paper's IBDMS and PLDMS (tests/outside_in/paper_distance_reference.hpp) against the wall
// camera's exact projection, then the paper's way of placing the robot (the floor point below the
// blob's centroid, through IBDMS and PLDMS) against the box fit on rendered frames.
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "algo/markers/outside_in/box_silhouette.hpp"
#include "tests/outside_in/outside_in_drive.hpp"
#include "tests/outside_in/paper_distance_reference.hpp"

namespace irloc::test {
namespace {

using namespace irloc::outside_in;  // the source under test

constexpr double kTile = 0.5;  // the floor's tiles: the paper's known rectangle

// The paper's locating of a floor pixel: two tile edges running away from the camera (world
// y = +-kTile / 2) give P and Q on the pixel's row; IBDMS gives the row's depth, PLDMS the offset.
Eigen::Vector2d paper_floor_point(const WallCamera& camera, const Eigen::Vector2d& pixel) {
  const WallProjection view(camera);
  const auto line_image = [&](double y, Eigen::Vector2d& a, Eigen::Vector2d& b) {
    a = view.project({1.5, y, 0});
    b = view.project({8.0, y, 0});
  };
  Eigen::Vector2d p1, p2, q1, q2;
  line_image(kTile / 2, p1, p2);
  line_image(-kTile / 2, q1, q2);
  const double p = paper::column_at_row(p1, p2, pixel.y()), q = paper::column_at_row(q1, q2, pixel.y());
  const double fov = 2 * std::atan(camera.intrinsics.width / 2.0 / camera.intrinsics.fx);
  const double depth = paper::ibdms_depth(kTile, std::abs(q - p), camera.intrinsics.width, fov);
  const double pitch = camera.pitch_deg * std::numbers::pi / 180;
  const double distance = paper::floor_distance_from_depth(depth, camera.height, pitch);
  // Image right is world -y: the offset from the line at +kTile / 2 runs toward -y.
  return {distance, kTile / 2 - paper::pldms_offset(kTile, p, q, pixel.x())};
}

TEST(PaperDistance, IbdmsAndPldmsPlaceFloorPointsExactly) {
  WallCamera camera;
  const WallProjection view(camera);
  for (const double x : {1.8, 3.0, 4.7, 6.4})
    for (const double y : {-1.1, -0.2, 0.6, 1.3}) {
      const Eigen::Vector2d pixel = view.project({x, y, 0});
      const Eigen::Vector2d found = paper_floor_point(camera, pixel);
      EXPECT_NEAR(found.x(), x, 1e-9) << x << ", " << y;
      EXPECT_NEAR(found.y(), y, 1e-9) << x << ", " << y;
    }
}

// The paper places the robot at the floor point of its blob's centroid. A camera looking down at
// a box sees its centroid at about half the box's height, whose floor point lies beyond the
// footprint: the error grows with distance (the paper's 22 mm near to 124 mm far). The box fit
// places the footprint's centre.
TEST(PaperDistance, TheBoxFitPlacesTheRobotWhereTheBlobCentroidDoesNot) {
  CleanBoxView view;
  double paper_sum2 = 0, fit_sum2 = 0, fit_max = 0;
  int count = 0;
  std::printf("distance  paper (centroid) mm  box fit mm\n");
  for (const double x : {2.0, 3.0, 4.0, 5.0, 6.0}) {
    for (const FloorPose pose : {FloorPose{x, -0.4, 0.3}, FloorPose{x, 0.5, 1.9}}) {
      Silhouette seen;
      ASSERT_NO_FATAL_FAILURE(view.seen(pose, seen));
      const Eigen::Vector2d paper = paper_floor_point(view.camera, {seen.cx, seen.cy});
      const BoxFit fit = fit_box(view.box, seen);
      ASSERT_TRUE(fit.ok);
      const double paper_error = std::hypot(paper.x() - pose.x, paper.y() - pose.y);
      const double fit_error = std::hypot(fit.pose.x - pose.x, fit.pose.y - pose.y);
      std::printf("%4.1f m    %8.1f             %6.1f\n", x, 1000 * paper_error, 1000 * fit_error);
      paper_sum2 += paper_error * paper_error;
      fit_sum2 += fit_error * fit_error;
      fit_max = std::max(fit_max, fit_error);
      ++count;
    }
  }
  const double paper_rms = std::sqrt(paper_sum2 / count), fit_rms = std::sqrt(fit_sum2 / count);
  std::printf("RMS: paper %.1f mm, box fit %.1f mm\n", 1000 * paper_rms, 1000 * fit_rms);
  EXPECT_LE(fit_max, 0.02);
  EXPECT_GE(paper_rms, 10 * fit_rms);
}

}  // namespace
}  // namespace irloc::test
