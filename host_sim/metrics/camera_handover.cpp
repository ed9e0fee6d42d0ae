#include "host_sim/metrics/camera_handover.hpp"

#include <limits>
#include <map>

#include "io/input_error.hpp"

namespace irloc::sim {

double metres_per_pixel(const WallCamera& camera, const Eigen::Vector2d& position) {
  const Eigen::Vector3d centre = camera.world_from_camera().translation;
  return (Eigen::Vector3d(position.x(), position.y(), 0) - centre).norm() / camera.intrinsics.fx;
}

CameraHandOver combine_cameras(const std::vector<WallCamera>& cameras, const std::vector<std::vector<OutsideInTruth>>& truth,
                               const std::vector<std::vector<PoseEstimate>>& poses) {
  if (cameras.empty() || truth.size() != cameras.size() || poses.size() != cameras.size()) {
    throw io::InputError("combine_cameras: one truth and one pose list per camera expected");
  }
  std::vector<std::map<std::uint64_t, const PoseEstimate*>> ok_by_seq(cameras.size());
  for (std::size_t i = 0; i < cameras.size(); ++i) {
    if (truth[i].size() != truth[0].size()) throw io::InputError("combine_cameras: the cameras' truth differ in length");
    for (const PoseEstimate& pose : poses[i]) {
      if (pose.ok) ok_by_seq[i][pose.seq] = &pose;
    }
  }
  CameraHandOver result;
  int last_camera = -1;
  for (std::size_t frame = 0; frame < truth[0].size(); ++frame) {
    OutsideInTruth combined = truth[0][frame];
    combined.whole_in_view = false;
    combined.hidden_fraction = 1;
    int chosen = -1;
    double finest = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < cameras.size(); ++i) {
      const OutsideInTruth& seen = truth[i][frame];
      if (seen.whole_in_view) {
        combined.whole_in_view = true;
        combined.hidden_fraction = std::min(combined.hidden_fraction, seen.hidden_fraction);
      }
      const auto found = ok_by_seq[i].find(seen.pose.seq);
      if (found == ok_by_seq[i].end()) continue;
      const double scale = metres_per_pixel(cameras[i], {found->second->x, found->second->y});
      if (scale < finest) {
        finest = scale;
        chosen = static_cast<int>(i);
      }
    }
    if (!combined.whole_in_view) combined.hidden_fraction = 0;
    PoseEstimate pose;
    if (chosen >= 0) {
      pose = *ok_by_seq[static_cast<std::size_t>(chosen)][combined.pose.seq];
      if (last_camera >= 0 && chosen != last_camera) ++result.hand_overs;
      last_camera = chosen;
    } else {
      pose.seq = combined.pose.seq;
      pose.t_ns = combined.pose.t_ns;
      pose.ok = false;
      pose.source = SourceKind::external;
    }
    result.truth.push_back(combined);
    result.poses.push_back(pose);
    result.camera.push_back(chosen);
  }
  return result;
}

}  // namespace irloc::sim
