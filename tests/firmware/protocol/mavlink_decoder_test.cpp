// The MAVLink pose stream checked by an independent implementation: irlocd's encoder writes
// through the termios serial port into a real pseudo-terminal, and node-mavlink (its own parser,
// CRC_EXTRA table and field decoding) reads the master side. Every field of every message must
// come back as sent: the estimates, the heartbeats with their system_status, a STATUSTEXT in
// chunks, the EKF origin and a TIMESYNC answer; and ODOMETRY, whose decoded attitude and body
// velocity must give back the pose's NED velocity as an autopilot computes it (q * v_FRD).

#include <sys/ioctl.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "algo/pipeline/localizer.hpp"
#include "firmware/protocol/mavlink_messages.hpp"
#include "firmware/protocol/mavlink_pose_stream.hpp"
#include "firmware/protocol/ned_frame.hpp"
#include "hal/linux/termios_serial.hpp"
#include "tests/dot/dot_scene.hpp"
#include "tests/firmware/protocol/node_mavlink_decoder.hpp"
#include "tests/support/pseudo_terminal.hpp"
#include "tests/support/temp_dir.hpp"

namespace irloc::firmware {
namespace {

std::vector<std::string> split(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> fields;
  for (std::string field; in >> field;) fields.push_back(field);
  return fields;
}

// node prints a float32 as the shortest decimal that reads back as the same double.
void expect_float(const std::string& text, float sent, const char* what) {
  EXPECT_EQ(std::stod(text), static_cast<double>(sent)) << what << ": " << text;
}

// Hands `send` a writer into the termios serial port of a pty that node-mavlink reads, and returns
// node-mavlink's lines once the pty is drained.
template <typename Send>
std::vector<std::string> decode_through_pty(Send send) {
  test::TempDir dir;
  test::PseudoTerminal pty;
  test::NodeMavlinkDecoder decoder(pty.master_fd(), dir / "decoded.txt");
  {
    hal::TermiosSerial serial(pty.slave_path(), 921600, 64 * 1024);
    send([&](std::span<const std::uint8_t> bytes) {
      if (!bytes.empty()) {
        ASSERT_TRUE(serial.write_message(bytes));
      }
    });
    // Let the decoder drain the pty before the slave closes (a pty drops unread output on close).
    for (int i = 0; i < 100 && serial.queued_bytes() > 0; ++i) {
      usleep(10'000);
      serial.flush();
    }
    EXPECT_EQ(serial.queued_bytes(), 0u);
    int pending = 1;
    for (int i = 0; i < 300 && pending > 0; ++i) {
      usleep(10'000);
      ioctl(pty.master_fd(), FIONREAD, &pending);
    }
  }
  return decoder.finish();
}

// The covariance the dot source's solver reports for a rendered view of two markers from a
// level robot at (0.3, 0.1), heading 0.8: anisotropic, with cross terms.
PoseCovariance solver_covariance() {
  test::Scene scene;
  const std::vector<DotMarker> markers{test::ceiling_marker(1782, 0.0, 0.0, 0.3), test::ceiling_marker(613, 0.5, 0.2, -1.1)};
  for (const DotMarker& marker : markers) scene.add_marker(marker);
  scene.world_from_base = test::level_pose(0.3, 0.1, 0.8);
  LocalizerSetup setup;
  setup.camera = scene.camera;
  setup.mount = to_rigid(scene.mount);
  setup.map.dot_markers = markers;
  Localizer localizer(setup);
  Image8 on, off;
  scene.render(on, off);
  const PoseEstimate estimate = localizer.process(test::strobe_pair(on, off));
  EXPECT_TRUE(estimate.ok);
  EXPECT_EQ(estimate.covariance, localizer.last_results()[0].covariance);  // the solver's own
  return estimate.covariance;
}

std::vector<PoseEstimate> test_poses() {
  const PoseCovariance covariance = solver_covariance();
  std::vector<PoseEstimate> poses;
  for (int i = 0; i < 120; ++i) {
    PoseEstimate pose;
    pose.seq = static_cast<std::uint64_t>(2 * i);
    pose.t_ns = 1'000'000'000LL + i * 33'333'333LL;
    pose.ok = i % 7 != 3;
    pose.x = 0.1 * i - 3.0;
    pose.y = 1.0 - 0.05 * i + (i >= 60 ? 2.0 : 0.0);  // one relocalization jump
    pose.z = 0.01 * (i % 5);
    pose.roll = 0.01 * (i % 3);
    pose.pitch = -0.02 * (i % 4);
    pose.yaw = std::remainder(0.1 * i, 2 * std::numbers::pi);
    pose.confidence = 0.2 + 0.005 * i;
    pose.marker_id = 1782;
    pose.covariance = covariance * (1 + 0.01 * i);
    poses.push_back(pose);
  }
  return poses;
}

TEST(MavlinkDecoder, NodeMavlinkDecodesEveryFieldFromARealPty) {
  const std::vector<PoseEstimate> poses = test_poses();
  MavlinkStreamSettings settings;
  settings.address = {7, 197};
  // A small floor, so that the solver's part shows beside it in float32.
  settings.position_floor_m = 1e-4;
  settings.angle_floor_rad = 1e-4;
  settings.ekf_origin = GeoOrigin{47.3977419, 8.5455938, 488.25};
  MavlinkPoseStream stream(settings);
  const std::string warning =
      "camera /base/soc/i2c0mux/i2c@1/imx219@10: no frame for 2000 ms: no pose until it is back; reopening every 0.5 s";

  // The message the stream should have built for each good pose, from the same inputs.
  std::vector<VisionPositionEstimate> expected;
  std::vector<std::uint8_t> expected_resets;
  {
    MavlinkPoseStream reference(settings);
    for (const PoseEstimate& pose : poses) {
      reference.encode(pose);
      if (!pose.ok) continue;
      const NedPose ned = ned_from_world(pose);
      VisionPositionEstimate message;
      message.usec = static_cast<std::uint64_t>(pose.t_ns / 1000);
      message.x = static_cast<float>(ned.north);
      message.y = static_cast<float>(ned.east);
      message.z = static_cast<float>(ned.down);
      message.roll = static_cast<float>(ned.roll);
      message.pitch = static_cast<float>(ned.pitch);
      message.yaw = static_cast<float>(ned.yaw);
      // NED flips y, z, pitch and yaw; the floor adds to the variances.
      constexpr double kSign[6] = {1, -1, -1, 1, -1, -1};
      std::size_t k = 0;
      for (int r = 0; r < 6; ++r) {
        for (int c = r; c < 6; ++c) {
          const double floor = r != c ? 0 : std::pow(r < 3 ? settings.position_floor_m : settings.angle_floor_rad, 2);
          message.covariance[k++] = static_cast<float>(kSign[r] * kSign[c] * pose.covariance(r, c) + floor);
        }
      }
      expected.push_back(message);
      expected_resets.push_back(reference.reset_counter());
    }
  }

  const std::vector<std::string> lines = decode_through_pty([&](const auto& write) {
    for (std::size_t i = 0; i < poses.size(); ++i) {
      // The link's clock runs with the frames here; starting until the second pose, critical
      // around 3 s (pose 60), active otherwise.
      if (i == 1) stream.set_health(LinkHealth::active);
      if (i == 55) stream.set_health(LinkHealth::critical);
      if (i == 65) stream.set_health(LinkHealth::active);
      write(stream.tick(poses[i].t_ns));
      write(stream.encode(poses[i]));
      if (i == 10) write(stream.warning(warning));
      if (i == 20) {  // a ground station's TIMESYNC request, split in two reads
        Timesync request;
        request.ts1 = 987'654'321'000LL;
        std::array<std::uint8_t, Timesync::kPayloadSize> payload{};
        std::array<std::uint8_t, kMavlink2MaxFrame> frame{};
        const std::size_t size = encode_mavlink2(frame, {255, 190}, 0, Timesync::kId, Timesync::kCrcExtra,
                                                 write_payload(request, payload));
        EXPECT_TRUE(stream.receive(std::span(frame).first(5), 1'700'000'000).empty());
        write(stream.receive(std::span(frame).subspan(5, size - 5), 1'700'000'000));
      }
    }
  });

  ASSERT_FALSE(lines.empty());
  // The estimates, 4 heartbeats, 1 origin, 3 text chunks, 1 TIMESYNC.
  EXPECT_EQ(lines.back(), "END valid=" + std::to_string(expected.size() + 9) + " invalid=0 unknown=0 crc_errors=0");
  std::size_t estimate = 0;
  std::vector<std::string> statuses;
  std::string text;
  int expected_sequence = 0;
  for (std::size_t l = 0; l + 1 < lines.size(); ++l) {
    const std::vector<std::string> f = split(lines[l]);
    ASSERT_GE(f.size(), 4u) << lines[l];
    EXPECT_EQ(std::stoi(f[1]), expected_sequence++ % 256) << lines[l];
    EXPECT_EQ(f[2], "7");
    EXPECT_EQ(f[3], "197");
    if (f[0] == "HEARTBEAT") {
      ASSERT_EQ(f.size(), 11u);  // and the arrival time
      EXPECT_EQ(std::vector<std::string>(f.begin() + 4, f.begin() + 8), (std::vector<std::string>{"18", "8", "0", "0"}));
      EXPECT_EQ(f[9], "3");
      statuses.push_back(f[8]);
      continue;
    }
    if (f[0] == "ORIGIN") {  // with the first heartbeat
      EXPECT_TRUE(statuses.empty());
      EXPECT_EQ(std::vector<std::string>(f.begin() + 4, f.end()),
                (std::vector<std::string>{"473977419", "85455938", "488250", "0", "1000000"}));
      continue;
    }
    if (f[0] == "STATUSTEXT") {  // severity 4 (WARNING), chunks of one non-zero id
      EXPECT_EQ(f[4], "4");
      EXPECT_EQ(f[5], "1");
      EXPECT_EQ(f[6], std::to_string(text.size() / 50));
      const std::size_t quote = lines[l].find('"');
      text += lines[l].substr(quote + 1, lines[l].size() - quote - 2);
      continue;
    }
    if (f[0] == "TIMESYNC") {  // tc1: the time the request arrived; ts1 as sent; to the requester
      EXPECT_EQ(std::vector<std::string>(f.begin() + 4, f.end()),
                (std::vector<std::string>{"1700000000", "987654321000", "255", "190"}));
      continue;
    }
    ASSERT_EQ(f[0], "VPE");
    ASSERT_EQ(f.size(), 4u + 1u + 7u + 21u + 1u) << lines[l];
    ASSERT_LT(estimate, expected.size());
    const VisionPositionEstimate& sent = expected[estimate];
    EXPECT_EQ(f[5], std::to_string(sent.usec));
    expect_float(f[6], sent.x, "x");
    expect_float(f[7], sent.y, "y");
    expect_float(f[8], sent.z, "z");
    expect_float(f[9], sent.roll, "roll");
    expect_float(f[10], sent.pitch, "pitch");
    expect_float(f[11], sent.yaw, "yaw");
    for (std::size_t c = 0; c < 21; ++c) expect_float(f[12 + c], sent.covariance[c], "covariance");
    EXPECT_EQ(std::stoi(f[33]), expected_resets[estimate]);
    ++estimate;
  }
  EXPECT_EQ(estimate, expected.size());
  // At 1, 2, 3 and 4 s (t = 1.0 .. 4.97 s): standby, active, critical, active.
  EXPECT_EQ(statuses, (std::vector<std::string>{"3", "4", "5", "4"}));
  EXPECT_EQ(text, warning);
  EXPECT_EQ(expected_resets.back(), 1);  // the jump at pose 60
  // The solver's covariance is anisotropic with cross terms, and they reach the autopilot: x-y
  // (index 1) and x-yaw (index 5) are not zero, and x and y variances differ.
  EXPECT_NE(expected.front().covariance[1], 0.0f);
  EXPECT_NE(expected.front().covariance[5], 0.0f);
  EXPECT_NE(expected.front().covariance[0], expected.front().covariance[6]);
}

TEST(MavlinkDecoder, OdometryCarriesThePoseAndTheTracksVelocityInTheFramesAnAutopilotExpects) {
  std::vector<PoseEstimate> poses = test_poses();
  // Every third good pose without a track (its velocity unknown); the others driving at up to 1 m/s.
  for (std::size_t i = 0; i < poses.size(); ++i) {
    if (i % 3 == 0) continue;
    PoseVelocity velocity;
    velocity.world = Eigen::Vector3d(0.8 * std::cos(0.05 * i), -0.6 * std::sin(0.03 * i), 0.02 * (i % 4));
    velocity.yaw_rate = 0.3 - 0.005 * i;
    velocity.covariance = Eigen::Matrix4d::Identity() * 1e-4;
    velocity.covariance(0, 1) = velocity.covariance(1, 0) = 4e-5;
    velocity.covariance(0, 3) = velocity.covariance(3, 0) = -2e-5;
    poses[i].velocity = velocity;
  }
  MavlinkStreamSettings settings;
  settings.address = {7, 197};
  settings.pose_message = MavlinkPoseMessage::odometry;
  MavlinkPoseStream stream(settings);
  const std::vector<std::string> lines = decode_through_pty([&](const auto& write) {
    for (const PoseEstimate& pose : poses) write(stream.encode(pose));
  });

  std::vector<const PoseEstimate*> good;
  for (const PoseEstimate& pose : poses) {
    if (pose.ok) good.push_back(&pose);
  }
  ASSERT_EQ(lines.size(), good.size() + 1);
  EXPECT_EQ(lines.back(), "END valid=" + std::to_string(good.size()) + " invalid=0 unknown=0 crc_errors=0");
  const Eigen::Matrix3d flip = Eigen::Vector3d(1, -1, -1).asDiagonal();
  for (std::size_t l = 0; l < good.size(); ++l) {
    const PoseEstimate& pose = *good[l];
    const std::vector<std::string> f = split(lines[l]);
    ASSERT_EQ(f.size(), 66u) << lines[l];
    ASSERT_EQ(f[0], "ODOMETRY");
    EXPECT_EQ(f[4], "233");  // the payload, no extension truncated (quality is never 0)
    EXPECT_EQ(f[5], std::to_string(pose.t_ns / 1000));
    // Position in NED (x north = x_W, y east = -y_W, z down = -z_W).
    EXPECT_NEAR(std::stod(f[6]), pose.x, 1e-6);
    EXPECT_NEAR(std::stod(f[7]), -pose.y, 1e-6);
    EXPECT_NEAR(std::stod(f[8]), -pose.z, 1e-6);
    // The attitude: R_NED_FRD = F R_W_B F.
    const Eigen::Quaterniond q(std::stod(f[9]), std::stod(f[10]), std::stod(f[11]), std::stod(f[12]));
    const Eigen::Matrix3d expected_attitude = flip * rotation_from_rpy(pose.roll, pose.pitch, pose.yaw) * flip;
    EXPECT_LT((q.toRotationMatrix() - expected_attitude).norm(), 1e-6) << lines[l];
    EXPECT_EQ(f[16], "NaN");  // rollspeed
    EXPECT_EQ(f[17], "NaN");  // pitchspeed
    // The pose covariance as VISION_POSITION_ESTIMATE carries it (the signs of y, z, pitch and yaw
    // flipped, the floors added).
    EXPECT_NEAR(std::stod(f[19]), pose.covariance(0, 0) + std::pow(settings.position_floor_m, 2), 1e-9);
    EXPECT_NEAR(std::stod(f[20]), -pose.covariance(0, 1), 1e-9);
    EXPECT_EQ(f[61], "20");  // MAV_FRAME_LOCAL_FRD
    EXPECT_EQ(f[62], "12");  // MAV_FRAME_BODY_FRD
    EXPECT_EQ(f[64], "3");   // MAV_ESTIMATOR_TYPE_VISION
    EXPECT_EQ(std::stoi(f[65]), std::clamp(static_cast<int>(std::lround(pose.confidence * 100)), 1, 100));
    if (!pose.velocity) {
      for (int c : {13, 14, 15, 18, 40}) EXPECT_EQ(f[c], "NaN") << c;
      continue;
    }
    // What an autopilot does with it: v_NED = q * v_FRD must be the track's velocity in NED.
    const Eigen::Vector3d v_ned = q * Eigen::Vector3d(std::stod(f[13]), std::stod(f[14]), std::stod(f[15]));
    const Eigen::Vector3d& v_world = pose.velocity->world;
    EXPECT_NEAR(v_ned.x(), v_world.x(), 1e-5) << lines[l];
    EXPECT_NEAR(v_ned.y(), -v_world.y(), 1e-5) << lines[l];
    EXPECT_NEAR(v_ned.z(), -v_world.z(), 1e-5) << lines[l];
    EXPECT_NEAR(std::stod(f[18]), -pose.velocity->yaw_rate, 1e-6);  // the NED heading's rate
    // The velocity covariance: a rotation keeps the trace; the yaw rate's variance as it was; the
    // rates that are not measured NaN.
    const double trace = std::stod(f[40]) + std::stod(f[46]) + std::stod(f[51]);
    const double world_trace = pose.velocity->covariance.topLeftCorner<3, 3>().trace();
    EXPECT_NEAR(trace, world_trace, 1e-9);
    EXPECT_NEAR(std::stod(f[60]), pose.velocity->covariance(3, 3), 1e-9);
    EXPECT_EQ(f[43], "NaN");  // vx-rollspeed
  }
}

}  // namespace
}  // namespace irloc::firmware
