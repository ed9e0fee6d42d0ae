#include "algo/calibration/drive_calibration.hpp"

#include <algorithm>
#include <array>
#include <vector>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "algo/calibration/drive_adjustment.hpp"
#include "algo/core/chi_square.hpp"
#include "algo/geometry/pose.hpp"

namespace irloc::calibration {

bool DriveAdjustment::check_motion(CalibrationResult& result) {
  const std::span<const DriveFrame> frames = drive_.frames();
  if (frames.size() < 10) {
    result.message = "the drive gave " + std::to_string(frames.size()) + " poses with dots (need at least 10)";
    return false;
  }
  for (std::size_t k = 0; k + 1 < frames.size(); ++k) {
    result.turned_rad += std::abs(wrap_angle(heading(input_.poses[k + 1]) - heading(input_.poses[k])));
    result.driven_m += (input_.poses[k + 1].translation - input_.poses[k].translation).head<2>().norm();
  }
  result.duration_s = static_cast<double>(frames.back().t_ns - frames.front().t_ns) * 1e-9;
  result.views = fix_by_motion(result.driven_m, result.turned_rad);
  if (result.views >= options_.min_views) return true;
  char text[240];
  std::snprintf(text, sizeof text,
                "the drive shows the ceiling from %d distinct views (%.2f m driven, %.0f deg turned; a view is %.2f m or "
                "%.0f deg from the last): need at least %d",
                result.views, result.driven_m, result.turned_rad * 180 / std::numbers::pi, options_.view_spacing_m,
                options_.view_spacing_rad * 180 / std::numbers::pi, options_.min_views);
  result.message = text;
  return false;
}

GlobalVector DriveAdjustment::drive_sigmas(const NormalEquations& normal, const GlobalMatrix& covariance) const {
  // Without a prior: the sigma with the prior-bound parameters known, so that a parameter only as
  // uncertain as a prior makes it (the focal length through the camera height) is observed. The
  // principal point: its sigma with its prior taken out of the information (a rank-one downdate,
  // var / (1 - var / prior^2)), so that the prior never counts as the drive's evidence.
  GlobalVector sigma = global_covariance(normal, informative_).diagonal().cwiseMax(0).cwiseSqrt();
  for (int g = 0; g < globals_; ++g) {
    if (!held_unless_observed_[static_cast<std::size_t>(g)] || fixed_[static_cast<std::size_t>(g)]) continue;
    const double variance = std::max(covariance(g, g), 0.0);
    const double prior_share = variance / (prior_sigma_[g] * prior_sigma_[g]);
    sigma[g] = prior_share < 1 - 1e-9 ? std::sqrt(variance / (1 - prior_share)) : std::numeric_limits<double>::infinity();
  }
  return sigma;
}

int DriveAdjustment::least_observed(const GlobalVector& drive_sigma, const NormalEquations& normal) const {
  int worst = -1;
  double worst_ratio = 1;
  for (int g = 0; g < globals_; ++g) {
    const std::size_t i = static_cast<std::size_t>(g);
    if (fixed_[i] || (informative_[i] && !held_unless_observed_[i])) continue;
    const int a = g - lenses_;
    const double ratio = g < lenses_ ? drive_sigma[g] * normal.max_sensitivity[g] / options_.max_lens_effect_px
                         : a < 3     ? drive_sigma[g] / options_.max_mount_rotation_sigma_rad
                                     : drive_sigma[g] / options_.max_mount_offset_sigma_m;
    if (!(ratio <= worst_ratio)) {
      worst_ratio = ratio;
      worst = g;
    }
  }
  return worst;
}

void DriveAdjustment::fix_unobservable(int g, const GlobalVector& drive_sigma, const NormalEquations& normal) {
  char text[220];
  const int a = g - lenses_;
  const char* alone = held_unless_observed_[static_cast<std::size_t>(g)] ? " alone (without its prior)" : "";
  if (g < lenses_) {
    std::snprintf(text, sizeof text, "not observable on this drive%s: its sigma (%.3g) moves the dots by %.3g px (limit %.3g px)",
                  alone, drive_sigma[g], drive_sigma[g] * normal.max_sensitivity[g], options_.max_lens_effect_px);
  } else {
    std::snprintf(text, sizeof text, "not observable on this drive%s: sigma %.3g %s (limit %.3g)", alone, drive_sigma[g],
                  a < 3 ? "rad" : "m", a < 3 ? options_.max_mount_rotation_sigma_rad : options_.max_mount_offset_sigma_m);
  }
  fixed_[static_cast<std::size_t>(g)] = true;
  fixed_reason_[static_cast<std::size_t>(g)] = text;
  reset_global(g);
}

// Each round either finds every free parameter observable or fixes one more: it ends.
bool DriveAdjustment::refine_until_observable(CalibrationResult& result, GlobalMatrix& covariance) {
  const double frame_count = static_cast<double>(drive_.frames().size());
  NormalEquations normal;
  while (true) {
    result.iterations += solve();
    // The dots' noise as the residuals show it, per coordinate; then the final solve with it.
    const AdjustmentCost fit = evaluate(state_, nullptr);
    const double redundancy = 2.0 * static_cast<double>(fit.valid) - free_globals() - frame_count * pose_dim_;
    if (redundancy <= 0) {
      result.message = "too few dots for the unknowns";
      return false;
    }
    pixel_sigma_ = std::max(std::sqrt(fit.weighted_sq / redundancy), 1e-3);
    result.iterations += solve();
    evaluate(state_, &normal);
    covariance = global_covariance(normal);
    const GlobalVector drive_sigma = drive_sigmas(normal, covariance);
    const int worst = least_observed(drive_sigma, normal);
    if (worst < 0) return true;
    fix_unobservable(worst, drive_sigma, normal);
  }
}

double DriveAdjustment::input_refit_rms() {
  const AdjustmentState refined = state_;
  const std::array<bool, kMaxGlobals> fixed = fixed_;
  state_ = input_;
  fixed_.fill(true);
  solve();
  std::vector<DotResidual> scratch(drive_.observations().size());
  const double rms = residual_stats(state_, true, scratch).rms_px;
  state_ = refined;
  fixed_ = fixed;
  return rms;
}

void DriveAdjustment::report_parameters(CalibrationResult& result, const GlobalVector& sigma) const {
  for (int g = 0; g < globals_; ++g) {
    const std::size_t i = static_cast<std::size_t>(g);
    ParameterEstimate estimate;
    estimate.name = global_name(g);
    const int a = g - lenses_;
    estimate.unit = g < 4 ? "px" : g < lenses_ ? "" : a < 3 ? "rad" : "m";
    estimate.input = global_value(input_, g);
    estimate.value = global_value(state_, g);
    if (fixed_[i]) {
      estimate.state = ParameterState::fixed;
      estimate.reason = fixed_reason_[i];
    } else {
      estimate.sigma = sigma[g];
      if (informative_[i] && sigma[g] > 0.5 * prior_sigma_[g]) {
        estimate.state = ParameterState::prior_bound;
        estimate.reason = prior_reason_[i];
      } else if (informative_[i]) {
        estimate.reason = "from the drive (" + prior_reason_[i] + ")";
      }
    }
    result.parameters.push_back(estimate);
  }
}

CalibrationResult DriveAdjustment::run() {
  CalibrationResult result;
  result.camera = input_.lens;
  result.mount = input_.mount;
  if (!check_motion(result)) return result;
  result.residuals.resize(drive_.observations().size());
  result.before = residual_stats(input_, false, result.residuals);
  pixel_sigma_ = std::max(result.before.rms_px / std::sqrt(2.0), 0.05);
  GlobalMatrix covariance;
  if (!refine_until_observable(result, covariance)) return result;

  // Evidence against the input: frames of nearly one view are not independent, so the
  // covariance is widened by frames / views.
  result.change_chi2 = change_chi2(covariance) * result.views / static_cast<double>(drive_.frames().size());
  result.chance_chi2 = chi_square_quantile(free_globals(), 1 - options_.evidence_probability);
  if (!(result.change_chi2 > result.chance_chi2)) {
    char text[240];
    std::snprintf(text, sizeof text,
                  "it shows no evidence against the input calibration: the refined parameters differ from it by chi-square "
                  "%.1f over %d parameters (%d views), within what noise gives (%.1f); the input stands",
                  result.change_chi2, free_globals(), result.views, result.chance_chi2);
    result.message = text;
    return result;
  }
  result.after = residual_stats(state_, true, result.residuals);
  result.input_refit_rms_px = input_refit_rms();
  result.rms_limit_px = (1 - options_.min_residual_gain) * result.input_refit_rms_px;
  if (!(result.after.rms_px < result.rms_limit_px)) {
    char text[240];
    std::snprintf(text, sizeof text,
                  "it explains the dots no better than the input calibration: RMS %.4f px with the input (every pose "
                  "refined to it), %.4f px refined (needs %.0f %% less); the input stands",
                  result.input_refit_rms_px, result.after.rms_px, 100 * options_.min_residual_gain);
    result.message = text;
    return result;
  }
  result.ok = true;
  result.camera = state_.lens;
  result.mount = state_.mount;
  result.poses = state_.poses;
  result.pixel_sigma = pixel_sigma_;
  report_parameters(result, covariance.diagonal().cwiseMax(0).cwiseSqrt());
  return result;
}

CalibrationResult calibrate_from_drive(const DriveObservations& drive, const CameraIntrinsics& camera,
                                       const RigidTransform& mount, const CalibrationOptions& options) {
  DriveAdjustment adjustment(drive, camera, mount, options);
  return adjustment.run();
}

}  // namespace irloc::calibration
