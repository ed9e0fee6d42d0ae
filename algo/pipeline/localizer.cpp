#include "algo/pipeline/localizer.hpp"

#include <utility>

namespace irloc {
namespace {

void write_square_pose(const SquareDetection& square, PoseEstimate& estimate) {
  const RollPitchYaw rpy = rpy_from_rotation(square.world_from_base.rotation);
  estimate.ok = true;
  estimate.x = square.world_from_base.translation.x();
  estimate.y = square.world_from_base.translation.y();
  estimate.z = square.world_from_base.translation.z();
  estimate.roll = 0;
  estimate.pitch = 0;
  estimate.yaw = rpy.yaw;
  estimate.marker_id = -1;
  estimate.confidence = square.confidence;
  estimate.source = PoseSource::square;
}

}  // namespace

Localizer::Localizer(LocalizerSetup setup) : setup_(std::move(setup)) {
  if (setup_.map.square_markers.size() == 1 && setup_.dof != Dof::full6) {
    square_path_ = std::make_unique<SquareDetector>(setup_.camera, setup_.mount, setup_.dof,
                                                    setup_.map.square_markers.front(), setup_.square);
  }
}

PoseEstimate Localizer::process(const StrobePair& pair) {
  PoseEstimate estimate;
  estimate.seq = pair.on.seq;
  estimate.t_ns = pair.on.t_ns;
  estimate.ok = false;
  if (square_path_ && pair.off) {
    const SquareDetection square = square_path_->detect(pair.on.image, pair.off->image);
    if (square.found()) write_square_pose(square, estimate);
  }
  return estimate;
}

}  // namespace irloc
