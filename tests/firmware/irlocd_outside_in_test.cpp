// irlocd in `mode: outside_in` on a rendered wall-camera dataset (host_sim/render's ray-cast outside-in
// scene, written with the dataset writer): one pose row per frame from the external source, poses
// on the robot, and set-ups the mode refuses with one line naming the file and field.

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/config/camera_info_writer.hpp"
#include "io/dataset/dataset_writer.hpp"
#include "tests/outside_in/outside_in_drive.hpp"
#include "tests/support/child_process.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/text_file.hpp"

namespace irloc {
namespace {

using ::testing::HasSubstr;

constexpr int kFrames = 80;
constexpr double kFps = 10;

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::istringstream in(line);
  for (std::string field; std::getline(in, field, ',');) fields.push_back(field);
  return fields;
}

// The dataset is rendered once for the suite (ctest runs it as one process); each test writes
// its own config beside it and its outputs in its own folder.
class IrlocdOutsideIn : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dataset_dir_ = new test::TempDir;
    const test::WallCamera camera;
    io::DatasetWriter writer(dataset());
    test::SceneRenderer renderer(camera);
    for (int i = 0; i < kFrames; ++i) {
      test::SceneState scene;
      scene.robot = test::ellipse_pose(i / kFps);
      test::FrameTruth truth;
      const auto& pixels = renderer.render(scene, truth);
      writer.write(Frame{static_cast<std::uint64_t>(i), static_cast<std::int64_t>(i) * 100'000'000, false,
                         ImageView8(pixels.data(), camera.intrinsics.width, camera.intrinsics.height)});
      truth_[i] = {*scene.robot, truth.robot_whole_in_view};
    }
    std::ofstream(dataset() / "calib.yaml") << io::camera_info_yaml(camera.intrinsics, "wall", "");
    const outside_in::FloorReference reference = test::floor_reference_of(camera);
    std::ostringstream corners;
    corners << "      world: [";
    for (int k = 0; k < 4; ++k) corners << (k ? ", " : "") << "[" << reference.world[k].x() << ", " << reference.world[k].y() << "]";
    corners << "]\n      pixels: [";
    for (int k = 0; k < 4; ++k) corners << (k ? ", " : "") << "[" << reference.pixels[k].x() << ", " << reference.pixels[k].y() << "]";
    corners << "]\n";
    floor_reference_ = corners.str();
  }
  static void TearDownTestSuite() {
    delete dataset_dir_;
    dataset_dir_ = nullptr;
  }
  void SetUp() override { write_config(3, floor_reference_); }

  static std::filesystem::path dataset() { return dataset_dir_->path() / "dataset"; }
  std::filesystem::path config() const { return dataset() / "config.yaml"; }
  void write_config(int dof, const std::string& floor_reference, const std::string& extra = "") {
    std::ofstream(config()) << "mode: outside_in\ncamera:\n  calibration: calib.yaml\n  floor_reference:\n" << floor_reference
                            << "robot:\n  dof: " << dof << "\n  body: {length: 0.60, width: 0.40, height: 0.35}\n" << extra;
  }
  // irlocd on the dataset with `options`.
  test::ProcessResult irlocd_with(const std::vector<std::string>& options) {
    std::vector<std::string> arguments = {IRLOCD_PATH, "--config", config().string(), "--camera", "dir:" + dataset().string()};
    arguments.insert(arguments.end(), options.begin(), options.end());
    return test::run_to_end(std::move(arguments), dir_ / "stderr.txt");
  }
  // The same writing the pose CSV, with `extra` options.
  test::ProcessResult irlocd(const std::vector<std::string>& extra = {}) {
    std::vector<std::string> options = {"--serial", "none", "--pose-csv", (dir_ / "pose.csv").string()};
    options.insert(options.end(), extra.begin(), extra.end());
    return irlocd_with(options);
  }
  void expect_one_line(const test::ProcessResult& run, const std::string& what) {
    EXPECT_EQ(run.status, 1);
    EXPECT_EQ(std::count(run.stderr_text.begin(), run.stderr_text.end(), '\n'), 1) << run.stderr_text;
    EXPECT_THAT(run.stderr_text, HasSubstr(config().string()));
    EXPECT_THAT(run.stderr_text, HasSubstr(what));
  }

  struct Truth {
    outside_in::FloorPose robot;
    bool whole_in_view = false;
  };
  static inline test::TempDir* dataset_dir_ = nullptr;
  static inline std::map<int, Truth> truth_;
  static inline std::string floor_reference_;
  test::TempDir dir_;
};

