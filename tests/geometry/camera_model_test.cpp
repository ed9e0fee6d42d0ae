// Camera models on their own: round trips over the whole image, Jacobians against finite
// differences, and the valid region at its edges.

#include "algo/geometry/camera_model.hpp"

#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "tests/geometry/calibrations.hpp"
#include "tests/support/allocation_counter.hpp"

namespace irloc {
namespace {

using test::make_intrinsics;

class EveryLens : public ::testing::TestWithParam<CameraIntrinsics> {};

std::string lens_name(const ::testing::TestParamInfo<CameraIntrinsics>& lens) {
  static const std::array<const char*, 4> names = {"plumb_bob", "wide_plumb_bob", "equidistant", "equisolid"};
  return names.at(lens.index);
}

INSTANTIATE_TEST_SUITE_P(Lenses, EveryLens,
                         ::testing::Values(test::plumb_bob_lens(), test::wide_plumb_bob_lens(),
                                           test::equidistant_lens(), test::equisolid_lens()),
                         lens_name);

// Every pixel centre on a 5-pixel grid, every image edge and the four outer corners.
TEST_P(EveryLens, UnprojectThenProjectRoundTripsOverTheWholeImage) {
  const CameraModel camera(GetParam());
  const double right = GetParam().width - 0.5, bottom = GetParam().height - 0.5;
  double worst = 0;
  int checked = 0;
  auto check = [&](double u, double v) {
    const Eigen::Vector2d pixel(u, v);
    Eigen::Vector3d bearing;
    ASSERT_TRUE(camera.unproject(pixel, bearing)) << "pixel " << u << ", " << v;
    EXPECT_NEAR(bearing.norm(), 1.0, 1e-12);
    Eigen::Vector2d again;
    ASSERT_TRUE(camera.project(bearing, again)) << "pixel " << u << ", " << v;
    worst = std::max(worst, (again - pixel).norm());
    ++checked;
  };
  for (double v = 0; v <= bottom; v += 5) {
    for (double u = 0; u <= right; u += 5) check(u, v);
  }
  for (double u = -0.5; u <= right; u += 1) {
    check(u, -0.5);
    check(u, bottom);
  }
  for (double v = -0.5; v <= bottom; v += 1) {
    check(-0.5, v);
    check(right, v);
  }
  EXPECT_LT(worst, 1e-6) << "over " << checked << " pixels";
}

TEST_P(EveryLens, ProjectThenUnprojectGivesTheBearing) {
  const CameraModel camera(GetParam());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1, 1);
  int checked = 0;
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector3d point(unit(rng), unit(rng), 0.2 + unit(rng));
    Eigen::Vector2d pixel;
    if (!camera.project(point, pixel) || !camera.in_image(pixel)) continue;
    Eigen::Vector3d bearing;
    ASSERT_TRUE(camera.unproject(pixel, bearing));
    EXPECT_LT((bearing - point.normalized()).norm(), 1e-10);
    ++checked;
  }
  EXPECT_GT(checked, 200);
}

TEST_P(EveryLens, JacobianMatchesCentralDifferences) {
  const CameraModel camera(GetParam());
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(-1, 1);
  int checked = 0;
  for (int i = 0; i < 500; ++i) {
    const Eigen::Vector3d point(unit(rng), unit(rng), 0.3 + 0.5 * (1 + unit(rng)));
    Eigen::Vector2d pixel;
    Eigen::Matrix<double, 2, 3> jacobian;
    if (!camera.project(point, pixel, jacobian)) continue;
    Eigen::Vector2d plain;
    ASSERT_TRUE(camera.project(point, plain));
    EXPECT_EQ(pixel, plain);
    Eigen::Matrix<double, 2, 3> numeric;
    const double h = 1e-6;
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector2d plus, minus;
      ASSERT_TRUE(camera.project(point + h * Eigen::Vector3d::Unit(k), plus));
      ASSERT_TRUE(camera.project(point - h * Eigen::Vector3d::Unit(k), minus));
      numeric.col(k) = (plus - minus) / (2 * h);
    }
    EXPECT_LT((jacobian - numeric).norm(), 1e-5 * (1 + numeric.norm())) << point.transpose();
    ++checked;
  }
  EXPECT_GT(checked, 300);
}

