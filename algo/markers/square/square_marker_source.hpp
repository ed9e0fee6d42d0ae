#pragma once
// The square tape marker source: the map's square seen by the SquareDetector, reported in the
// shape of every source (algo/source/pose_source.hpp). Its observations are the four corners of
// each square the pose is from (landmark: the square's index in the map). Under a rolling shutter
// the detector fits the sides to the tape points moved to the frame's t_ns (TapePoints::collect,
// algo/source/rolling_shutter.hpp), so the pose and corners are those at t_ns. The motion is the
// track's, else the one the frame's own tape shows (SquareDetector::fit_motion: its uncertainty
// is added to the covariance); where the tape does not show it either, the pose as seen, its
// covariance allowing for the fastest robot.

#include "algo/geometry/camera_model.hpp"
#include "algo/markers/square/square_config.hpp"
#include "algo/markers/square/square_detector.hpp"
#include "algo/source/pose_source.hpp"

namespace irloc::square {

class SquareMarkerSource final : public PoseSource {
 public:
  // Uses every square marker of the map. Throws std::invalid_argument as SquareDetector does.
  SquareMarkerSource(const SourceSetup& setup, const SquareConfig& config);

  SourceKind kind() const override { return SourceKind::square; }
  void process(const SourceInput& input, SourceResult& result) override;

  const SquareDetector& detector() const { return detector_; }
  // The detector's result for the last pair (outcome no_square when there was no LED-off frame).
  const SquareDetection& last_diagnostics() const { return detection_; }

 private:
  // detection_ for the input's pair; true when its pose is the one at t_ns (a global shutter,
  // or the motion within the frame known).
  bool detect(const SourceInput& input, const RigidTransform* prior);
  SquareDetector detector_;
  SquareDetection detection_;
  // Of (x, y, yaw): the uncertainty of the frame's own motion, when detect() used it; else zero.
  Eigen::Matrix3d own_motion_covariance_ = Eigen::Matrix3d::Zero();
  // The motion detect() moved the tape with, where the poses before the frame told it (the track's,
  // or the arc from the last pose to this frame's fit); else empty.
  std::optional<FrameMotion> motion_from_track_;
  // Where detect() used the frame's own motion: the square's pose as seen (the plain fit), which
  // the track takes (SourceResult::plain_fit), and its corners' mean row time after t_ns, when it
  // holds (SourceResult::plain_fit_delay_ns).
  std::optional<RigidTransform> plain_fit_;
  std::int64_t plain_fit_delay_ns_ = 0;
  std::int64_t max_prior_age_ns_;  // an older SourceInput::prior is not used
};

}  // namespace irloc::square
