// The floor geometry (the wall camera's pose from floor points) on the room of issue #27: a
// 640 x 480 camera with barrel distortion 2.4 m up, pitched 35 degrees down, and one 0.6 m tile
// about 3 m away whose corners a careful user clicks to 0.3 px. And its checks.
#include "algo/markers/outside_in/floor_geometry.hpp"

#include <random>

#include <gtest/gtest.h>
#include <Eigen/LU>

#include "algo/markers/outside_in/box_silhouette.hpp"
#include "algo/markers/outside_in/outside_in_source.hpp"
#include "tests/outside_in/outside_in_drive.hpp"

namespace irloc::test {
namespace {

using namespace irloc::outside_in;  // the source under test

struct BarrelRoom {
  WallCamera camera;
  CameraModel model{camera.intrinsics};

  BarrelRoom() : camera(barrel_camera()), model(camera.intrinsics) {}
  static WallCamera barrel_camera() {
    WallCamera camera;
    camera.intrinsics.distortion = {-0.25, 0.07, 0, 0, 0};
    camera.height = 2.4;
    camera.pitch_deg = 35;
    return camera;
  }
  RigidTransform camera_from_world() const { return camera.world_from_camera().inverse(); }
  Eigen::Vector2d pixel_of(const Eigen::Vector2d& floor) const {
    Eigen::Vector2d pixel;
    EXPECT_TRUE(model.project(camera_from_world() * Eigen::Vector3d(floor.x(), floor.y(), 0), pixel));
    return pixel;
  }
  // The corners of a grid of columns x rows tiles of side `tile`, its near left corner at corner.
  FloorReference reference(const Eigen::Vector2d& corner, int columns, int rows, double tile, double sigma,
                           std::mt19937& rng) const {
    std::normal_distribution<double> noise(0, sigma);
    FloorReference reference;
    reference.pixel_sigma = std::max(sigma, 0.01);
    for (int i = 0; i <= columns; ++i) {
      for (int j = 0; j <= rows; ++j) {
        const Eigen::Vector2d floor = corner + tile * Eigen::Vector2d(i, j);
        reference.world.push_back(floor);
        reference.pixels.push_back(pixel_of(floor) + Eigen::Vector2d(noise(rng), noise(rng)));
      }
    }
    return reference;
  }
};

const Eigen::Vector2d kFarTile(2.7, 0.1);  // the one tile of the issue, 2.7-3.3 m out

// The camera centre's covariance, from the pose's (the perturbation of floor_geometry.hpp):
// c = -R^T t moves by -R^T [t]x w - R^T dt.
Eigen::Matrix3d centre_covariance(const FloorGeometry& floor) {
  const RigidTransform& pose = floor.camera_from_world;
  Eigen::Matrix<double, 3, 6> jacobian;
  Eigen::Matrix3d t_cross;
  t_cross << 0, -pose.translation.z(), pose.translation.y(), pose.translation.z(), 0, -pose.translation.x(),
      -pose.translation.y(), pose.translation.x(), 0;
  jacobian.leftCols<3>() = -pose.rotation.transpose() * t_cross;
  jacobian.rightCols<3>() = -pose.rotation.transpose();
  return jacobian * floor.covariance * jacobian.transpose();
}

struct CameraErrors {
  int accepted = 0, within_2cm = 0;
  double sum2 = 0, predicted2 = 0, worst = 0;
};

CameraErrors camera_errors(const BarrelRoom& room, int columns, int rows, int trials, std::mt19937& rng) {
  CameraErrors errors;
  for (int trial = 0; trial < trials; ++trial) {
    const FloorGeometry floor =
        solve_floor_geometry(room.camera.intrinsics, room.reference(kFarTile, columns, rows, 0.6, 0.3, rng));
    if (!floor.ok) continue;
    ++errors.accepted;
    const double error = (floor.camera_from_world.inverse().translation - room.camera.world_from_camera().translation).norm();
    errors.within_2cm += error <= 0.02;
    errors.worst = std::max(errors.worst, error);
    errors.sum2 += error * error;
    errors.predicted2 += centre_covariance(floor).trace();
  }
  return errors;
}

// The issue's reference is accepted as a careful user clicks it, and the camera lands where the
// clicks' noise puts it: the spread of its position is what the covariance predicts (OpenCV's
// IPPE lands in the same place: PlanarPnpOracle). 0.3 px on a 55-95 px tile 3.8 m away leaves
// the camera 35 mm RMS off: within 2 cm in about a fifth of the draws, not in all
// (docs/outside_in.md).
TEST(FloorGeometry, TheIssuesOneTileClickedToAThirdOfAPixelIsAcceptedAndItsSpreadPredicted) {
  const BarrelRoom room;
  std::mt19937 rng(27);
  const FloorReference exact = room.reference(kFarTile, 1, 1, 0.6, 0, rng);
  double across_min = 1e9, across_max = 0;
  for (int i = 0; i < 4; ++i) {
    const double side = (exact.pixels[i] - exact.pixels[(i + 1) % 4]).norm();
    across_min = std::min(across_min, side);
    across_max = std::max(across_max, side);
  }
  EXPECT_GT(across_min, 50);   // the issue's tile: 55 to 95 px across
  EXPECT_LT(across_max, 100);
  const FloorGeometry clean = solve_floor_geometry(room.camera.intrinsics, exact);
  ASSERT_TRUE(clean.ok) << clean.error;
  EXPECT_LT((clean.camera_from_world.inverse().translation - room.camera.world_from_camera().translation).norm(), 1e-6);

  constexpr int kTrials = 1000;
  const CameraErrors errors = camera_errors(room, 1, 1, kTrials, rng);
  const double rms = std::sqrt(errors.sum2 / errors.accepted), predicted = std::sqrt(errors.predicted2 / errors.accepted);
  std::printf("one 0.6 m tile at 3 m, corners to 0.3 px: %d of %d accepted, camera within 2 cm in %d, RMS %.1f mm "
              "(predicted %.1f), worst %.1f mm\n",
              errors.accepted, kTrials, errors.within_2cm, 1000 * rms, 1000 * predicted, 1000 * errors.worst);
  EXPECT_GE(errors.accepted, kTrials * 995 / 1000);  // the check's 99.9 % quantile
  // The covariance takes the larger of pixel_sigma and the residuals' own estimate: a little
  // conservative, never optimistic.
  EXPECT_GT(rms / predicted, 0.75);
  EXPECT_LT(rms / predicted, 1.05);
}

// Nine corners of four tiles: accepted, and the camera twice as close as from one of those tiles.
TEST(FloorGeometry, MoreFloorPointsGiveABetterCamera) {
  const BarrelRoom room;
  std::mt19937 rng(4);
  const CameraErrors one = camera_errors(room, 1, 1, 300, rng);
  const CameraErrors four = camera_errors(room, 2, 2, 300, rng);
  std::printf("corners to 0.3 px: one tile, camera %.1f mm RMS, within 2 cm in %d of %d; four tiles (9 corners), "
              "%.1f mm RMS, within 2 cm in %d of %d\n",
              1000 * std::sqrt(one.sum2 / one.accepted), one.within_2cm, one.accepted,
              1000 * std::sqrt(four.sum2 / four.accepted), four.within_2cm, four.accepted);
  EXPECT_GE(four.accepted, 297);
  EXPECT_LT(four.sum2 / four.accepted, 0.25 * one.sum2 / one.accepted);
}

// The reference's covariance, carried into a robot's floor pose by the box fit's sensitivity to
// the camera pose, predicts the spread of the fitted pose over the clicks' noise (the robot's
// silhouette held fixed, the camera re-solved each time).
TEST(FloorGeometry, ItsCovariancePredictsTheSpreadItGivesTheRobotsPose) {
  const BarrelRoom room;
  const BoxBody body;
  const BoxSilhouette truth_box(room.model, room.camera_from_world(), body);
  std::mt19937 rng(9);
  for (const FloorPose& robot : {FloorPose{4.5, -0.8, 0.6}, FloorPose{2.5, 0.7, 2.0}}) {
    Silhouette seen;
    ASSERT_TRUE(truth_box.project(robot, seen));
    const BoxFit at_truth = fit_box(truth_box, seen, HeadingPrior{robot.yaw, 0.17});
    ASSERT_TRUE(at_truth.ok);
    Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
    Eigen::Matrix3d predicted = Eigen::Matrix3d::Zero();
    int fitted = 0;
    for (int trial = 0; trial < 300; ++trial) {
      const FloorGeometry floor = solve_floor_geometry(room.camera.intrinsics, room.reference(kFarTile, 1, 1, 0.6, 0.3, rng));
      if (!floor.ok) continue;
      const BoxFit fit = fit_box(BoxSilhouette(room.model, floor.camera_from_world, body), seen, HeadingPrior{robot.yaw, 0.17});
      ASSERT_TRUE(fit.ok);
      const Eigen::Vector3d error(fit.pose.x - robot.x, fit.pose.y - robot.y,
                                  std::remainder(fit.pose.yaw - robot.yaw, body.symmetry_turn()));
      scatter += error * error.transpose();
      predicted += at_truth.camera_sensitivity * floor.covariance * at_truth.camera_sensitivity.transpose();
      ++fitted;
    }
    scatter /= fitted;
    predicted /= fitted;
    for (int k = 0; k < 3; ++k) {
      std::printf("robot at (%.1f, %.1f): axis %d spread %.4g, predicted %.4g\n", robot.x, robot.y, k,
                  std::sqrt(scatter(k, k)), std::sqrt(predicted(k, k)));
      EXPECT_NEAR(std::sqrt(scatter(k, k) / predicted(k, k)), 1, 0.3) << k;
    }
  }
}

// A small tile far away makes every pose less certain than a large rectangle near the middle of
// the view, and the covariance says so.
TEST(FloorGeometry, ASmallFarTileMakesEveryPoseLessCertain) {
  const BarrelRoom room;
  const BoxBody body;
  std::mt19937 rng(1);
  FloorReference large = room.reference({2.5, -1.0}, 1, 1, 2.0, 0, rng);
  FloorReference small = room.reference(kFarTile, 1, 1, 0.6, 0, rng);
  large.pixel_sigma = small.pixel_sigma = 0.5;
  const FloorGeometry near_large = solve_floor_geometry(room.camera.intrinsics, large);
  const FloorGeometry far_small = solve_floor_geometry(room.camera.intrinsics, small);
  ASSERT_TRUE(near_large.ok && far_small.ok);
  const BoxSilhouette box(room.model, room.camera_from_world(), body);
  for (const FloorPose& robot : {FloorPose{2.0, 0.5, 0.3}, FloorPose{4.0, -1.0, 1.2}, FloorPose{5.5, 1.0, -2.0}}) {
    Silhouette seen;
    ASSERT_TRUE(box.project(robot, seen));
    const BoxFit fit = fit_box(box, seen, HeadingPrior{robot.yaw, 0.17});
    ASSERT_TRUE(fit.ok);
    const Eigen::Matrix3d from_small = fit.camera_sensitivity * far_small.covariance * fit.camera_sensitivity.transpose();
    const Eigen::Matrix3d from_large = fit.camera_sensitivity * near_large.covariance * fit.camera_sensitivity.transpose();
    const double small_variance = from_small(0, 0) + from_small(1, 1), large_variance = from_large(0, 0) + from_large(1, 1);
    EXPECT_GT(small_variance, 2 * large_variance) << robot.x;
    EXPECT_GT(large_variance, 0);
  }
}

TEST(FloorGeometry, RecoversTheCameraPoseFromTheFloorRectangle) {
  const WallCamera camera;
  const FloorGeometry floor = solve_floor_geometry(camera.intrinsics, floor_reference_of(camera));
  ASSERT_TRUE(floor.ok) << floor.error;
  const RigidTransform world_from_camera = floor.camera_from_world.inverse();
  EXPECT_NEAR((world_from_camera.translation - camera.world_from_camera().translation).norm(), 0, 0.01);
  EXPECT_NEAR(Eigen::AngleAxisd(world_from_camera.rotation.transpose() * camera.world_from_camera().rotation).angle(), 0,
              0.002);
}

// A camera away from the world origin, looking away from it (the origin is behind it): every wall
// of a room has such a camera when one origin serves them all.
TEST(FloorGeometry, RecoversACameraThatLooksAwayFromTheWorldOrigin) {
  for (const double yaw_deg : {0.0, 90.0, -150.0}) {
    WallCamera camera;
    camera.position = Eigen::Vector2d(2.79, 5.70);
    camera.yaw_deg = yaw_deg;
    const Eigen::Rotation2Dd turn(yaw_deg * std::numbers::pi / 180);
    std::array<Eigen::Vector2d, 4> world;
    const Eigen::Vector2d local[4] = {{2.5, 1.0}, {4.5, 1.0}, {4.5, -1.0}, {2.5, -1.0}};
    for (int i = 0; i < 4; ++i) world[i] = camera.position + turn * local[i];
    const FloorGeometry floor = solve_floor_geometry(camera.intrinsics, sim::measured_floor_reference(camera, world));
    ASSERT_TRUE(floor.ok) << "yaw " << yaw_deg << ": " << floor.error;
    EXPECT_NEAR((floor.camera_from_world.inverse().translation - camera.world_from_camera().translation).norm(), 0, 0.01)
        << "yaw " << yaw_deg;
  }
}

TEST(FloorGeometry, RejectsPointsThatDoNotFitOrCannotDecide) {
  const WallCamera camera;
  const auto error_of = [&](const FloorReference& reference) { return solve_floor_geometry(camera.intrinsics, reference).error; };
  FloorReference skewed = floor_reference_of(camera);
  skewed.world[2].x() += 0.3;
  EXPECT_NE(error_of(skewed).find("do not fit one floor"), std::string::npos) << error_of(skewed);

  FloorReference crossed = floor_reference_of(camera);
  std::swap(crossed.pixels[1], crossed.pixels[2]);
  EXPECT_FALSE(error_of(crossed).empty());

  FloorReference mirrored = floor_reference_of(camera);
  std::swap(mirrored.pixels[0], mirrored.pixels[1]);
  std::swap(mirrored.pixels[2], mirrored.pixels[3]);
  EXPECT_FALSE(error_of(mirrored).empty());

  FloorReference outside = floor_reference_of(camera);
  outside.pixels[0].x() = -20;
  EXPECT_NE(error_of(outside).find("point 1 lies outside the image"), std::string::npos) << error_of(outside);

  FloorReference three = floor_reference_of(camera);
  three.world.pop_back();
  three.pixels.pop_back();
  EXPECT_NE(error_of(three).find("expected 4 to 64 points, got 3"), std::string::npos) << error_of(three);

  FloorReference on_a_line = floor_reference_of(camera);
  for (int i = 0; i < 4; ++i) on_a_line.world[i] = Eigen::Vector2d(2.5 + 0.5 * i, 0.005 * (i % 2));
  EXPECT_NE(error_of(on_a_line).find("on one line"), std::string::npos) << error_of(on_a_line);

  FloorReference doubled = floor_reference_of(camera);
  doubled.world[1] = doubled.world[0] + Eigen::Vector2d(0.01, 0.02);
  EXPECT_NE(error_of(doubled).find("points 1 and 2 are closer than 5 cm"), std::string::npos) << error_of(doubled);

  // The same clicks judged against a claimed precision they do not have.
  const BarrelRoom room;
  std::mt19937 rng(3);
  FloorReference sloppy = room.reference(kFarTile, 1, 1, 0.6, 0, rng);
  sloppy.pixels[0] += Eigen::Vector2d(3.0, -2.0);
  sloppy.pixel_sigma = 0.3;
  const std::string refused = solve_floor_geometry(room.camera.intrinsics, sloppy).error;
  EXPECT_NE(refused.find("pixel_sigma 0.30 px allows for 4 points"), std::string::npos) << refused;
  sloppy.pixel_sigma = 2;
  EXPECT_TRUE(solve_floor_geometry(room.camera.intrinsics, sloppy).ok) << solve_floor_geometry(room.camera.intrinsics, sloppy).error;

  OutsideInConfig config;
  config.floor_reference = skewed;
  EXPECT_THROW(OutsideInSource(SourceSetup{camera.intrinsics, RigidTransform{}, Dof::planar3, MarkerMap{}}, config),
               std::invalid_argument);
}

}  // namespace
}  // namespace irloc::test
