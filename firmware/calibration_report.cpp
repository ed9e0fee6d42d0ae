#include "firmware/calibration_report.hpp"

#include <cstdio>
#include <numbers>

namespace irloc::firmware {
namespace {

void append(std::string& text, const char* format, auto... values) {
  char line[512];
  std::snprintf(line, sizeof line, format, values...);
  text += line;
}

const char* state_name(calibration::ParameterState state) {
  switch (state) {
    case calibration::ParameterState::estimated: return "estimated";
    case calibration::ParameterState::prior_bound: return "prior";
    case calibration::ParameterState::fixed: return "fixed";
  }
  return "?";
}

void append_residuals(std::string& text, const char* label, const calibration::ResidualStats& stats) {
  append(text, "  %-7s %zu dots, RMS %.3f px, median %.3f px, max %.3f px\n", label, stats.count, stats.rms_px,
         stats.median_px, stats.max_px);
}

}  // namespace

std::string calibration_report(const calibration::CalibrationResult& result, std::size_t frames_dropped,
                               const std::string& config_file) {
  constexpr double kDegree = std::numbers::pi / 180;
  std::string text = "irlocd --calibrate: self-calibration from the ceiling's dot markers\n";
  append(text, "input config: %s\n\n", config_file.c_str());
  append(text, "drive: %zu poses with dots over %.1f s, %.2f m driven, %.0f deg turned", result.poses.size(),
         result.duration_s, result.driven_m, result.turned_rad / kDegree);
  if (frames_dropped > 0) append(text, " (%zu later poses not used: the drive is capped)", frames_dropped);
  append(text, ", %d distinct views\n", result.views);
  append(text, "evidence against the input: chi-square %.1f of the parameters' change (noise gives up to %.1f)",
         result.change_chi2, result.chance_chi2);
  append(text, "\n%d Levenberg-Marquardt iterations; dot noise from the final residuals %.3f px (scales every sigma)\n\n",
         result.iterations, result.pixel_sigma);
  text += "reprojection residuals of every dot:\n";
  append_residuals(text, "before", result.before);
  append_residuals(text, "after", result.after);
  append(text, "  input, every pose refined to it: RMS %.3f px (the refined calibration must be below %.3f px)\n",
         result.input_refit_rms_px, result.rms_limit_px);
  text += "\nparameters (mount roll/pitch/yaw: rotation about the base's x/y/z axes from the input mount;\n"
          "state: estimated from the drive, prior = mostly its prior, fixed = kept at the input value):\n";
  append(text, "  %-12s %-9s %16s %16s %12s\n", "parameter", "state", "input", "refined", "sigma");
  for (const calibration::ParameterEstimate& p : result.parameters) {
    const bool angle = p.unit == "rad";
    const double scale = angle ? 1 / kDegree : 1;
    const std::string unit = angle ? "deg" : p.unit;
    append(text, "  %-12s %-9s %16.9g %16.9g %12.3g %s\n", p.name.c_str(), state_name(p.state), p.input * scale,
           p.value * scale, p.sigma * scale, unit.c_str());
  }
  text += "\nwhy (priors and parameters the drive could not observe):\n";
  for (const calibration::ParameterEstimate& p : result.parameters) {
    if (!p.reason.empty()) append(text, "  %-12s %s\n", p.name.c_str(), p.reason.c_str());
  }
  return text;
}

}  // namespace irloc::firmware
