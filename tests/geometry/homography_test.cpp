// The normalized DLT homography (algo/geometry/homography.hpp).
#include "algo/geometry/homography.hpp"

#include <array>

#include <gtest/gtest.h>

namespace irloc {
namespace {

TEST(Homography, RecoversAKnownHomography) {
  Eigen::Matrix3d truth;
  truth << 1.2, 0.1, 3.0, -0.2, 0.9, -1.0, 0.01, -0.02, 1.0;
  std::array<Eigen::Vector2d, 7> from, to;
  for (std::size_t k = 0; k < from.size(); ++k) {
    from[k] = {static_cast<double>(k % 3), static_cast<double>(k * k % 5)};
    to[k] = apply_homography(truth, from[k]);
  }
  Eigen::Matrix3d fitted;
  ASSERT_TRUE(fit_homography(from, to, fitted));
  EXPECT_LT((fitted - truth).norm(), 1e-9);
}

TEST(Homography, RejectsCollinearPoints) {
  std::array<Eigen::Vector2d, 5> from, to;
  for (std::size_t k = 0; k < from.size(); ++k) {
    from[k] = {static_cast<double>(k), 2.0 * static_cast<double>(k)};
    to[k] = from[k];
  }
  Eigen::Matrix3d fitted;
  EXPECT_FALSE(fit_homography(from, to, fitted));
}

}  // namespace
}  // namespace irloc
