#include "firmware/protocol/stargazer_pose_stream.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "algo/geometry/pose.hpp"

namespace irloc::firmware {
namespace {

constexpr char kDeadZone[] = "~*DeadZone`";

// The host commands' view of irloc's map and link.
StarGazerParameters parameters_of(const MarkerMap& map, double mark_height_m, std::string_view version, int baud_rate) {
  StarGazerParameters parameters;
  parameters.version = version;
  parameters.baud_rate = baud_rate;
  parameters.id_count = static_cast<int>(map.dot_markers.size());
  for (const DotMarker& marker : map.dot_markers) {
    if (parameters.reference_id == 0 || marker.id < parameters.reference_id) parameters.reference_id = marker.id;
  }
  parameters.mark_height_mm = static_cast<int>(std::lround(std::max(0.0, mark_height_m) * 1000));
  return parameters;
}

double mean_landmark_z(const MarkerMap& map) {
  double sum = 0;
  int count = 0;
  for (const DotMarker& marker : map.dot_markers) {
    sum += marker.origin.z();
    ++count;
  }
  for (const SquareMarker& marker : map.square_markers) {
    for (const Eigen::Vector3d& corner : marker.corners) {
      sum += corner.z() / 4;
    }
    ++count;
  }
  for (const LedLandmark& landmark : map.led_landmarks) {
    sum += landmark.position.z();
    ++count;
  }
  return count > 0 ? sum / count : 0.0;
}

}  // namespace

StarGazerPoseStream::StarGazerPoseStream(const MarkerMap& map, double camera_height_m, std::string_view version, int baud_rate)
    : mean_landmark_z_(mean_landmark_z(map)),
      camera_height_m_(camera_height_m),
      commands_(parameters_of(map, mean_landmark_z(map) - camera_height_m, version, baud_rate)) {
  for (const DotMarker& marker : map.dot_markers) dot_marker_z_.emplace_back(marker.id, marker.origin.z());
}

std::span<const std::uint8_t> StarGazerPoseStream::receive(std::span<const std::uint8_t> bytes, std::int64_t /*now_ns*/) {
  return commands_.receive(bytes);
}

double StarGazerPoseStream::landmark_z(int marker_id) const {
  for (const auto& [id, z] : dot_marker_z_) {
    if (id == marker_id) return z;
  }
  return mean_landmark_z_;
}

std::span<const std::uint8_t> StarGazerPoseStream::encode(const PoseEstimate& estimate) {
  if (!commands_.calculating()) return {};
  int length = 0;
  if (!estimate.ok) {
    length = std::snprintf(buffer_.data(), buffer_.size(), "%s", kDeadZone);
  } else {
    // wrap_angle gives (-pi, pi]; the degrees keep that range.
    const double angle_deg = wrap_angle(estimate.yaw) * 180.0 / std::numbers::pi;
    const StarGazerParameters& parameters = commands_.parameters();
    const double height_cm = parameters.height_fixed
                                 ? parameters.mark_height_mm / 10.0
                                 : std::max(0.0, landmark_z(estimate.marker_id) - estimate.z - camera_height_m_) * 100.0;
    length = std::snprintf(buffer_.data(), buffer_.size(), "~^I%d|%+.2f|%+.2f|%+.2f|%.2f`", std::max(estimate.marker_id, 0),
                           angle_deg, estimate.x * 100.0, estimate.y * 100.0, height_cm);
  }
  // Only absurd coordinates (beyond 1e80 m) overflow the buffer: nothing is sent for them.
  if (length < 0 || static_cast<std::size_t>(length) >= buffer_.size()) length = 0;
  return {reinterpret_cast<const std::uint8_t*>(buffer_.data()), static_cast<std::size_t>(length)};
}

}  // namespace irloc::firmware
