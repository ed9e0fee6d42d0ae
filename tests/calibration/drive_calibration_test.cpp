// Self-calibration from the ceiling (algo/calibration): synthetic drives under dot markers seen
// through a known calibration, started from a wrong one.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "algo/calibration/drive_calibration.hpp"
#include "algo/calibration/lens_parameters.hpp"
#include "tests/calibration/synthetic_drive.hpp"

namespace irloc::test {
namespace {

using calibration::CalibrationOptions;
using calibration::CalibrationResult;
using calibration::ParameterState;

constexpr double kDegree = std::numbers::pi / 180;

// The calibration of issue 17: focal 0.5 %, principal point 2 px, k1 5 %, mount 0.2 deg in roll,
// pitch and yaw and 3 mm in x, y, z.
CameraIntrinsics perturbed_camera() {
  CameraIntrinsics k = true_camera();
  k.fx *= 1.005;
  k.fy *= 1.005;
  k.cx += 2 / std::sqrt(2.0);
  k.cy -= 2 / std::sqrt(2.0);
  k.distortion[0] *= 1.05;
  return k;
}

RigidTransform perturbed_mount() {
  RigidTransform mount = true_mount();
  mount.rotation = rotation_from_rpy(0.2 * kDegree, -0.2 * kDegree, 0.2 * kDegree) * mount.rotation;
  mount.translation += Eigen::Vector3d(0.003, -0.003, 0.003);
  return mount;
}

// A lens's nominal data sheet: focal length 3 % off, the principal point at the image centre,
// no distortion.
CameraIntrinsics data_sheet_camera() {
  CameraIntrinsics k = true_camera();
  k.fx = k.fy = 0.97 * 519;
  k.cx = (k.width - 1) / 2.0;
  k.cy = (k.height - 1) / 2.0;
  k.distortion = {};
  return k;
}

// Truth of each reported parameter (lens parameters, then the mount's rotation change about base
// x, y, z from the input and its offset).
double truth_of(int index, const CameraIntrinsics& camera, const RigidTransform& mount, const RigidTransform& input_mount) {
  const int lenses = calibration::lens_parameter_count(camera.model);
  if (index < lenses) return calibration::lens_parameter(camera, index);
  const int axis = index - lenses;
  if (axis < 3) {
    const Eigen::AngleAxisd change(mount.rotation * input_mount.rotation.transpose());
    return (change.angle() * change.axis())[axis];
  }
  return mount.translation[axis - 3];
}

struct PoseErrors {
  double position_rms = 0, planar_rms = 0, yaw_rms = 0;  // planar: x, y only
};

PoseErrors pose_errors(const std::vector<RigidTransform>& estimates, const std::vector<RigidTransform>& truth) {
  PoseErrors errors;
  for (std::size_t k = 0; k < truth.size(); ++k) {
    errors.position_rms += (estimates[k].translation - truth[k].translation).squaredNorm();
    errors.planar_rms += (estimates[k].translation - truth[k].translation).head<2>().squaredNorm();
    const double yaw = wrap_angle(rpy_from_rotation(estimates[k].rotation).yaw - rpy_from_rotation(truth[k].rotation).yaw);
    errors.yaw_rms += yaw * yaw;
  }
  errors.position_rms = std::sqrt(errors.position_rms / static_cast<double>(truth.size()));
  errors.planar_rms = std::sqrt(errors.planar_rms / static_cast<double>(truth.size()));
  errors.yaw_rms = std::sqrt(errors.yaw_rms / static_cast<double>(truth.size()));
  return errors;
}

std::vector<RigidTransform> starting_poses(const calibration::DriveObservations& drive) {
  std::vector<RigidTransform> poses;
  for (const calibration::DriveFrame& frame : drive.frames()) poses.push_back(frame.world_from_base);
  return poses;
}

void print(const CalibrationResult& result) {
  for (const calibration::ParameterEstimate& p : result.parameters) {
    std::printf("  %-12s input %12.6g value %12.6g sigma %10.3g  %s\n", p.name.c_str(), p.input, p.value, p.sigma,
                p.state == ParameterState::fixed ? ("fixed: " + p.reason).c_str() : p.reason.c_str());
  }
  std::printf("  residual rms %.3f -> %.3f px, pixel sigma %.3f, %d iterations\n", result.before.rms_px,
              result.after.rms_px, result.pixel_sigma, result.iterations);
}

// Every parameter that is not fixed lies within 3 of its reported sigmas of the truth.
void expect_within_sigmas(const CalibrationResult& result, const RigidTransform& input_mount) {
  for (std::size_t i = 0; i < result.parameters.size(); ++i) {
    const calibration::ParameterEstimate& p = result.parameters[i];
    if (p.state == ParameterState::fixed) continue;
    const double truth = truth_of(static_cast<int>(i), true_camera(), true_mount(), input_mount);
    EXPECT_LE(std::abs(p.value - truth), 3 * p.sigma) << p.name << " " << p.value << " truth " << truth;
  }
}

// How far the base is off when the mount's offset along the axle (y), which no motion shows,
// stays at its input value: the floor of the position error.
double axle_offset_error() { return std::abs(perturbed_mount().translation.y() - true_mount().translation.y()); }

TEST(DriveCalibration, RecoversAPerturbedCalibrationWithinItsSigmas) {
  const SyntheticDrive drive = observe_drive(wheeled_drive(), marker_grid(), true_camera(), true_mount(),
                                             perturbed_camera(), perturbed_mount(), 0.1, 1);
  ASSERT_GT(drive.truth.size(), 200u);
  const PoseErrors start = pose_errors(starting_poses(drive.observations), drive.truth);
  CalibrationOptions options;
  const CalibrationResult result = calibrate_from_drive(drive.observations, perturbed_camera(), perturbed_mount(), options);
  print(result);
  ASSERT_TRUE(result.ok) << result.message;
  expect_within_sigmas(result, perturbed_mount());
  // Every lens parameter the solver estimated moved the right way or stayed close: the focal
  // lengths and k1 from the drive, not from a prior.
  for (const char* name : {"fx", "fy", "k1"}) {
    const auto found = std::find_if(result.parameters.begin(), result.parameters.end(), [&](const auto& p) { return p.name == name; });
    ASSERT_NE(found, result.parameters.end());
    EXPECT_EQ(found->state, ParameterState::estimated) << name;
  }
  const PoseErrors after = pose_errors(result.poses, drive.truth);
  std::printf("  poses: %.2f mm / %.3f deg RMS -> %.2f mm / %.4f deg RMS\n", start.position_rms * 1e3,
              start.yaw_rms / kDegree, after.position_rms * 1e3, after.yaw_rms / kDegree);
  EXPECT_GT(start.position_rms, 0.004);
  EXPECT_LT(after.position_rms, axle_offset_error() + 0.0015);
  EXPECT_LT(after.yaw_rms, 0.05 * kDegree);
  EXPECT_LT(result.after.rms_px, 0.2);
  EXPECT_NEAR(result.pixel_sigma, 0.1, 0.02);
}

TEST(DriveCalibration, StartsFromADataSheetCalibration) {
  const SyntheticDrive drive = observe_drive(wheeled_drive(), marker_grid(), true_camera(), true_mount(),
                                             data_sheet_camera(), perturbed_mount(), 0.1, 2);
  ASSERT_GT(drive.truth.size(), 200u);
  const PoseErrors start = pose_errors(starting_poses(drive.observations), drive.truth);
  const CalibrationResult result = calibrate_from_drive(drive.observations, data_sheet_camera(), perturbed_mount(), {});
  print(result);
  ASSERT_TRUE(result.ok) << result.message;
  expect_within_sigmas(result, perturbed_mount());
  const PoseErrors after = pose_errors(result.poses, drive.truth);
  std::printf("  poses: %.2f mm / %.3f deg RMS -> %.2f mm / %.4f deg RMS\n", start.position_rms * 1e3,
              start.yaw_rms / kDegree, after.position_rms * 1e3, after.yaw_rms / kDegree);
  EXPECT_GT(result.before.rms_px, 2.0);
  EXPECT_LT(after.position_rms, axle_offset_error() + 0.0015);
  EXPECT_LT(after.yaw_rms, 0.05 * kDegree);
  EXPECT_LT(result.after.rms_px, 0.2);
}

TEST(DriveCalibration, KeepsTheMountOffsetWhenTheRobotNeverTurns) {
  const SyntheticDrive drive = observe_drive(wheeled_drive(false), marker_grid(), true_camera(), true_mount(),
                                             perturbed_camera(), perturbed_mount(), 0.1, 3);
  const CalibrationResult result = calibrate_from_drive(drive.observations, perturbed_camera(), perturbed_mount(), {});
  print(result);
  ASSERT_TRUE(result.ok) << result.message;
  const auto mount_x = std::find_if(result.parameters.begin(), result.parameters.end(), [](const auto& p) { return p.name == "mount x"; });
  ASSERT_NE(mount_x, result.parameters.end());
  EXPECT_EQ(mount_x->state, ParameterState::fixed);
  EXPECT_NE(mount_x->reason.find("not observable"), std::string::npos);
  EXPECT_EQ(mount_x->value, perturbed_mount().translation.x());
  expect_within_sigmas(result, perturbed_mount());
}

// A calibration wrong in what a drive without turns shows: focal lengths 1 % long, k1 10 %
// strong; the principal point and the mount true.
CameraIntrinsics wrong_lens_camera() {
  CameraIntrinsics k = true_camera();
  k.fx *= 1.01;
  k.fy *= 1.01;
  k.distortion[0] *= 1.1;
  return k;
}

// Without turns the principal point shifts the image as a shift of every pose does; only the
// lens's perspective and distortion over many views tell them apart. A drive that does not show
// it keeps it at the input's value (its prior is no evidence); one that does estimates it. A
// drive of 2.7 s (1.1 m) does not show it (its sigma without the prior, 1.1 px, is over the
// 0.5 px limit), one of a minute (4.8 m) does (0.2 px). From three inputs: the true calibration is
// kept (no evidence against it), a wrong one is replaced and its poses are no worse than the
// input's. Before the principal point was held, the short drive moved a true principal point by
// its prior's pull (0.8 px), and the wrong lens's poses went from 1.3 to 5.1 mm RMS.
TEST(DriveCalibration, AStraightDriveMovesThePrincipalPointOnlyWhereItShowsIt) {
  struct Input {
    const char* name;
    CameraIntrinsics camera;
    RigidTransform mount;
  };
  const Input inputs[] = {{"true", true_camera(), true_mount()},
                          {"perturbed", perturbed_camera(), perturbed_mount()},
                          {"wrong lens", wrong_lens_camera(), true_mount()}};
  for (const double seconds : {2.7, 60.0}) {
    for (const Input& input : inputs) {
      const SyntheticDrive drive = observe_drive(straight_drive(seconds, seconds < 10 ? 0.4 : 0.08), marker_grid(),
                                                 true_camera(), true_mount(), input.camera, input.mount, 0.1, 12);
      const CalibrationResult result = calibrate_from_drive(drive.observations, input.camera, input.mount, {});
      std::printf("%.1f s straight, %s input: %s\n", seconds, input.name, result.ok ? "calibrated" : result.message.c_str());
      print(result);
      SCOPED_TRACE(std::to_string(seconds) + " s, " + input.name + " input");
      if (std::string(input.name) == "true") {
        EXPECT_FALSE(result.ok);
        EXPECT_NE(result.message.find("no evidence against the input"), std::string::npos) << result.message;
        continue;
      }
      ASSERT_TRUE(result.ok) << result.message;
      for (const char* name : {"cx", "cy"}) {
        const auto found = std::find_if(result.parameters.begin(), result.parameters.end(), [&](const auto& p) { return p.name == name; });
        ASSERT_NE(found, result.parameters.end());
        if (seconds < 10) {
          EXPECT_EQ(found->state, ParameterState::fixed) << name << " " << found->value << " input " << found->input;
          EXPECT_EQ(found->value, found->input) << name;
          EXPECT_NE(found->reason.find("not observable on this drive alone"), std::string::npos) << found->reason;
        } else {
          EXPECT_EQ(found->state, ParameterState::estimated) << name << " " << found->reason;
        }
      }
      // A held principal point keeps the input's error, which the other parameters then absorb.
      if (seconds > 10 || std::string(input.name) == "wrong lens") expect_within_sigmas(result, input.mount);
      const PoseErrors start = pose_errors(starting_poses(drive.observations), drive.truth);
      const PoseErrors after = pose_errors(result.poses, drive.truth);
      std::printf("  poses (x, y): %.2f mm -> %.2f mm RMS\n", start.planar_rms * 1e3, after.planar_rms * 1e3);
      // Better than the input's, or within what the estimate's own noise gives (the minute's
      // principal point sigma, 0.2 px, is 1 mm at f / 2.3 m).
      EXPECT_LT(after.planar_rms, std::max(start.planar_rms, 0.002));
    }
  }
}

// Each dot with a bias of its own (0.06 px, a detector's systematic error) over noise of 0.02 px:
// the sigmas from the scatter make the refined calibration's small fit to the biases look
// significant, but it explains the dots barely better than the true input: the input stands.
TEST(DriveCalibration, KeepsATrueCalibrationThatOnlySystematicErrorsDisputes) {
  const SyntheticDrive drive = observe_drive(wheeled_drive(), marker_grid(), true_camera(), true_mount(), true_camera(),
                                             true_mount(), 0.02, 11, 0.06);
  CalibrationOptions statistics_only;
  statistics_only.min_residual_gain = 0;
  const CalibrationResult fooled = calibrate_from_drive(drive.observations, true_camera(), true_mount(), statistics_only);
  EXPECT_TRUE(fooled.ok) << "the statistical test alone should take the biases for evidence: " << fooled.message;
  const CalibrationResult result = calibrate_from_drive(drive.observations, true_camera(), true_mount(), {});
  print(result);
  EXPECT_FALSE(result.ok);
  EXPECT_NE(result.message.find("explains the dots no better than the input calibration"), std::string::npos) << result.message;
  EXPECT_GT(result.change_chi2, result.chance_chi2);
  EXPECT_GT(result.after.rms_px, 0.9 * result.input_refit_rms_px);
}

TEST(DriveCalibration, RefusesADriveOfTooFewPoses) {
  const std::vector<TimedPose> full = wheeled_drive();
  const SyntheticDrive drive = observe_drive(std::vector<TimedPose>(full.begin(), full.begin() + 5), marker_grid(), true_camera(), true_mount(), true_camera(), true_mount(), 0.1, 4);
  const CalibrationResult result = calibrate_from_drive(drive.observations, true_camera(), true_mount(), {});
  EXPECT_FALSE(result.ok);
  EXPECT_NE(result.message.find("need at least 10"), std::string::npos);
}

// The analytic derivatives of a pixel with respect to the lens parameters, against central
// differences through CameraModel, for every model.
TEST(LensParameters, JacobianMatchesCentralDifferences) {
  CameraIntrinsics plumb_bob = true_camera();
  plumb_bob.distortion = {-0.12, 0.05, 0.001, -0.002, 0.01};
  CameraIntrinsics equidistant = true_camera();
  equidistant.model = LensModel::equidistant;
  equidistant.distortion = {0.02, -0.01, 0.003, -0.001, 0};
  CameraIntrinsics equisolid = true_camera();
  equisolid.model = LensModel::equisolid;
  equisolid.distortion = {};
  for (const CameraIntrinsics& lens : {plumb_bob, equidistant, equisolid}) {
    for (const Eigen::Vector3d& point : {Eigen::Vector3d(0.3, -0.2, 1.0), Eigen::Vector3d(-0.5, 0.4, 1.2), Eigen::Vector3d(0.01, 0.02, 2.0)}) {
      Eigen::Vector2d pixel;
      ASSERT_TRUE(CameraModel(lens).project(point, pixel));
      const calibration::LensJacobian jacobian = calibration::lens_jacobian(lens, point, pixel);
      for (int i = 0; i < calibration::lens_parameter_count(lens.model); ++i) {
        const double step = i < 4 ? 1e-4 : 1e-6;
        CameraIntrinsics plus = lens, minus = lens;
        calibration::set_lens_parameter(plus, i, calibration::lens_parameter(lens, i) + step);
        calibration::set_lens_parameter(minus, i, calibration::lens_parameter(lens, i) - step);
        Eigen::Vector2d pixel_plus, pixel_minus;
        ASSERT_TRUE(CameraModel(plus).project(point, pixel_plus));
        ASSERT_TRUE(CameraModel(minus).project(point, pixel_minus));
        const Eigen::Vector2d numeric = (pixel_plus - pixel_minus) / (2 * step);
        EXPECT_LT((jacobian.col(i) - numeric).norm(), 1e-5 * (1 + numeric.norm()))
            << calibration::lens_parameter_name(lens.model, i) << " model " << static_cast<int>(lens.model);
      }
      EXPECT_TRUE(jacobian.rightCols(calibration::kMaxLensParameters - calibration::lens_parameter_count(lens.model)).isZero());
    }
  }
}

}  // namespace
}  // namespace irloc::test

