#include "algo/pipeline/pose_revision.hpp"

#include <array>

#include <Eigen/Cholesky>

#include "algo/core/chi_square.hpp"

namespace irloc {

bool revision_agrees(const PoseEstimate& first, const PoseEstimate& revised, const PoseCovariance& revised_from) {
  constexpr std::array<int, 3> kPlanar{0, 1, 5};
  Eigen::Matrix3d both;
  for (std::size_t i = 0; i < kPlanar.size(); ++i) {
    for (std::size_t j = 0; j < kPlanar.size(); ++j) {
      both(i, j) = first.covariance(kPlanar[i], kPlanar[j]) + revised_from(kPlanar[i], kPlanar[j]);
    }
  }
  const Eigen::LDLT<Eigen::Matrix3d> solver(both);
  if (solver.info() != Eigen::Success || !(solver.vectorD().minCoeff() > 0)) return false;
  const Eigen::Vector3d moved(revised.x - first.x, revised.y - first.y, wrap_angle(revised.yaw - first.yaw));
  return moved.dot(solver.solve(moved)) <= chi_square_quantile_at(3, kRevisionGateNormalQuantile);
}

}  // namespace irloc