TEST_F(IrlocdOutsideIn, EveryFrameIsAnExternalPoseAttemptOnTheRobot) {
  const auto [status, errors] = irlocd();
  ASSERT_EQ(status, 0) << errors;
  std::istringstream rows(test::read_text(dir_ / "pose.csv"));
  std::string line;
  std::getline(rows, line);
  int count = 0, scored = 0, posed = 0;
  double sum2 = 0, heading2 = 0;
  while (std::getline(rows, line)) {
    const std::vector<std::string> f = split(line);
    ASSERT_EQ(f.size(), 12u) << line;
    EXPECT_EQ(f[11], "external");
    EXPECT_EQ(f[9], "-1");
    const int seq = std::stoi(f[0]);
    EXPECT_EQ(seq, count++);
    if (seq < 35 || !truth_[seq].whole_in_view) continue;  // the background is learned with the robot in view
    ++scored;
    if (f[2] != "ok") continue;
    ++posed;
    const outside_in::FloorPose& robot = truth_[seq].robot;
    const double error = std::hypot(std::stod(f[3]) - robot.x, std::stod(f[4]) - robot.y);
    const double heading = std::remainder(std::stod(f[8]) - robot.yaw, 2 * std::numbers::pi);
    sum2 += error * error;
    heading2 += heading * heading;
    EXPECT_LT(error, 0.05) << line;
    EXPECT_LT(std::abs(heading), 10 * std::numbers::pi / 180) << line;
  }
  EXPECT_EQ(count, kFrames);
  const double heading_rms_deg = std::sqrt(heading2 / std::max(posed, 1)) * 180 / std::numbers::pi;
  std::printf("outside-in replay: %d of %d frames posed, position RMS %.1f mm, heading RMS %.2f deg\n", posed, scored,
              1000 * std::sqrt(sum2 / std::max(posed, 1)), heading_rms_deg);
  EXPECT_GE(posed, scored * 9 / 10);
  EXPECT_LT(heading_rms_deg, 3.0);
  EXPECT_THAT(errors, HasSubstr(std::to_string(kFrames) + " frames, " + std::to_string(kFrames) + " pose attempts"));
}

TEST_F(IrlocdOutsideIn, AFloorReferenceThatIsNoRectangleIsNamed) {
  write_config(3, "      world: [[2.5, 1.0], [4.5, 1.0], [4.5, -1.0], [2.5, -1.3]]\n"
                  "      pixels: [[100, 100], [500, 100], [500, 300], [100, 300]]\n");
  expect_one_line(irlocd(), "camera.floor_reference");
}

TEST_F(IrlocdOutsideIn, TheModeNeedsDofThreeAndNoSurvey) {
  write_config(4, floor_reference_);
  expect_one_line(irlocd(), "robot.dof: outside-in mode gives the robot's x, y and heading");
  write_config(3, floor_reference_);
  expect_one_line(irlocd({"--survey", (dir_ / "map.yaml").string()}), "--survey needs the camera on the robot");
  write_config(3, floor_reference_, "mode: on_ceiling\n");
  const test::ProcessResult run = irlocd();
  EXPECT_EQ(run.status, 1);
  EXPECT_THAT(run.stderr_text, HasSubstr("mode"));
}

