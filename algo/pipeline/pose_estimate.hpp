#pragma once
// What one pose attempt produces: a row of the pose CSV, a message on the serial line.

#include <cstdint>

#include "algo/source/source_kind.hpp"
#include "algo/source/source_result.hpp"

namespace irloc {

struct PoseEstimate {
  std::uint64_t seq = 0;  // of the LED-on frame the pose was computed from
  std::int64_t t_ns = 0;
  bool ok = false;        // false: nothing trustworthy, the pose fields mean nothing
  // T_W_B: position in metres, orientation R_W_B = Rz(yaw) Ry(pitch) Rx(roll) in radians.
  double x = 0, y = 0, z = 0, roll = 0, pitch = 0, yaw = 0;
  int marker_id = -1;     // the dot marker's ID, or -1
  double confidence = 0;  // in [0, 1]; 0 when not ok
  SourceKind source = SourceKind::dot;
  // Of (x, y, z, roll, pitch, yaw) in W, from the solver of the source (or the fusion) at its
  // solution; the rows of parameters the dof fixes are zero. Zero when not ok.
  PoseCovariance covariance = PoseCovariance::Zero();
};

}  // namespace irloc
