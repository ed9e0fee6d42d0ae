#include "algo/pipeline/pose_fusion.hpp"

#include <cmath>

#include <Eigen/Cholesky>

#include "algo/geometry/pose_refinement.hpp"

namespace irloc {
namespace {

// Indices in (x, y, z, roll, pitch, yaw) of the parameters the dof estimates.
std::span<const int> estimated_parameters(Dof dof) {
  static constexpr int kPlanar[] = {0, 1, 5};
  static constexpr int kHeight[] = {0, 1, 2, 5};
  static constexpr int kFull[] = {0, 1, 2, 3, 4, 5};
  switch (dof) {
    case Dof::planar3: return kPlanar;
    case Dof::height4: return kHeight;
    case Dof::full6: return kFull;
  }
  return kFull;
}

bool is_angle(int parameter) { return parameter >= 3; }

// At most 6 x 6, on the stack: the per-frame path allocates nothing.
using Block = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;
using BlockVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>;

}  // namespace

bool fuse_poses(std::span<const SourceResult* const> results, Dof dof, const FusionGate& gate, FusedPose& fused) {
  if (results.empty()) return false;
  const std::span<const int> estimated = estimated_parameters(dof);
  const auto n = static_cast<Eigen::Index>(estimated.size());
  const PoseParameters reference = parameters_from_pose(results.front()->world_from_base);

  Block information = Block::Zero(n, n);
  BlockVector weighted = BlockVector::Zero(n);
  for (const SourceResult* result : results) {
    const PoseParameters parameters = parameters_from_pose(result->world_from_base);
    if ((parameters.head<3>() - reference.head<3>()).norm() > gate.position ||
        std::abs(wrap_angle(parameters(5) - reference(5))) > gate.yaw) {
      return false;
    }
    Block covariance(n, n);
    BlockVector offset(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      const int p = estimated[static_cast<std::size_t>(i)];
      offset(i) = is_angle(p) ? wrap_angle(parameters(p) - reference(p)) : parameters(p) - reference(p);
      for (Eigen::Index j = 0; j < n; ++j) covariance(i, j) = result->covariance(p, estimated[static_cast<std::size_t>(j)]);
    }
    const Eigen::LLT<Block> factor(covariance);
    if (factor.info() != Eigen::Success) return false;
    const Block inverse = factor.solve(Block::Identity(n, n));
    information += inverse;
    weighted += inverse * offset;
  }
  const Eigen::LLT<Block> factor(information);
  if (factor.info() != Eigen::Success) return false;
  const Block covariance = factor.solve(Block::Identity(n, n));
  const BlockVector mean_offset = covariance * weighted;

  PoseParameters mean = reference;
  fused.covariance.setZero();
  for (Eigen::Index i = 0; i < n; ++i) {
    const int p = estimated[static_cast<std::size_t>(i)];
    mean(p) = is_angle(p) ? wrap_angle(reference(p) + mean_offset(i)) : reference(p) + mean_offset(i);
    for (Eigen::Index j = 0; j < n; ++j) fused.covariance(p, estimated[static_cast<std::size_t>(j)]) = covariance(i, j);
  }
  fused.world_from_base = pose_from_parameters(mean);
  return true;
}

}  // namespace irloc
