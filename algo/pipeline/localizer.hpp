#pragma once
// The per-frame pipeline: a strobe pair in, one pose attempt out. The same object runs in
// irlocd on the robot, in replay, and in irloc-sim.

#include <memory>

#include <Eigen/Geometry>

#include "algo/geometry/camera_intrinsics.hpp"
#include "algo/geometry/pose.hpp"
#include "algo/markers/dot/dot_path.hpp"
#include "algo/markers/marker_map.hpp"
#include "algo/pipeline/pose_estimate.hpp"
#include "algo/pipeline/stage_times.hpp"
#include "algo/pipeline/strobe_pairer.hpp"

namespace irloc {

// Everything the pipeline is set up with; fixed for the lifetime of a Localizer.
struct LocalizerSetup {
  CameraIntrinsics camera;
  Eigen::Isometry3d mount = Eigen::Isometry3d::Identity();  // T_B_C
  Dof dof = Dof::planar3;
  MarkerMap map;
  dot::DotPathConfig dot;  // the dot-marker path, used when the map has dot markers
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

 private:
  LocalizerSetup setup_;
  std::unique_ptr<dot::DotPath> dot_path_;
  StageClock::Times stage_times_;
};

}  // namespace irloc
