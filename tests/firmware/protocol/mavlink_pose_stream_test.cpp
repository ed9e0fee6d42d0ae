// The MAVLink pose stream's behaviour: heartbeat timing, no estimate for a failed attempt,
// reset_counter on relocalization, sequence numbers, and no
// allocation per attempt. (Field-by-field decoding by an independent decoder is in
// mavlink_decoder_test.cpp.)

#include <cstdint>
#include <span>
#include <vector>

#include <gtest/gtest.h>

#include "firmware/protocol/mavlink_frame.hpp"
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

TEST(MavlinkPoseStream, HeartbeatOncePerSecondAndEstimatesOnlyForGoodPoses) {
  MavlinkPoseStream stream({});
  std::vector<std::uint32_t> ids;
  for (int i = 0; i < 60; ++i) {
    PoseEstimate pose = good_pose(i * 50'000'000LL, 1.0);
    pose.ok = i % 3 != 0;
    for (const FrameHeader& frame : frames_in(stream.encode(pose))) ids.push_back(frame.message_id);
  }
  // 3 s of attempts at 20 Hz: heartbeats at 0, 1 and 2 s; 40 good poses.
  EXPECT_EQ(std::count(ids.begin(), ids.end(), 0u), 3);
  EXPECT_EQ(std::count(ids.begin(), ids.end(), 102u), 40);
  EXPECT_EQ(ids.front(), 0u);
}

TEST(MavlinkPoseStream, SequenceNumbersCountEveryFrame) {
  MavlinkPoseStream stream({});
  std::vector<std::uint8_t> sequences;
  for (int i = 0; i < 300; ++i) {
    for (const FrameHeader& frame : frames_in(stream.encode(good_pose(i * 10'000'000LL, 1.0)))) sequences.push_back(frame.sequence);
  }
  for (std::size_t i = 0; i < sequences.size(); ++i) EXPECT_EQ(sequences[i], static_cast<std::uint8_t>(i));
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

TEST(MavlinkPoseStream, AFrameClockThatJumpsBackKeepsTheHeartbeatAndCountsAReset) {
  MavlinkPoseStream stream({});
  std::vector<std::uint32_t> ids;
  // 1 s at 20 Hz, then the clock goes back an hour: 2 s more at 20 Hz.
  for (int i = 0; i < 60; ++i) {
    const std::int64_t t_ns = i * 50'000'000LL - (i >= 20 ? 3'600'000'000'000LL : 0);
    for (const FrameHeader& frame : frames_in(stream.encode(good_pose(t_ns, 1.0)))) ids.push_back(frame.message_id);
  }
  // Heartbeats at 0 s, at the jump, and 1 s after it.
  EXPECT_EQ(std::count(ids.begin(), ids.end(), 0u), 3);
  EXPECT_EQ(stream.reset_counter(), 1);  // the estimator must not fuse across the jump
}

TEST(MavlinkPoseStream, EncodingAllocatesNothing) {
  MavlinkPoseStream stream({});
  stream.encode(good_pose(0, 1.0));
  test::AllocationCounter counter;
  std::size_t bytes = 0;
  for (int i = 1; i < 100; ++i) bytes += stream.encode(good_pose(i * 20'000'000LL, 1.0)).size();
  EXPECT_EQ(counter.count(), 0u);
  EXPECT_GT(bytes, 0u);
}

}  // namespace
}  // namespace irloc::firmware
