#include "algo/pipeline/localizer.hpp"

#include <utility>

namespace irloc {

Localizer::Localizer(LocalizerSetup setup) : setup_(std::move(setup)) {}

PoseEstimate Localizer::process(const StrobePair& pair) {
  PoseEstimate estimate;
  estimate.seq = pair.on.seq;
  estimate.t_ns = pair.on.t_ns;
  // No marker path is wired in yet: every attempt is reported as `none`.
  estimate.ok = false;
  return estimate;
}

}  // namespace irloc
