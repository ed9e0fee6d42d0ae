#pragma once
// Several wall cameras watching one robot (issue 14): each camera's irlocd sends its own poses;
// the robot takes them all. The combined stream, frame by frame: the robot is covered when any
// camera has it whole in view, posed when any camera gives a pose, and the combined pose is the
// pose of the camera that sees the robot at the finest scale (fewest metres per pixel at the
// pose: its box fit's covariance is the smallest). The choice uses the poses only, never the truth.

#include <vector>

#include <Eigen/Core>

#include "algo/pipeline/pose_estimate.hpp"
#include "host_sim/metrics/outside_in_metrics.hpp"
#include "host_sim/render/outside_in_dataset.hpp"
#include "host_sim/render/wall_camera.hpp"

namespace irloc::sim {

struct CameraHandOver {
  // Per frame: whole in view when any camera has the robot whole in view, hidden the least
  // hidden fraction among those cameras (so that compute_outside_in_metrics scores the coverage).
  std::vector<OutsideInTruth> truth;
  std::vector<PoseEstimate> poses;  // per frame: the chosen camera's ok pose, or a `none` row
  std::vector<int> camera;          // per frame: the chosen camera's index, -1 for none
  int hand_overs = 0;               // changes of the posing camera (frames without a pose between do not count)
};

// truth[i] and poses[i] are camera i's (its render truth and its irlocd's pose CSV rows), every
// camera's truth over the same frames.
CameraHandOver combine_cameras(const std::vector<WallCamera>& cameras, const std::vector<std::vector<OutsideInTruth>>& truth,
                               const std::vector<std::vector<PoseEstimate>>& poses);

// Metres on the floor per pixel of `camera` at the floor point `position`: range over focal length.
double metres_per_pixel(const WallCamera& camera, const Eigen::Vector2d& position);

}  // namespace irloc::sim
