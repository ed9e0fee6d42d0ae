// estimate_pose: the whole solve, and the planar ambiguity of a flat marker seen head-on.

#include "algo/geometry/pose_solver.hpp"

#include <gtest/gtest.h>

#include "algo/geometry/p3p.hpp"
#include "tests/geometry/calibrations.hpp"
#include "tests/geometry/ceiling_scene.hpp"
#include "tests/support/allocation_counter.hpp"

namespace irloc {
namespace {

using test::up_mount;

constexpr double kDegree = M_PI / 180;

double tilt(const RigidTransform& world_from_base) {
  return std::acos(std::clamp(world_from_base.rotation(2, 2), -1.0, 1.0));
}

// A level robot whose camera sits right under (dx, dy) from the marker centre (0, 0).
RigidTransform level_robot(double dx, double dy, double yaw) {
  RigidTransform world_from_base{rotation_from_rpy(0, 0, yaw), Eigen::Vector3d::Zero()};
  const Eigen::Vector3d camera = world_from_base * up_mount().translation;
  world_from_base.translation = Eigen::Vector3d(dx - camera.x(), dy - camera.y(), 0);
  return world_from_base;
}

// What a solver without the dof rule would do: refine every P3P candidate in 6 dof, keep the
// lowest cost.
PoseFit lowest_cost_of_p3p_candidates(const std::vector<Eigen::Vector3d>& points,
                                      const std::vector<Eigen::Vector2d>& pixels, const CameraModel& camera,
                                      const RefinementOptions& options) {
  std::array<Eigen::Vector3d, 3> world, bearings;
  for (int k = 0; k < 3; ++k) {
    world[k] = points[k];
    EXPECT_TRUE(camera.unproject(pixels[k], bearings[k]));
  }
  P3PSolutions solutions;
  solve_p3p(world, bearings, solutions);
  PoseFit best;
  for (const RigidTransform& camera_from_world : solutions) {
    const PoseFit fit = refine_pose(points, pixels, camera, up_mount(),
                                    camera_from_world.inverse() * up_mount().inverse(), options);
    if (fit.ok && (!best.ok || fit.cost < best.cost)) best = fit;
  }
  return best;
}

struct AmbiguityCase {
  const char* name;
  double dx, dy;  // camera offset from the marker centre, metres
};

class FlatMarkerHeadOn : public ::testing::TestWithParam<AmbiguityCase> {};
INSTANTIATE_TEST_SUITE_P(Placements, FlatMarkerHeadOn,
                         ::testing::Values(AmbiguityCase{"image_centre", 0, 0}, AmbiguityCase{"near_centre", 0.08, -0.05},
                                           AmbiguityCase{"off_centre", 0.9, 0.6}),
                         [](const auto& placement) { return std::string(placement.param.name); });

// A 0.3 m square parallel to the image plane, 2.7 m above the camera, 0.5 px noise. Under dof 3
// and 4 the pose must come out level and accurate. Under dof 6 the tilt of so small a target is
// only known to several degrees (even the minimum nearest the truth is tilted by up to ~15 deg at
// the image centre), so the test compares with that minimum, found by refining from the truth:
// the result may be closer to level, never tilted beyond it by more than 3 sigma of the tilt
// (from the covariance): several minima that close are one noisy answer. Off centre a distinct mirrored
// minimum (~45 deg of tilt) exists and sometimes has the lower cost: the lowest-cost candidate
// alone picks it.
TEST_P(FlatMarkerHeadOn, NeverReturnsTheMirroredPose) {
  const CameraModel camera(test::plumb_bob_lens());
  const auto corners = test::square(0, 0, 0.3);
  std::mt19937 rng(7);
  std::vector<Eigen::Vector2d> pixels;
  int naive_flips = 0;
  const int trials = 300;
  for (Dof dof : {Dof::planar3, Dof::height4, Dof::full6}) {
    RefinementOptions options;
    options.dof = dof;
    double worst_tilt = 0, worst_excess_tilt = 0, worst_position = 0;
    for (int t = 0; t < trials; ++t) {
      const RigidTransform truth = level_robot(GetParam().dx, GetParam().dy, 0.3 + 0.01 * t);
      ASSERT_TRUE(test::observe(corners, camera, truth, up_mount(), 0.5, rng, pixels));
      const PoseFit fit = estimate_pose(corners, pixels, camera, up_mount(), options);
      ASSERT_TRUE(fit.ok);
      worst_tilt = std::max(worst_tilt, tilt(fit.world_from_base));
      if (dof != Dof::full6) {
        const Eigen::Vector3d error = fit.world_from_base.translation - truth.translation;
        worst_position = std::max(worst_position, error.head<2>().norm());
        EXPECT_LT(std::abs(error.z()), 4 * std::sqrt(fit.covariance(2, 2)) + 1e-12);
        EXPECT_LT(test::rotation_error(fit.world_from_base, truth), 2 * kDegree);
        continue;
      }
      const PoseFit nearest_truth = refine_pose(corners, pixels, camera, up_mount(), truth, options);
      const double tilt_sigma = std::sqrt(std::max(nearest_truth.covariance(3, 3), nearest_truth.covariance(4, 4)));
      const double excess = tilt(fit.world_from_base) - tilt(nearest_truth.world_from_base);
      worst_excess_tilt = std::max(worst_excess_tilt, excess);
      EXPECT_LT(excess, 3 * tilt_sigma) << "trial " << t;
      const PoseFit naive = lowest_cost_of_p3p_candidates(corners, pixels, camera, options);
      if (tilt(naive.world_from_base) > tilt(nearest_truth.world_from_base) + 20 * kDegree) ++naive_flips;
    }
    std::printf("%s dof %d: worst tilt %.2f deg (%.2f deg beyond the minimum nearest the truth), worst "
                "horizontal error %.1f mm\n", GetParam().name, static_cast<int>(dof), worst_tilt / kDegree,
                worst_excess_tilt / kDegree, worst_position * 1e3);
    if (dof != Dof::full6) {
      EXPECT_LT(worst_tilt, 1e-12);
      EXPECT_LT(worst_position, 0.03);
    }
  }
  std::printf("%s: the lowest-cost candidate alone is the mirror in %d of %d trials\n", GetParam().name,
              naive_flips, trials);
  if (GetParam().dx > 0.5) {
    EXPECT_GT(naive_flips, 0) << "the ambiguity this test is about did not arise";
  }
}

TEST(EstimatePose, DotMarkerUnderEveryDofAndLens) {
  for (const CameraIntrinsics& lens : {test::plumb_bob_lens(), test::equidistant_lens(), test::equisolid_lens()}) {
    const CameraModel camera(lens);
    const auto dots = test::dot_grid(0.2, -0.1, 1.0);
    for (Dof dof : {Dof::planar3, Dof::height4, Dof::full6}) {
      RigidTransform truth = level_robot(0.5, 0.3, -1.7);
      if (dof != Dof::planar3) truth.translation.z() = 0.15;
      if (dof == Dof::full6) truth.rotation = rotation_from_rpy(0.02, -0.03, -1.7);
      std::mt19937 rng(8);
      std::vector<Eigen::Vector2d> pixels;
      ASSERT_TRUE(test::observe(dots, camera, truth, up_mount(), 0, rng, pixels));
      RefinementOptions options;
      options.dof = dof;
      const PoseFit fit = estimate_pose(dots, pixels, camera, up_mount(), options);
      ASSERT_TRUE(fit.ok);
      EXPECT_LT((fit.world_from_base.translation - truth.translation).norm(), 1e-7) << static_cast<int>(dof);
      EXPECT_LT(test::rotation_error(fit.world_from_base, truth), 1e-8) << static_cast<int>(dof);
      EXPECT_LT(fit.rms_px, 1e-6);
    }
  }
}

TEST(EstimatePose, TwoPointsSufficeForALevelRobot) {
  const CameraModel camera(test::plumb_bob_lens());
  const std::vector<Eigen::Vector3d> points = {{0, 0, test::kCeilingZ}, {0.5, 0.1, test::kCeilingZ}};
  const RigidTransform truth = level_robot(0.3, -0.2, 2.0);
  std::mt19937 rng(9);
  std::vector<Eigen::Vector2d> pixels;
  ASSERT_TRUE(test::observe(points, camera, truth, up_mount(), 0, rng, pixels));
  RefinementOptions options;
  options.dof = Dof::planar3;
  const PoseFit fit = estimate_pose(points, pixels, camera, up_mount(), options);
  ASSERT_TRUE(fit.ok);
  EXPECT_LT((fit.world_from_base.translation - truth.translation).norm(), 1e-8);
  options.dof = Dof::full6;
  EXPECT_FALSE(estimate_pose(points, pixels, camera, up_mount(), options).ok);
}

TEST(EstimatePose, AllocatesNothing) {
  const CameraModel camera(test::equisolid_lens());
  const auto dots = test::dot_grid(0.2, -0.1, 1.0);
  std::mt19937 rng(10);
  std::vector<Eigen::Vector2d> pixels;
  ASSERT_TRUE(test::observe(dots, camera, level_robot(0.4, 0.1, 0.5), up_mount(), 0.3, rng, pixels));
  for (Dof dof : {Dof::planar3, Dof::height4, Dof::full6}) {
    RefinementOptions options;
    options.dof = dof;
    test::AllocationCounter counter;
    const PoseFit fit = estimate_pose(dots, pixels, camera, up_mount(), options);
    EXPECT_EQ(counter.count(), 0u);
    EXPECT_TRUE(fit.ok);
  }
}

}  // namespace
}  // namespace irloc
