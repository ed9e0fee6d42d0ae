#pragma once
// The bundle adjustment behind calibrate_from_drive (drive_calibration.hpp): the lens, the mount
// and every pose of a drive refined together from the dots' pixels, with the parameters the
// drive's motion cannot show fixed, and what each estimate rests on. Internal to
// algo/calibration.

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "algo/calibration/drive_calibration.hpp"
#include "algo/calibration/lens_parameters.hpp"

namespace irloc::calibration {

// Global parameters: the lens's, then the mount's rotation about base x, y, z and its offset.
inline constexpr int kMaxGlobals = kMaxLensParameters + 6;
using GlobalVector = Eigen::Matrix<double, kMaxGlobals, 1>;
using GlobalMatrix = Eigen::Matrix<double, kMaxGlobals, kMaxGlobals>;
using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;
using GlobalPoseMatrix = Eigen::Matrix<double, kMaxGlobals, 6>;

// Which of a pose's six increments (translation x, y, z, rotation about W's x, y, z) the dof
// estimates. Rotations are applied on the world side, R <- exp(d) R: under dof 3 and 4 the one
// rotation about z is exactly a yaw increment.
std::array<bool, 6> pose_axes(Dof dof);

struct AdjustmentState {
  CameraIntrinsics lens;
  RigidTransform mount;
  std::vector<RigidTransform> poses;
};

// The normal equations of one linearization, in the full (fixed parameters included) indexing.
struct NormalEquations {
  GlobalMatrix globals = GlobalMatrix::Zero();
  GlobalVector global_gradient = GlobalVector::Zero();
  std::vector<Matrix6> poses;              // per frame
  std::vector<GlobalPoseMatrix> crossing;  // globals x frame
  std::vector<Vector6> pose_gradient;
  std::vector<Matrix6> links;              // frame k x frame k + 1
  GlobalVector max_sensitivity = GlobalVector::Zero();  // per global: max |d pixel / d parameter|

  void reset(std::size_t frames) {
    globals.setZero();
    global_gradient.setZero();
    poses.assign(frames, Matrix6::Zero());
    crossing.assign(frames, GlobalPoseMatrix::Zero());
    pose_gradient.assign(frames, Vector6::Zero());
    links.assign(frames, Matrix6::Zero());
    max_sensitivity.setZero();
  }
};

struct AdjustmentCost {
  double cost = 0;
  std::size_t valid = 0;     // dots inside the lens's valid region
  double weighted_sq = 0;    // sum of w |e|^2, px^2
};

class DriveAdjustment {
 public:
  DriveAdjustment(const DriveObservations& drive, const CameraIntrinsics& camera, const RigidTransform& mount,
                  const CalibrationOptions& options)
      : drive_(drive), options_(options), input_{camera, mount, {}}, lenses_(lens_parameter_count(camera.model)),
        globals_(lenses_ + 6), axes_(pose_axes(options.dof)) {
    for (const DriveFrame& frame : drive.frames()) input_.poses.push_back(frame.world_from_base);
    state_ = input_;
    set_up_parameters();
  }

  // The whole calibration: the motion check, the rounds of refinement, the evidence test.
  CalibrationResult run();

 private:
  void set_up_parameters();
  // The motion and the distinct views of the drive; false (with the message) when they are too few.
  bool check_motion(CalibrationResult& result);
  // Refines until every free parameter is observable, fixing the least observed one per round;
  // false (with the message) when the dots are too few for the unknowns.
  bool refine_until_observable(CalibrationResult& result, GlobalMatrix& covariance);
  // Each free parameter's sigma from the drive's own evidence (`covariance`: every free
  // parameter's, priors included).
  GlobalVector drive_sigmas(const NormalEquations& normal, const GlobalMatrix& covariance) const;
  // The free parameter observed least, beyond its limit, or -1.
  int least_observed(const GlobalVector& drive_sigma, const NormalEquations& normal) const;
  void fix_unobservable(int g, const GlobalVector& drive_sigma, const NormalEquations& normal);
  // The dots' RMS residual with the input calibration and every pose refined to it (state_ and
  // the fixed parameters are restored).
  double input_refit_rms();
  // The refined values with their sigma, state and reason, into the result.
  void report_parameters(CalibrationResult& result, const GlobalVector& sigma) const;
  // The terms of the cost: the dots' reprojection (robust), the base's lateral slip between
  // consecutive frames, the globals' priors. Each adds its Jacobians to `normal` when given.
  void add_reprojection(const AdjustmentState& state, NormalEquations* normal, AdjustmentCost& result) const;
  void add_lateral_slip(const AdjustmentState& state, NormalEquations* normal, AdjustmentCost& result) const;
  void add_priors(const AdjustmentState& state, NormalEquations* normal, AdjustmentCost& result) const;
  double global_value(const AdjustmentState& state, int g) const;
  void reset_global(int g);
  AdjustmentCost evaluate(const AdjustmentState& state, NormalEquations* normal) const;
  int solve();  // Levenberg-Marquardt from state_; returns iterations
  bool step(const NormalEquations& normal, double damping, AdjustmentState& next) const;
  // The normal matrix (damped) and right-hand side over the free parameters; `held` globals are
  // left out too (treated as known).
  Eigen::SparseMatrix<double> assemble(const NormalEquations& normal, double damping, Eigen::VectorXd& rhs,
                                       const std::array<bool, kMaxGlobals>& held = {}) const;
  // The free globals' covariance (zero rows and columns for fixed and `held` ones, which are
  // treated as known: conditional covariance).
  GlobalMatrix global_covariance(const NormalEquations& normal, const std::array<bool, kMaxGlobals>& held = {}) const;
  // Fixes the parameters the drive's motion cannot show; returns the distinct views.
  int fix_by_motion(double driven_m, double turned_rad);
  // The free globals' change from the input, in their covariance (Mahalanobis distance squared).
  double change_chi2(const GlobalMatrix& covariance) const;
  int free_globals() const;
  std::string global_name(int g) const;
  ResidualStats residual_stats(const AdjustmentState& state, bool after, std::vector<DotResidual>& residuals) const;

  const DriveObservations& drive_;
  CalibrationOptions options_;
  AdjustmentState input_, state_;
  int lenses_, globals_;
  std::array<bool, 6> axes_;
  int pose_dim_ = 0;
  std::array<bool, kMaxGlobals> fixed_{};
  std::array<std::string, kMaxGlobals> fixed_reason_;
  GlobalVector prior_sigma_ = GlobalVector::Zero();  // every global has one; informative_ marks the real ones
  std::array<bool, kMaxGlobals> informative_{};
  // Informative, but the prior only stands in for what the drive may show (the principal point
  // beside the mount's tilt): kept at its input value unless the drive alone observes it.
  std::array<bool, kMaxGlobals> held_unless_observed_{};
  std::array<std::string, kMaxGlobals> prior_reason_;
  double pixel_sigma_ = 0.5;
};

}  // namespace irloc::calibration