namespace irloc::test {
namespace {

// Under dof 4 the mount's z is every pose's z; under dof 6 also its roll and pitch are every
// pose's: they are fixed with the reason, and the drive still calibrates the lens (its focal
// length only as well as its prior: the poses' heights are free). Every third pose of the drive.
TEST(DriveCalibration, UnderDof4And6TheMountParametersThePosesCarryAreFixed) {
  std::vector<TimedPose> path;
  for (const TimedPose& pose : wheeled_drive()) {
    if (path.empty() || pose.t - path.back().t > 2.5 * kFramePeriod) path.push_back(pose);
  }
  for (const Dof dof : {Dof::height4, Dof::full6}) {
    const SyntheticDrive drive = observe_drive(path, marker_grid(), true_camera(), true_mount(),
                                               perturbed_camera(), perturbed_mount(), 0.1, 6);
    CalibrationOptions options;
    options.dof = dof;
    const CalibrationResult result = calibrate_from_drive(drive.observations, perturbed_camera(), perturbed_mount(), options);
    print(result);
    ASSERT_TRUE(result.ok) << result.message;
    std::vector<std::string> fixed;
    for (const calibration::ParameterEstimate& p : result.parameters) {
      if (p.state == ParameterState::fixed) fixed.push_back(p.name);
    }
    const auto is_fixed = [&](const char* name) { return std::find(fixed.begin(), fixed.end(), name) != fixed.end(); };
    EXPECT_TRUE(is_fixed("mount z"));
    EXPECT_EQ(is_fixed("mount roll"), dof == Dof::full6);
    EXPECT_EQ(is_fixed("mount pitch"), dof == Dof::full6);
    expect_within_sigmas(result, perturbed_mount());
    EXPECT_LT(result.after.rms_px, 0.2);
    const auto fx = std::find_if(result.parameters.begin(), result.parameters.end(), [](const auto& p) { return p.name == "fx"; });
    EXPECT_EQ(fx->state, ParameterState::prior_bound);
    const PoseErrors after = pose_errors(result.poses, drive.truth);
    std::printf("  dof %d poses: %.2f mm (x, y: %.2f mm) / %.4f deg RMS\n", static_cast<int>(dof), after.position_rms * 1e3,
                after.planar_rms * 1e3, after.yaw_rms / kDegree);
    EXPECT_LT(after.planar_rms, axle_offset_error() + 0.0015);
    EXPECT_LT(after.yaw_rms, 0.05 * kDegree);
  }
}

}  // namespace
}  // namespace irloc::test
