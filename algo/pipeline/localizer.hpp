#pragma once
// The per-frame pipeline: a strobe pair in, one pose attempt out. The same object runs in
// irlocd on the robot, in replay, and in irloc-sim.

#include <Eigen/Geometry>

#include "algo/geometry/camera_intrinsics.hpp"
#include "algo/geometry/pose.hpp"
#include "algo/markers/marker_map.hpp"
#include "algo/pipeline/pose_estimate.hpp"
#include "algo/pipeline/strobe_pairer.hpp"

namespace irloc {

// Everything the pipeline is set up with; fixed for the lifetime of a Localizer.
struct LocalizerSetup {
  CameraIntrinsics camera;
  Eigen::Isometry3d mount = Eigen::Isometry3d::Identity();  // T_B_C
  Dof dof = Dof::planar3;
  MarkerMap map;
};

class Localizer {
 public:
  // Allocates every buffer the per-frame path needs; process() allocates nothing.
  explicit Localizer(LocalizerSetup setup);

  // One pose attempt for the pair's LED-on frame. Frames must have the calibrated size.
  PoseEstimate process(const StrobePair& pair);

  const LocalizerSetup& setup() const { return setup_; }

 private:
  LocalizerSetup setup_;
};

}  // namespace irloc
