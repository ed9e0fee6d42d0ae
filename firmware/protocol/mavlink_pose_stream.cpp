#include "firmware/protocol/mavlink_pose_stream.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "firmware/protocol/mavlink_messages.hpp"
#include "firmware/protocol/ned_frame.hpp"

namespace irloc::firmware {

namespace {

constexpr std::uint8_t kMavStateStandby = 3;
constexpr std::uint8_t kMavStateActive = 4;
constexpr std::uint8_t kMavStateCritical = 5;
constexpr std::uint64_t kOriginEveryHeartbeats = 10;

std::uint64_t usec_of(std::int64_t t_ns) { return static_cast<std::uint64_t>(std::max<std::int64_t>(t_ns, 0) / 1000); }

// MAVLink's upper-right triangle of a 6x6 covariance, row by row.
std::array<float, 21> upper_triangle(const Eigen::Matrix<double, 6, 6>& covariance) {
  std::array<float, 21> triangle{};
  std::size_t k = 0;
  for (int row = 0; row < 6; ++row) {
    for (int column = row; column < 6; ++column) triangle[k++] = static_cast<float>(covariance(row, column));
  }
  return triangle;
}

std::uint8_t system_status(LinkHealth health) {
  switch (health) {
    case LinkHealth::starting: return kMavStateStandby;
    case LinkHealth::active: return kMavStateActive;
    case LinkHealth::critical: return kMavStateCritical;
  }
  return kMavStateCritical;
}

}  // namespace

template <typename Message>
void MavlinkPoseStream::append(const Message& message) {
  std::array<std::uint8_t, Message::kPayloadSize> payload{};
  const std::span<const std::uint8_t> bytes = write_payload(message, payload);
  const std::size_t written = encode_mavlink2(std::span(buffer_).subspan(used_), settings_.address, sequence_, Message::kId,
                                              Message::kCrcExtra, bytes);
  if (written == 0) return;
  used_ += written;
  ++sequence_;
}

std::span<const std::uint8_t> MavlinkPoseStream::encode(const PoseEstimate& estimate) {
  used_ = 0;
  if (estimate.ok) {
    update_reset_counter(estimate);
    if (settings_.pose_message == MavlinkPoseMessage::odometry) {
      append_odometry(estimate);
    } else {
      append_vision_position(estimate);
    }
  }
  return {buffer_.data(), used_};
}

std::span<const std::uint8_t> MavlinkPoseStream::tick(std::int64_t now_ns) {
  used_ = 0;
  // A clock that went back must not silence the heartbeat until it catches up.
  if (!last_heartbeat_ns_ || now_ns < *last_heartbeat_ns_ || now_ns - *last_heartbeat_ns_ >= settings_.heartbeat_period_ns) {
    if (settings_.ekf_origin && heartbeats_ % kOriginEveryHeartbeats == 0) append_origin(now_ns);
    append_heartbeat();
    // On the period's grid, so that ticks arriving a little late do not stretch the period; a
    // link that fell behind by a whole period (or a clock that jumped) starts a new grid.
    const bool on_grid = last_heartbeat_ns_ && now_ns >= *last_heartbeat_ns_ &&
                         now_ns - *last_heartbeat_ns_ < 2 * settings_.heartbeat_period_ns;
    last_heartbeat_ns_ = on_grid ? *last_heartbeat_ns_ + settings_.heartbeat_period_ns : now_ns;
  }
  return {buffer_.data(), used_};
}

std::span<const std::uint8_t> MavlinkPoseStream::receive(std::span<const std::uint8_t> bytes, std::int64_t now_ns) {
  used_ = 0;
  for (const std::uint8_t byte : bytes) {
    const std::optional<ReceivedMavlinkFrame> frame = receiver_.push(byte);
    if (!frame || frame->message_id != Timesync::kId) continue;
    const Timesync request = read_timesync(frame->payload);
    if (request.tc1 != 0) continue;  // an answer to someone else's request
    Timesync answer;
    answer.tc1 = now_ns;
    answer.ts1 = request.ts1;
    answer.target_system = frame->system_id;
    answer.target_component = frame->component_id;
    if (buffer_.size() - used_ < kMavlink2MaxFrame) break;  // the rest waits for the sender's retry
    append(answer);
  }
  return {buffer_.data(), used_};
}

std::span<const std::uint8_t> MavlinkPoseStream::warning(std::string_view text) {
  used_ = 0;
  StatusText message;
  const std::size_t chunks = std::max<std::size_t>(1, (text.size() + StatusText::kTextSize - 1) / StatusText::kTextSize);
  // A text longer than one chunk carries a non-zero id shared by its chunks.
  if (chunks > 1) {
    if (++last_text_id_ == 0) ++last_text_id_;
    message.id = last_text_id_;
  }
  const std::size_t sent_chunks = std::min<std::size_t>(chunks, buffer_.size() / kMavlink2MaxFrame);
  for (std::size_t chunk = 0; chunk < sent_chunks; ++chunk) {
    message.text.fill('\0');
    const std::string_view part = text.substr(std::min(text.size(), chunk * StatusText::kTextSize), StatusText::kTextSize);
    std::copy(part.begin(), part.end(), message.text.begin());
    message.chunk_seq = static_cast<std::uint8_t>(chunk);
    append(message);
  }
  return {buffer_.data(), used_};
}

void MavlinkPoseStream::append_heartbeat() {
  Heartbeat heartbeat;
  heartbeat.system_status = system_status(health_);
  append(heartbeat);
  ++heartbeats_;
}

void MavlinkPoseStream::append_origin(std::int64_t now_ns) {
  SetGpsGlobalOrigin origin;
  origin.latitude = static_cast<std::int32_t>(std::lround(settings_.ekf_origin->latitude_deg * 1e7));
  origin.longitude = static_cast<std::int32_t>(std::lround(settings_.ekf_origin->longitude_deg * 1e7));
  origin.altitude = static_cast<std::int32_t>(std::lround(settings_.ekf_origin->altitude_m * 1000));
  origin.time_usec = usec_of(now_ns);
  append(origin);
}

void MavlinkPoseStream::update_reset_counter(const PoseEstimate& estimate) {
  if (last_good_ && !settings_.fixed_frame) {
    const double jump = std::hypot(estimate.x - last_good_->x, estimate.y - last_good_->y, estimate.z - last_good_->z);
    const double gap_s = static_cast<double>(estimate.t_ns - last_good_->t_ns) * 1e-9;
    if (jump > settings_.reset_jump_m || gap_s > settings_.reset_after_loss_s || gap_s < 0) ++reset_counter_;
  }
  last_good_ = estimate;
}

std::array<float, 21> MavlinkPoseStream::pose_covariance(const PoseEstimate& estimate) const {
  PoseCovariance covariance = ned_covariance(estimate.covariance);
  for (int i = 0; i < 6; ++i) {
    covariance(i, i) += std::pow(i < 3 ? settings_.position_floor_m : settings_.angle_floor_rad, 2);
  }
  return upper_triangle(covariance);
}

void MavlinkPoseStream::append_vision_position(const PoseEstimate& estimate) {
  const NedPose ned = ned_from_world(estimate);
  VisionPositionEstimate message;
  message.usec = usec_of(estimate.t_ns);
  message.x = static_cast<float>(ned.north);
  message.y = static_cast<float>(ned.east);
  message.z = static_cast<float>(ned.down);
  message.roll = static_cast<float>(ned.roll);
  message.pitch = static_cast<float>(ned.pitch);
  message.yaw = static_cast<float>(ned.yaw);
  message.covariance = pose_covariance(estimate);
  message.reset_counter = reset_counter_;
  append(message);
}

void MavlinkPoseStream::append_odometry(const PoseEstimate& estimate) {
  const NedPose ned = ned_from_world(estimate);
  Odometry message;
  message.time_usec = usec_of(estimate.t_ns);
  message.x = static_cast<float>(ned.north);
  message.y = static_cast<float>(ned.east);
  message.z = static_cast<float>(ned.down);
  const Eigen::Quaterniond q = ned_attitude(ned);
  message.q = {static_cast<float>(q.w()), static_cast<float>(q.x()), static_cast<float>(q.y()), static_cast<float>(q.z())};
  message.pose_covariance = pose_covariance(estimate);
  // Roll and pitch rates are not measured; without a track, neither is the velocity.
  constexpr float kUnknown = std::numeric_limits<float>::quiet_NaN();
  message.rollspeed = message.pitchspeed = kUnknown;
  if (estimate.velocity) {
    const FrdVelocity frd = frd_velocity(estimate, *estimate.velocity);
    message.vx = static_cast<float>(frd.velocity.x());
    message.vy = static_cast<float>(frd.velocity.y());
    message.vz = static_cast<float>(frd.velocity.z());
    message.yawspeed = static_cast<float>(frd.heading_rate);
    // (vx, vy, vz, heading rate) into the 6x6 of (vx, vy, vz, rollspeed, pitchspeed, yawspeed).
    Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Constant(kUnknown);
    const std::array<int, 4> rows{0, 1, 2, 5};
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) covariance(rows[i], rows[j]) = frd.covariance(i, j);
    }
    message.velocity_covariance = upper_triangle(covariance);
  } else {
    message.vx = message.vy = message.vz = message.yawspeed = kUnknown;
    message.velocity_covariance.fill(kUnknown);
  }
  message.reset_counter = reset_counter_;
  message.quality = static_cast<std::int8_t>(std::clamp<long>(std::lround(estimate.confidence * 100), 1, 100));
  append(message);
}

}  // namespace irloc::firmware
