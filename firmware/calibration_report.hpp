#pragma once
// The text of OUT_DIR/calibration_report.txt written by `irlocd --calibrate OUT_DIR`: the drive,
// the residuals before and after, each parameter with its sigma, and the parameters the drive
// could not observe with the reason (docs/calibration.md).

#include <cstddef>
#include <string>

#include "algo/calibration/drive_calibration.hpp"

namespace irloc::firmware {

std::string calibration_report(const calibration::CalibrationResult& result, std::size_t frames_dropped,
                               const std::string& config_file);

}  // namespace irloc::firmware
