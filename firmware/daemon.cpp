#include "firmware/daemon.hpp"

#include <algorithm>
#include <memory>
#include <string_view>

#include "algo/pipeline/localizer.hpp"
#include "firmware/camera_source.hpp"
#include "hal/config/config_file.hpp"
#include "hal/files/pose_csv_writer.hpp"
#include "hal/input_error.hpp"

namespace irloc::firmware {

DaemonSummary run_daemon(const DaemonOptions& options) {
  if (options.serial != "none") {
    throw hal::InputError("--serial " + options.serial + ": serial output is not available in this build yet; use --serial none");
  }
  hal::RobotConfig config = hal::load_robot_config(options.config);
  const CameraIntrinsics& intrinsics = config.setup.camera;
  std::unique_ptr<hal::Camera> camera =
      open_camera(options.camera, intrinsics.width, intrinsics.height, config.calibration_file.string());
  std::optional<hal::PoseCsvWriter> pose_csv;
  if (options.pose_csv) pose_csv.emplace(*options.pose_csv);

  Localizer localizer(std::move(config.setup));
  StrobePairer pairer;
  DaemonSummary summary;

  const auto attempt = [&](const StrobePair& pair) {
    const PoseEstimate estimate = localizer.process(pair);
    ++summary.pose_attempts;
    if (!pair.off) ++summary.unpaired;
    if (estimate.ok) ++summary.poses_ok;
    if (pose_csv) pose_csv->write(estimate);
    for (const StageTime& stage : localizer.last_stage_times()) {
      StageTime* total = std::find_if(summary.stage_totals.begin(), summary.stage_totals.end(),
                                      [&](const StageTime& t) { return std::string_view(t.name) == stage.name; });
      if (total == summary.stage_totals.end()) summary.stage_totals.push_back(stage);
      else total->milliseconds += stage.milliseconds;
    }
  };

  // The per-frame loop: nothing below allocates.
  Frame frame;
  while (camera->next(frame)) {
    ++summary.frames;
    if (const std::optional<StrobePair> pair = pairer.push(frame)) attempt(*pair);
  }
  if (const std::optional<StrobePair> pair = pairer.flush()) attempt(*pair);
  return summary;
}

}  // namespace irloc::firmware
