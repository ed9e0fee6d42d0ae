#pragma once
// What every pose source is handed for one pose attempt: the frame the pose is for and, in
// strobed mode, its LED-off partner and the pair's shared pass. The Localizer checks both frames
// once before any source runs: same pixel depth, the calibrated size. A source never sees a frame
// it would have to refuse for its size.

#include "algo/frames/frame.hpp"
#include "algo/geometry/rigid_transform.hpp"
#include "algo/kernels/pair_pass.hpp"

namespace irloc {

// The Localizer's last pose (of any source, fused), for sources that must tell apart landmarks
// that look alike (two squares of one dash pattern).
struct PosePrior {
  RigidTransform world_from_base;
  std::int64_t t_ns = 0;  // of the frame it was found in
};

struct SourceInput {
  const Frame& on;    // the LED-on frame (in outside-in mode: the one frame)
  const Frame* off;   // its LED-off partner; nullptr when it has none
  // With off: the pair's one shared pass (pair_pass.hpp), already run by the Localizer: the noise
  // of the difference, the threshold and blobs, the strobe counts. A source that needs its blobs at
  // another threshold may relabel it (the blobs then change for the sources after it).
  PairPass* pair = nullptr;
  const PosePrior* prior = nullptr;  // nullptr until the Localizer has found a pose
};

}  // namespace irloc