TEST_P(EveryLens, JacobianOnTheOpticalAxis) {
  const CameraModel camera(GetParam());
  const Eigen::Vector3d point(0, 0, 2);
  Eigen::Vector2d pixel;
  Eigen::Matrix<double, 2, 3> jacobian;
  ASSERT_TRUE(camera.project(point, pixel, jacobian));
  EXPECT_NEAR(pixel.x(), GetParam().cx, 1e-12);
  EXPECT_NEAR(pixel.y(), GetParam().cy, 1e-12);
  Eigen::Matrix<double, 2, 3> expected;
  expected << GetParam().fx / 2, 0, 0, 0, GetParam().fy / 2, 0;
  EXPECT_LT((jacobian - expected).norm(), 1e-9);
}

TEST_P(EveryLens, AllocatesNothing) {
  const CameraModel camera(GetParam());
  test::AllocationCounter counter;
  Eigen::Vector3d bearing;
  Eigen::Vector2d pixel;
  Eigen::Matrix<double, 2, 3> jacobian;
  EXPECT_TRUE(camera.unproject(Eigen::Vector2d(3, 4), bearing));
  EXPECT_TRUE(camera.project(bearing, pixel));
  EXPECT_TRUE(camera.project(bearing, pixel, jacobian));
  EXPECT_EQ(counter.count(), 0u);
}

TEST(PlumbBob, RejectsPointsBehindOrBesideTheCamera) {
  const CameraModel camera(test::plumb_bob_lens());
  Eigen::Vector2d pixel;
  EXPECT_FALSE(camera.project(Eigen::Vector3d(0, 0, 0), pixel));
  EXPECT_FALSE(camera.project(Eigen::Vector3d(0.1, 0.1, 0), pixel));
  EXPECT_FALSE(camera.project(Eigen::Vector3d(0.1, 0.1, -1), pixel));
  EXPECT_TRUE(camera.project(Eigen::Vector3d(0.1, 0.1, 1), pixel));
}

// With only k1 < 0 the radial map r (1 + k1 r^2) peaks at r = 1 / sqrt(-3 k1).
TEST(PlumbBob, ValidRegionEndsWhereTheDistortionFoldsBack) {
  const double k1 = -0.2;
  const CameraModel camera(make_intrinsics(LensModel::plumb_bob, 640, 480, 500, 500, {k1, 0, 0, 0, 0}));
  const double r_max = 1 / std::sqrt(-3 * k1);
  EXPECT_NEAR(camera.max_field_angle(), std::atan(r_max), 1e-9);
  Eigen::Vector2d pixel;
  EXPECT_TRUE(camera.project(Eigen::Vector3d(r_max * 0.999, 0, 1), pixel));
  EXPECT_FALSE(camera.project(Eigen::Vector3d(r_max * 1.001, 0, 1), pixel));
  EXPECT_FALSE(camera.project(Eigen::Vector3d(0, r_max * 3, 1), pixel));
  // Pixels beyond the fold's image have no direction.
  const double peak = r_max * (1 + k1 * r_max * r_max);
  Eigen::Vector3d bearing;
  EXPECT_TRUE(camera.unproject(Eigen::Vector2d(camera.intrinsics().cx + 500 * peak * 0.999, 0 + 239.5), bearing));
  EXPECT_FALSE(camera.unproject(Eigen::Vector2d(camera.intrinsics().cx + 500 * peak * 1.001, 239.5), bearing));
}

TEST(PlumbBob, WithoutDistortionEveryForwardPointIsValid) {
  const CameraModel camera(make_intrinsics(LensModel::plumb_bob, 640, 480, 500, 500, {}));
  EXPECT_DOUBLE_EQ(camera.max_field_angle(), std::numbers::pi / 2);
  Eigen::Vector2d pixel;
  ASSERT_TRUE(camera.project(Eigen::Vector3d(100, -50, 1), pixel));
  EXPECT_NEAR(pixel.x(), camera.intrinsics().cx + 50000, 1e-6);
  Eigen::Vector3d bearing;
  ASSERT_TRUE(camera.unproject(Eigen::Vector2d(1e6, -1e6), bearing));
  EXPECT_GT(bearing.z(), 0);
}