// The outside-in source works on 8-bit frames: 16-bit ones are refused at start, in one line
// naming the camera and the config's mode, before any frame is read.
TEST_F(IrlocdOutsideIn, SixteenBitFramesAreRefusedAtStart) {
  const test::WallCamera camera;
  const std::filesystem::path frames = dir_ / "sixteen_bit";
  {
    io::DatasetWriter writer(frames, 4095);
    const std::vector<std::uint16_t> pixels(static_cast<std::size_t>(camera.intrinsics.width * camera.intrinsics.height), 900);
    for (int i = 0; i < 3; ++i) {
      writer.write(Frame{static_cast<std::uint64_t>(i), static_cast<std::int64_t>(i) * 100'000'000, false,
                         ImageView16(pixels.data(), camera.intrinsics.width, camera.intrinsics.height)});
    }
  }
  std::string text = test::read_text(config());
  text.replace(text.find("calibration: calib.yaml"), 23, "calibration: " + (dataset() / "calib.yaml").string());
  std::ofstream(frames / "config.yaml") << text;
  const test::ProcessResult run = test::run_to_end({IRLOCD_PATH, "--config", (frames / "config.yaml").string(), "--camera",
                                                    "dir:" + frames.string(), "--serial", "none", "--pose-csv",
                                                    (dir_ / "pose.csv").string()},
                                                   dir_ / "stderr.txt");
  EXPECT_EQ(run.status, 1);
  EXPECT_EQ(std::count(run.stderr_text.begin(), run.stderr_text.end(), '\n'), 1) << run.stderr_text;
  EXPECT_THAT(run.stderr_text, HasSubstr("--camera dir:" + frames.string() + ": its frames are 16-bit, but mode: outside_in (" +
                                         (frames / "config.yaml").string() + ") works on 8-bit frames only"));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "pose.csv"));
}

// Two cameras watching one robot: one irlocd each, each with its own MAVLink component ID, both
// streaming to the same UDP port. The autopilot takes both as its one external-navigation source
// (docs/outside_in.md), so both keep the one reset counter of a frame that never jumps: 0.
TEST_F(IrlocdOutsideIn, TwoCamerasStreamOverUdpWithTheirOwnComponentIds) {
  const int socket_fd = socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(bind(socket_fd, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
  socklen_t size = sizeof address;
  getsockname(socket_fd, reinterpret_cast<sockaddr*>(&address), &size);
  const std::string udp = "udp:127.0.0.1:" + std::to_string(ntohs(address.sin_port));
  for (int camera = 0; camera < 2; ++camera) {
    const test::ProcessResult run = irlocd_with({"--serial", udp, "--component-id", std::to_string(201 + camera)});
    ASSERT_EQ(run.status, 0) << run.stderr_text;
  }
  // Pose estimates per component: one per posed frame, the same for both runs of one dataset
  // (heartbeats come on the link's own clock, so their count follows each run's length).
  std::map<int, int> estimates_per_component;
  pollfd waiting{socket_fd, POLLIN, 0};
  while (poll(&waiting, 1, 200) == 1) {
    std::uint8_t datagram[512];
    const ssize_t length = recv(socket_fd, datagram, sizeof datagram, 0);
    ASSERT_GT(length, 12);
    // The messages of one pose attempt, whole, in one datagram: MAVLink v2 frames back to back.
    for (ssize_t at = 0; at < length;) {
      ASSERT_EQ(datagram[at], 0xFD);
      ASSERT_EQ(datagram[at + 2], 0);  // unsigned
      const int message_id = datagram[at + 7] | datagram[at + 8] << 8 | datagram[at + 9] << 16;
      constexpr int kVisionPositionEstimate = 102, kResetCounterOffset = 116;
      if (message_id == kVisionPositionEstimate) ++estimates_per_component[datagram[at + 6]];
      // MAVLink v2 drops a payload's trailing zeros: a short payload has the counter 0.
      if (message_id == kVisionPositionEstimate && datagram[at + 1] > kResetCounterOffset) {
        EXPECT_EQ(datagram[at + 10 + kResetCounterOffset], 0);
      }
      at += 10 + datagram[at + 1] + 2;  // header, payload, checksum
      ASSERT_LE(at, length);
    }
  }
  close(socket_fd);
  ASSERT_EQ(estimates_per_component.size(), 2u);
  EXPECT_GT(estimates_per_component[201], 0);
  EXPECT_EQ(estimates_per_component[201], estimates_per_component[202]);
}

}  // namespace
}  // namespace irloc
