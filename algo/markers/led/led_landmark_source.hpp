#pragma once
// The active IR LED landmark pose source (docs/led_landmarks.md): always-on LEDs at known places
// on the walls or the ceiling, without IDs. Per pose attempt: detect the LEDs in the strobe pair
// (led_detector.hpp), then track them from the last poses or, when there is no track, search the
// association (led_association.hpp); the pose and its covariance come from the non-linear least
// squares fit of the matched LEDs' reprojection error under the robot's dof; under a rolling
// shutter, the pose at the frame's t_ns (fitted there with the motion within the frame, known or
// fitted: LedAssociator::set_rolling_shutter; else a plain fit moved there by
// move_fit_to_frame_time, algo/source/rolling_shutter.hpp).
//
//   LedLandmarkSource source(setup, config);   // start-up: allocates every buffer
//   source.process(input, result);             // per frame: allocates nothing

#include <cstdint>

#include "algo/frames/stage_times.hpp"
#include "algo/geometry/camera_model.hpp"
#include "algo/markers/led/led_association.hpp"
#include "algo/markers/led/led_config.hpp"
#include "algo/markers/led/led_detector.hpp"
#include "algo/source/pose_source.hpp"

namespace irloc::led {

// What the source's last process() saw: views of its own state, valid until the next process().
struct LedDiagnostics {
  const LedDetectionList& detections;    // the LEDs detected in the pair
  const LedDetectionCounters& counters;  // why the other spots were refused
  const LedGlareList& glare;             // the boxes of those refused for size or shape
  // The last attempt's association (the search's when tracking failed): its outcome and margin.
  const LedAssociation& association;
  int hypotheses;  // minimal-set solutions the last search tried (0 when it tracked)
};

class LedLandmarkSource final : public PoseSource {
 public:
  LedLandmarkSource(const SourceSetup& setup, const LedSourceConfig& config);

  SourceKind kind() const override { return SourceKind::led; }
  void process(const SourceInput& input, SourceResult& result) override;
  // Ends the track and forgets the last poses.
  void restart() override;

  // What the last process() saw, for reports and tests (LedDiagnostics, above).
  LedDiagnostics last_diagnostics() const { return {detections_, counters_, glare_, association_, last_hypotheses_}; }

 private:
  RigidTransform predicted_pose(std::int64_t t_ns) const;
  // The association's search at t_ns, its minimal-set winner confirmed by a track no older than
  // track_timeout (since_last: seconds since the last pose), refused when out of reach.
  void search(std::int64_t t_ns, double since_last, const MotionLimits& limits);
  // Under a rolling shutter, the robot's motion within the input's frame: the Localizer's track's,
  // else this source's own last two poses', while recent; empty when neither is known.
  std::optional<FrameMotion> motion_within_frame(const SourceInput& input) const;
  // Under a rolling shutter: the result's pose at t_ns and its observations' pixels moved there.
  void pose_at_frame_time(const SourceInput& input, SourceResult& result) const;
  // The robot can have moved from the last pose to `pose` by t_ns (led_config.hpp, continuity).
  bool within_reach(const RigidTransform& pose, std::int64_t t_ns, const MotionLimits& limits) const;
  // The fit's horizontal position and yaw standard deviations are within max_position_sigma and
  // max_yaw_sigma (covariance: x, y, z, roll, pitch, yaw).
  bool certain_enough(const Eigen::Matrix<double, 6, 6>& covariance) const;

  LedSourceConfig config_;
  CameraModel camera_;
  RigidTransform base_from_camera_;
  Dof dof_;
  const MarkerMap& map_;
  LedDetector detector_;
  LedAssociator associator_;
  StageClock clock_;
  LedDetectionList detections_;
  LedDetectionCounters counters_;
  LedGlareList glare_;
  StaticVector<Eigen::Vector3d, kMaxLedDetections> bearings_;
  LedAssociation association_;
  int last_hypotheses_ = 0;

  // The track: the last two poses and their times.
  int track_length_ = 0;
  RigidTransform last_pose_, previous_pose_;
  std::int64_t last_t_ns_ = 0, previous_t_ns_ = 0;
  bool has_pose_ = false;  // last_pose_ holds a pose (it is kept when the track is lost)
};

}  // namespace irloc::led
