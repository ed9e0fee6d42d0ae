#include "firmware/protocol/ned_frame.hpp"

#include "algo/geometry/pose.hpp"

namespace irloc::firmware {

NedPose ned_from_world(const PoseEstimate& estimate) {
  NedPose ned;
  ned.north = estimate.x;
  ned.east = -estimate.y;
  ned.down = -estimate.z;
  ned.roll = wrap_angle(estimate.roll);
  ned.pitch = -estimate.pitch;
  ned.yaw = wrap_angle(-estimate.yaw);
  return ned;
}

}  // namespace irloc::firmware
