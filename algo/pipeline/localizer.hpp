#pragma once
// The per-frame pipeline: a strobe pair in, one pose attempt out. The same object runs in
// irlocd on the robot, in replay, and in irloc-sim.

#include <memory>

#include <Eigen/Geometry>

#include "algo/geometry/camera_intrinsics.hpp"
#include "algo/geometry/pose.hpp"
#include "algo/markers/dot/dot_path.hpp"
#include "algo/map/marker_map.hpp"
#include "algo/markers/square/square_config.hpp"
#include "algo/markers/square/square_detector.hpp"
#include "algo/pipeline/pose_estimate.hpp"
#include "algo/pipeline/pose_fusion.hpp"
#include "algo/frames/stage_times.hpp"
#include "algo/frames/strobe_pairer.hpp"

namespace irloc {

// Everything the pipeline is set up with; fixed for the lifetime of a Localizer.
struct LocalizerSetup {
  CameraIntrinsics camera;
  Eigen::Isometry3d mount = Eigen::Isometry3d::Identity();  // T_B_C
  Dof dof = Dof::planar3;
  MarkerMap map;
  dot::DotPathConfig dot;  // the dot-marker path, used when the map has dot markers
  // The square tape marker path, used when the map has exactly one square marker and the robot
  // is level (dof 3 or 4). When both paths find a pose they are fused (source `fused`).
  SquareConfig square;
  FusionGate fusion;
};

class Localizer {
 public:
  // Allocates every buffer the per-frame path needs; process() allocates nothing.
  explicit Localizer(LocalizerSetup setup);

  // One pose attempt for the pair's LED-on frame. Frames must have the calibrated size.
  PoseEstimate process(const StrobePair& pair);

  const LocalizerSetup& setup() const { return setup_; }
  // Per-stage wall-clock times of the last process().
  const StageClock::Times& last_stage_times() const { return stage_times_; }
  // The dot path, or nullptr when the map has no dot markers.
  const dot::DotPath* dot_path() const { return dot_path_.get(); }
  // The square path, or nullptr when it is not in use.
  const SquareDetector* square_path() const { return square_path_.get(); }
  // The square path's result for the last pair (outcome no_square when it did not run).
  const SquareDetection& last_square() const { return last_square_; }

 private:
  PoseEstimate fuse(const PoseEstimate& dot_pose, const PoseEstimate& square_pose) const;

  LocalizerSetup setup_;
  std::unique_ptr<dot::DotPath> dot_path_;
  std::unique_ptr<SquareDetector> square_path_;
  SquareDetection last_square_;
  StageClock::Times stage_times_;
};

}  // namespace irloc
