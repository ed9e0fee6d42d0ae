// The MAVLink pose stream's behaviour: heartbeat timing on the link's clock whatever the
// attempts do, system_status, no estimate for a failed attempt, reset_counter on relocalization,
// sequence numbers, STATUSTEXT chunks, TIMESYNC answers, and no allocation per call. (Field-by-field decoding by an independent decoder is in
// mavlink_decoder_test.cpp.)

#include <array>
#include <cstdint>
#include <string>
#include <span>
#include <vector>

#include <gtest/gtest.h>

#include "firmware/protocol/mavlink_frame.hpp"
#include "firmware/protocol/mavlink_messages.hpp"
#include "firmware/protocol/mavlink_pose_stream.hpp"
#include "tests/support/allocation_counter.hpp"

namespace irloc::firmware {
namespace {

struct FrameHeader {
  std::uint32_t message_id;
  std::uint8_t sequence;
  std::size_t payload_size;
};

// Splits a byte run into frames by their length fields, checking the magic byte.
std::vector<FrameHeader> frames_in(std::span<const std::uint8_t> bytes) {
  std::vector<FrameHeader> frames;
  std::size_t at = 0;
  while (at < bytes.size()) {
    EXPECT_EQ(bytes[at], kMavlink2Magic);
    const std::size_t length = bytes[at + 1];
    frames.push_back({static_cast<std::uint32_t>(bytes[at + 7] | bytes[at + 8] << 8 | bytes[at + 9] << 16), bytes[at + 4], length});
    at += kMavlink2HeaderSize + length + kMavlink2ChecksumSize;
  }
  EXPECT_EQ(at, bytes.size());
  return frames;
}

PoseEstimate good_pose(std::int64_t t_ns, double x) {
  PoseEstimate pose;
  pose.ok = true;
  pose.t_ns = t_ns;
  pose.x = x;
  pose.confidence = 0.5;
  return pose;
}

TEST(MavlinkPoseStream, EstimatesOnlyForGoodPosesAndNoHeartbeatFromAttempts) {
  MavlinkPoseStream stream({});
  std::vector<std::uint32_t> ids;
  for (int i = 0; i < 60; ++i) {
    PoseEstimate pose = good_pose(i * 50'000'000LL, 1.0);
    pose.ok = i % 3 != 0;
    for (const FrameHeader& frame : frames_in(stream.encode(pose))) ids.push_back(frame.message_id);
  }
  EXPECT_EQ(ids, std::vector<std::uint32_t>(40, 102u));
}

TEST(MavlinkPoseStream, HeartbeatOncePerSecondOfTheLinksClockWithoutAnyAttempt) {
  MavlinkPoseStream stream({});
  std::vector<std::uint32_t> ids;
  // 3.5 s of ticks every 50 ms and no attempt at all (the camera is gone).
  for (int i = 0; i < 70; ++i) {
    for (const FrameHeader& frame : frames_in(stream.tick(i * 50'000'000LL))) ids.push_back(frame.message_id);
  }
  EXPECT_EQ(ids, std::vector<std::uint32_t>(4, 0u));  // at 0, 1, 2 and 3 s
}

TEST(MavlinkPoseStream, LateTicksDoNotStretchTheHeartbeatPeriod) {
  MavlinkPoseStream stream({});
  std::size_t heartbeats = 0;
  // Ticks every 47 ms (a link polling at up to 50 ms) for 100 s: 100 heartbeats, not 1 every 1.034 s.
  for (std::int64_t t = 0; t < 100'000'000'000LL; t += 47'000'000) heartbeats += frames_in(stream.tick(t)).size();
  EXPECT_EQ(heartbeats, 100u);
}

// The system_status byte of each heartbeat in `bytes` (payload offset 7 of HEARTBEAT).
std::vector<int> statuses_in(std::span<const std::uint8_t> bytes) {
  std::vector<int> statuses;
  std::size_t at = 0;
  for (const FrameHeader& frame : frames_in(bytes)) {
    if (frame.message_id == 0) statuses.push_back(bytes[at + kMavlink2HeaderSize + 7]);
    at += kMavlink2HeaderSize + frame.payload_size + kMavlink2ChecksumSize;
  }
  return statuses;
}

TEST(MavlinkPoseStream, SystemStatusSaysStandbyActiveCritical) {
  MavlinkPoseStream stream({});
  std::vector<int> statuses;
  const auto tick_at = [&](double seconds) {
    for (const int status : statuses_in(stream.tick(static_cast<std::int64_t>(seconds * 1e9)))) statuses.push_back(status);
  };
  tick_at(0);
  stream.set_health(LinkHealth::active);
  tick_at(1);
  stream.set_health(LinkHealth::critical);
  tick_at(2);
  tick_at(2.5);
  tick_at(3);
  stream.set_health(LinkHealth::active);
  tick_at(4);
  EXPECT_EQ(statuses, (std::vector<int>{3, 4, 5, 5, 4}));  // MAV_STATE_STANDBY, ACTIVE, CRITICAL
}

TEST(MavlinkPoseStream, SequenceNumbersCountEveryFrame) {
  MavlinkPoseStream stream({});
  std::vector<std::uint8_t> sequences;
  for (int i = 0; i < 300; ++i) {
    for (const FrameHeader& frame : frames_in(stream.tick(i * 10'000'000LL))) sequences.push_back(frame.sequence);
    for (const FrameHeader& frame : frames_in(stream.encode(good_pose(i * 10'000'000LL, 1.0)))) sequences.push_back(frame.sequence);
    if (i % 50 == 0) {
      for (const FrameHeader& frame : frames_in(stream.warning("strobe resynchronised"))) sequences.push_back(frame.sequence);
    }
  }
  EXPECT_EQ(sequences.size(), 300u + 3u + 6u);
  for (std::size_t i = 0; i < sequences.size(); ++i) EXPECT_EQ(sequences[i], static_cast<std::uint8_t>(i));
}

TEST(MavlinkPoseStream, LongWarningsGoOutInChunksShortOnesInOne) {
  MavlinkPoseStream stream({});
  EXPECT_EQ(frames_in(stream.warning("camera back after 0.5 s")).size(), 1u);
  EXPECT_EQ(frames_in(stream.warning(std::string(50, 'x'))).size(), 1u);
  EXPECT_EQ(frames_in(stream.warning(std::string(51, 'x'))).size(), 2u);
  EXPECT_EQ(frames_in(stream.warning(std::string(255, 'x'))).size(), 6u);
}

TEST(MavlinkPoseStream, AnswersTimesyncRequestsOnlyWithTheArrivalTime) {
  MavlinkPoseStream stream({});
  const auto frame_of = [](const Timesync& message, std::uint32_t id, std::uint8_t crc_extra) {
    std::array<std::uint8_t, Timesync::kPayloadSize> payload{};
    std::vector<std::uint8_t> frame(kMavlink2MaxFrame);
    frame.resize(encode_mavlink2(frame, {1, 1}, 9, id, crc_extra, write_payload(message, payload)));
    return frame;
  };
  Timesync request;
  request.ts1 = 123'456'789;
  const std::vector<std::uint8_t> bytes = frame_of(request, Timesync::kId, Timesync::kCrcExtra);
  // Line noise, then the request, then another message (a HEARTBEAT, not read), then the request again.
  Heartbeat heartbeat;
  std::array<std::uint8_t, Heartbeat::kPayloadSize> heartbeat_payload{};
  std::vector<std::uint8_t> other(kMavlink2MaxFrame);
  other.resize(encode_mavlink2(other, {1, 1}, 10, Heartbeat::kId, Heartbeat::kCrcExtra, write_payload(heartbeat, heartbeat_payload)));
  std::vector<std::uint8_t> received{0x00, 0x42, 0x13};
  received.insert(received.end(), bytes.begin(), bytes.end());
  received.insert(received.end(), other.begin(), other.end());
  received.insert(received.end(), bytes.begin(), bytes.end());
  std::span<const std::uint8_t> answer = stream.receive(received, 5'000'000'000);
  ASSERT_EQ(frames_in(answer).size(), 2u);
  EXPECT_EQ(frames_in(answer)[0].message_id, Timesync::kId);
  const Timesync decoded = read_timesync(answer.subspan(kMavlink2HeaderSize, frames_in(answer)[0].payload_size));
  EXPECT_EQ(decoded.tc1, 5'000'000'000);
  EXPECT_EQ(decoded.ts1, 123'456'789);
  EXPECT_EQ(decoded.target_system, 1);
  EXPECT_EQ(decoded.target_component, 1);

  Timesync answer_from_elsewhere = request;
  answer_from_elsewhere.tc1 = 42;  // not a request: no answer
  EXPECT_TRUE(stream.receive(frame_of(answer_from_elsewhere, Timesync::kId, Timesync::kCrcExtra), 6).empty());
  std::vector<std::uint8_t> corrupt = bytes;
  corrupt[kMavlink2HeaderSize] ^= 0x01;  // a checksum error: no answer
  EXPECT_TRUE(stream.receive(corrupt, 7).empty());
}

TEST(MavlinkPoseStream, ResetCounterCountsJumpsAndReacquisitions) {
  MavlinkStreamSettings settings;
  settings.reset_jump_m = 0.5;
  settings.reset_after_loss_s = 1.0;
  MavlinkPoseStream stream(settings);
  stream.encode(good_pose(0, 1.0));
  stream.encode(good_pose(50'000'000, 1.2));  // small step: the same track
  EXPECT_EQ(stream.reset_counter(), 0);
  stream.encode(good_pose(100'000'000, 2.0));  // 0.8 m jump: relocalized
  EXPECT_EQ(stream.reset_counter(), 1);
  PoseEstimate lost;
  lost.t_ns = 600'000'000;
  stream.encode(lost);
  stream.encode(good_pose(1'200'000'000, 2.0));  // 1.1 s after the last good pose
  EXPECT_EQ(stream.reset_counter(), 2);
  stream.encode(good_pose(1'250'000'000, 2.0));
  EXPECT_EQ(stream.reset_counter(), 2);
}

// Outside-in cameras share the room's frame: however their poses jump or pause, the counter that
// the vehicle keeps once for all of them stays the same.
TEST(MavlinkPoseStream, AFixedFrameNeverCountsAReset) {
  MavlinkStreamSettings settings;
  settings.fixed_frame = true;
  MavlinkPoseStream stream(settings);
  stream.encode(good_pose(0, 1.0));
  stream.encode(good_pose(100'000'000, 2.0));    // 1 m on: another camera's view
  stream.encode(good_pose(3'000'000'000, 2.0));  // 2.9 s without a pose
  stream.encode(good_pose(1'000'000'000, 2.0));  // the clock went back
  EXPECT_EQ(stream.reset_counter(), 0);
}

TEST(MavlinkPoseStream, AFrameClockThatJumpsBackCountsAReset) {
  MavlinkPoseStream stream({});
  // 1 s at 20 Hz, then the frame clock goes back an hour: 2 s more at 20 Hz.
  for (int i = 0; i < 60; ++i) {
    const std::int64_t t_ns = i * 50'000'000LL - (i >= 20 ? 3'600'000'000'000LL : 0);
    stream.encode(good_pose(t_ns, 1.0));
  }
  EXPECT_EQ(stream.reset_counter(), 1);  // the estimator must not fuse across the jump
}

TEST(MavlinkPoseStream, ALinkClockThatJumpsBackKeepsTheHeartbeat) {
  MavlinkPoseStream stream({});
  std::size_t heartbeats = 0;
  for (int i = 0; i < 60; ++i) {
    const std::int64_t t_ns = i * 50'000'000LL - (i >= 20 ? 3'600'000'000'000LL : 0);
    heartbeats += frames_in(stream.tick(t_ns)).size();
  }
  EXPECT_EQ(heartbeats, 3u);  // at 0 s, at the jump, and 1 s after it
}

TEST(MavlinkPoseStream, EncodingAllocatesNothing) {
  MavlinkPoseStream stream({});
  stream.encode(good_pose(0, 1.0));
  test::AllocationCounter counter;
  std::size_t bytes = 0;
  for (int i = 1; i < 100; ++i) {
    bytes += stream.encode(good_pose(i * 20'000'000LL, 1.0)).size();
    bytes += stream.tick(i * 20'000'000LL).size();
    bytes += stream.warning("no LED contrast in 60 pairs in a row: check the LED ring, its driver and the lens").size();
  }
  EXPECT_EQ(counter.count(), 0u);
  EXPECT_GT(bytes, 0u);
}

}  // namespace
}  // namespace irloc::firmware
