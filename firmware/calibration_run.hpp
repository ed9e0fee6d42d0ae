#pragma once
// `irlocd --calibrate OUT_DIR`: while the frame loop runs, collects every dot the dot marker
// source's pose fit used (pixel + the map's world point) with that pose; at the end of the
// drive, runs the self-calibration (algo/calibration) and writes
//   OUT_DIR/config.yaml              the same config with the refined mount, calib.yaml beside it,
//                                    the map by absolute path
//   OUT_DIR/calib.yaml               the refined intrinsics (ROS camera_info, the input's model)
//   OUT_DIR/calibration_report.txt   residuals before/after, parameters with sigmas, what the
//                                    drive could not observe and why
//   OUT_DIR/residuals.csv            every dot's residual before and after (for plots)
// Collecting copies the observations into growing vectors (bounded by the drive cap): an
// offline mode of irlocd, not its per-frame contract.

#include <filesystem>
#include <string>
#include <vector>

#include "algo/calibration/drive_observations.hpp"
#include "algo/pipeline/localizer.hpp"
#include "firmware/frame_loop.hpp"

namespace irloc::firmware {

class CalibrationRun final : public AttemptObserver {
 public:
  // The files finish() writes in OUT_DIR (irlocd checks them with its other outputs at start).
  static inline const std::vector<std::string> kOutputFiles = {"calib.yaml", "config.yaml", "calibration_report.txt",
                                                               "residuals.csv"};

  // The input calibration is the localizer's. Throws io::InputError when the map has no dot
  // markers. OUT_DIR is created by finish().
  CalibrationRun(std::filesystem::path out_dir, std::filesystem::path config_file, std::filesystem::path map_file,
                 const Localizer& localizer);

  // Adds the localizer's dot result of the attempt, when its pose fit ran (also below the
  // confidence floor: a wrong calibration is what lowers the confidence) at the frame's t_ns (not
  // a rolling shutter's plain fit: SourceResult::at_frame_time).
  void on_attempt(const StrobePair& pair, std::optional<StrobeVerdict> verdict, bool computed,
                  const PoseEstimate& estimate) override;
  // The same for one source result of the LED-on frame at t_ns (other sources are ignored).
  void add(std::int64_t t_ns, const SourceResult& result);

  // Calibrates, creates OUT_DIR when absent and replaces the files atomically
  // (io::replace_file_atomically); returns a one-line summary. Throws io::InputError (naming
  // OUT_DIR or the drive) when the drive does not allow a calibration or a file cannot be written.
  std::string finish() const;

  const calibration::DriveObservations& drive() const { return drive_; }

 private:
  std::filesystem::path out_dir_;
  std::filesystem::path config_file_;
  std::filesystem::path map_file_;
  const Localizer& localizer_;
  calibration::DriveObservations drive_;
};

}  // namespace irloc::firmware
