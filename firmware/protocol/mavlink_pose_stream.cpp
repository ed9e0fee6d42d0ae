#include "firmware/protocol/mavlink_pose_stream.hpp"

#include <algorithm>
#include <cmath>

#include "firmware/protocol/mavlink_messages.hpp"
#include "firmware/protocol/ned_frame.hpp"

namespace irloc::firmware {

std::span<const std::uint8_t> MavlinkPoseStream::encode(const PoseEstimate& estimate) {
  used_ = 0;
  // A frame clock that went back must not silence the heartbeat until it catches up.
  if (!last_heartbeat_ns_ || estimate.t_ns < *last_heartbeat_ns_ ||
      estimate.t_ns - *last_heartbeat_ns_ >= settings_.heartbeat_period_ns) {
    append_heartbeat();
    last_heartbeat_ns_ = estimate.t_ns;
  }
  if (estimate.ok) {
    update_reset_counter(estimate);
    append_vision_position(estimate);
  }
  return {buffer_.data(), used_};
}

void MavlinkPoseStream::append_heartbeat() {
  std::array<std::uint8_t, Heartbeat::kPayloadSize> payload{};
  const std::span<const std::uint8_t> bytes = write_payload(Heartbeat{}, payload);
  used_ += encode_mavlink2(std::span(buffer_).subspan(used_), settings_.address, sequence_++, Heartbeat::kId,
                           Heartbeat::kCrcExtra, bytes);
}

void MavlinkPoseStream::update_reset_counter(const PoseEstimate& estimate) {
  if (last_good_ && !settings_.fixed_frame) {
    const double jump = std::hypot(estimate.x - last_good_->x, estimate.y - last_good_->y, estimate.z - last_good_->z);
    const double gap_s = static_cast<double>(estimate.t_ns - last_good_->t_ns) * 1e-9;
    if (jump > settings_.reset_jump_m || gap_s > settings_.reset_after_loss_s || gap_s < 0) ++reset_counter_;
  }
  last_good_ = estimate;
}

void MavlinkPoseStream::append_vision_position(const PoseEstimate& estimate) {
  const NedPose ned = ned_from_world(estimate);
  VisionPositionEstimate message;
  message.usec = static_cast<std::uint64_t>(std::max<std::int64_t>(estimate.t_ns, 0) / 1000);
  message.x = static_cast<float>(ned.north);
  message.y = static_cast<float>(ned.east);
  message.z = static_cast<float>(ned.down);
  message.roll = static_cast<float>(ned.roll);
  message.pitch = static_cast<float>(ned.pitch);
  message.yaw = static_cast<float>(ned.yaw);
  PoseCovariance covariance = ned_covariance(estimate.covariance);
  for (int i = 0; i < 6; ++i) {
    covariance(i, i) += std::pow(i < 3 ? settings_.position_floor_m : settings_.angle_floor_rad, 2);
  }
  // The upper-right triangle, row by row.
  std::size_t k = 0;
  for (int row = 0; row < 6; ++row) {
    for (int column = row; column < 6; ++column) message.covariance[k++] = static_cast<float>(covariance(row, column));
  }
  message.reset_counter = reset_counter_;

  std::array<std::uint8_t, VisionPositionEstimate::kPayloadSize> payload{};
  const std::span<const std::uint8_t> bytes = write_payload(message, payload);
  used_ += encode_mavlink2(std::span(buffer_).subspan(used_), settings_.address, sequence_++,
                           VisionPositionEstimate::kId, VisionPositionEstimate::kCrcExtra, bytes);
}

}  // namespace irloc::firmware
