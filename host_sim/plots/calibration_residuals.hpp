#pragma once
// Reads OUT_DIR/residuals.csv, which `irlocd --calibrate OUT_DIR` writes (docs/calibration.md):
// every dot's pixel and its reprojection residual before and after the calibration.

#include <filesystem>
#include <vector>

#include <Eigen/Core>

namespace irloc::sim {

struct DotResidualRow {
  Eigen::Vector2d pixel, before, after;
};

// Throws io::InputError naming the file and line of the first malformed row.
std::vector<DotResidualRow> read_calibration_residuals(const std::filesystem::path& csv);

}  // namespace irloc::sim