TEST(Equidistant, SeesBeyondNinetyDegreesUpToThePeakOfItsPolynomial) {
  // theta_d = theta (1 + k1 theta^2) peaks at theta = 1 / sqrt(-3 k1) = 1.826 rad (104.6 deg).
  const double k1 = -0.1;
  const CameraModel camera(make_intrinsics(LensModel::equidistant, 640, 480, 200, 200, {k1, 0, 0, 0, 0}));
  const double theta_max = 1 / std::sqrt(-3 * k1);
  EXPECT_NEAR(camera.max_field_angle(), theta_max, 1e-9);
  Eigen::Vector2d pixel;
  auto ray = [](double theta) { return Eigen::Vector3d(std::sin(theta), 0, std::cos(theta)); };
  EXPECT_TRUE(camera.project(ray(theta_max - 1e-3), pixel));
  EXPECT_FALSE(camera.project(ray(theta_max + 1e-3), pixel));
  EXPECT_FALSE(camera.project(Eigen::Vector3d(0, 0, -1), pixel));
  EXPECT_FALSE(camera.project(Eigen::Vector3d::Zero(), pixel));
  const double peak = theta_max * (1 + k1 * theta_max * theta_max);
  Eigen::Vector3d bearing;
  EXPECT_FALSE(camera.unproject(Eigen::Vector2d(camera.intrinsics().cx, camera.intrinsics().cy + 200 * peak * 1.001), bearing));
}

TEST(Equidistant, WithoutDistortionCoversTheWholeSphereButTheBackAxis) {
  const CameraModel camera(make_intrinsics(LensModel::equidistant, 640, 480, 200, 200, {}));
  EXPECT_DOUBLE_EQ(camera.max_field_angle(), std::numbers::pi);
  Eigen::Vector2d pixel;
  ASSERT_TRUE(camera.project(Eigen::Vector3d(std::sin(2.5), 0, std::cos(2.5)), pixel));
  EXPECT_NEAR(pixel.x() - camera.intrinsics().cx, 200 * 2.5, 1e-9);  // r = f theta
  EXPECT_FALSE(camera.project(Eigen::Vector3d(0, 0, -1), pixel));
}

TEST(Equisolid, MatchesItsDefinition) {
  const CameraModel camera(test::equisolid_lens());
  const auto& k = camera.intrinsics();
  const double theta = 1.1, phi = 2.0;
  Eigen::Vector2d pixel;
  ASSERT_TRUE(camera.project(3 * Eigen::Vector3d(std::sin(theta) * std::cos(phi),
                                                 std::sin(theta) * std::sin(phi), std::cos(theta)),
                             pixel));
  EXPECT_NEAR(pixel.x(), k.cx + k.fx * 2 * std::sin(theta / 2) * std::cos(phi), 1e-9);
  EXPECT_NEAR(pixel.y(), k.cy + k.fy * 2 * std::sin(theta / 2) * std::sin(phi), 1e-9);
}

TEST(Equisolid, ValidUpToButExcludingTheBackAxis) {
  const CameraModel camera(test::equisolid_lens());
  EXPECT_DOUBLE_EQ(camera.max_field_angle(), std::numbers::pi);
  Eigen::Vector2d pixel;
  EXPECT_TRUE(camera.project(Eigen::Vector3d(std::sin(3.0), 0, std::cos(3.0)), pixel));
  EXPECT_FALSE(camera.project(Eigen::Vector3d(0, 0, -1), pixel));
  EXPECT_FALSE(camera.project(Eigen::Vector3d(1e-14, 0, -1), pixel));
  EXPECT_TRUE(camera.project(Eigen::Vector3d(1e-9, 0, -1), pixel));
  EXPECT_NEAR((pixel - Eigen::Vector2d(camera.intrinsics().cx, camera.intrinsics().cy)).norm(), 2 * 220, 1e-3);
  // The circle r = 2 f is the image of the back axis; nothing lies beyond it.
  const auto& k = camera.intrinsics();
  Eigen::Vector3d bearing;
  EXPECT_TRUE(camera.unproject(Eigen::Vector2d(k.cx + k.fx * 1.999, k.cy), bearing));
  EXPECT_LT(bearing.z(), -0.99);
  EXPECT_FALSE(camera.unproject(Eigen::Vector2d(k.cx + k.fx * 2.0, k.cy), bearing));
  EXPECT_FALSE(camera.unproject(Eigen::Vector2d(k.cx + k.fx * 2.5, k.cy + 3), bearing));
}

TEST(CameraModel, InImageCoversPixelCentresAndTheirOuterHalves) {
  const CameraModel camera(test::plumb_bob_lens());
  EXPECT_TRUE(camera.in_image(Eigen::Vector2d(-0.5, -0.5)));
  EXPECT_TRUE(camera.in_image(Eigen::Vector2d(639.5, 479.5)));
  EXPECT_FALSE(camera.in_image(Eigen::Vector2d(639.6, 100)));
  EXPECT_FALSE(camera.in_image(Eigen::Vector2d(100, -0.6)));
}

}  // namespace
}  // namespace irloc
