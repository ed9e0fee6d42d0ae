#pragma once

#include <Eigen/Core>

namespace irloc {

// The robot's motion within one frame, taken as constant over it (a frame's rows are read out in
// a few tens of milliseconds): the base origin's velocity in the frame of its heading (x forward,
// y left, z up: Rz(yaw)^T of W) and the rate of yaw. A robot driving an arc keeps both constant.
struct FrameMotion {
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  // m/s, heading frame
  double yaw_rate = 0;                                 // rad/s, about W's z
};

}  // namespace irloc
