#include "algo/pipeline/localizer.hpp"

#include <utility>

namespace irloc {

Localizer::Localizer(LocalizerSetup setup) : setup_(std::move(setup)) {
  if (!setup_.map.dot_markers.empty()) {
    dot_path_ = std::make_unique<dot::DotPath>(setup_.camera, setup_.mount, setup_.dof, setup_.map, setup_.dot);
  }
}

PoseEstimate Localizer::process(const StrobePair& pair) {
  stage_times_.clear();
  if (dot_path_) return dot_path_->process(pair, stage_times_);
  PoseEstimate estimate;
  estimate.seq = pair.on.seq;
  estimate.t_ns = pair.on.t_ns;
  // No marker path is wired in yet: every attempt is reported as `none`.
  estimate.ok = false;
  return estimate;
}

}  // namespace irloc
