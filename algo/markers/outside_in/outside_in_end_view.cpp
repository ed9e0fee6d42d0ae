// OutsideInSource's use of the end faces the appearance fit sees (end_face_looks.hpp): learned while
// a track knows the robot's front, and telling it where a track does not.
#include <cmath>
#include <cstdlib>
#include <numbers>

#include "algo/markers/outside_in/outside_in_source.hpp"

namespace irloc::outside_in {
namespace {

// Views in a row that tell the same branch before the track takes it.
constexpr int kEndVotes = 3;

}  // namespace

void OutsideInSource::use_end_view(const EndView& end, double fit_yaw, bool confident) {
  if (end.side == 0) return;
  // +1: the end seen is the front as the track's heading has it.
  const int side = std::cos(track_.heading.yaw() - fit_yaw) >= 0 ? end.side : -end.side;
  if (track_.heading_known && (!track_.branch_from_travel || track_.branch.confirmed())) {
    if (confident) end_looks_.learn(end, side > 0);
    return;
  }
  const int told = end_looks_.tell(end);
  if (told == 0) return;
  const int vote = told * side;  // +1: the track's heading is the robot's
  track_.end_votes = (vote > 0) == (track_.end_votes > 0) ? track_.end_votes + vote : vote;
  if (std::abs(track_.end_votes) < kEndVotes) return;
  if (track_.end_votes < 0) track_.heading.turn_by(std::numbers::pi);
  track_.pose.yaw = track_.heading.yaw();
  track_.heading_known = true;
  track_.branch.confirm();
  track_.end_votes = 0;
}

}  // namespace irloc::outside_in
