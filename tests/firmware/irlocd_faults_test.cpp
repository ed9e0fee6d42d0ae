// Faults injected into irlocd's camera while it runs (--inject-faults, hal/sim/fault_plan.hpp),
// the binary run as a user runs it, on a rendered drive under three dot markers with its truth:
// for each fault, no pose off the truth, no crash, and how many frames until poses come back.
// And on the simulated live camera: LEDs that die or lose their phase, and the stop signals.

#include <poll.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <random>
#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hal/replay/dataset_camera.hpp"
#include "host_sim/metrics/result_files.hpp"
#include "host_sim/render/dataset_render.hpp"
#include "host_sim/scenario/scenario.hpp"
#include "tests/firmware/loop_drive.hpp"
#include "tests/support/child_process.hpp"
#include "tests/support/pseudo_terminal.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/text_file.hpp"

namespace irloc {
namespace {

using ::testing::HasSubstr;

// 160 frames of the loop drive: a pose at every LED-on frame.
test::ScenarioText loop_scenario() { return test::loop_drive_scenario(160, 5); }

// A pose farther than this from the truth is a false pose (the dot path is sub-millimetre here).
constexpr double kFalsePoseM = 0.01;

struct IrlocdRun {
  int status = -1;
  std::string stderr_text;
  std::vector<PoseEstimate> poses;  // every row of the pose CSV
};

class IrlocdFaults : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    data_ = new test::TempDir;
    const sim::Scenario scenario = sim::parse_scenario(loop_scenario().yaml(), "scenario.yaml");
    for (const sim::TruthRow& row : sim::render_dataset(scenario, dataset())) truth_[row.seq] = row;
  }
  static void TearDownTestSuite() {
    delete data_;
    data_ = nullptr;
  }
  static std::filesystem::path dataset() { return data_->path() / "dataset"; }

  IrlocdRun replay(const std::string& faults) {
    const std::filesystem::path poses = dir_.path() / "pose.csv";
    std::vector<std::string> arguments = {IRLOCD_PATH, "--config", (dataset() / "config.yaml").string(), "--camera",
                                          "dir:" + dataset().string(), "--serial", "none", "--pose-csv", poses.string()};
    if (!faults.empty()) arguments.insert(arguments.end(), {"--inject-faults", faults});
    const test::ProcessResult result = test::run_to_end(std::move(arguments), dir_.path() / "stderr.txt");
    IrlocdRun run{result.status, result.stderr_text, {}};
    if (std::filesystem::exists(poses)) run.poses = sim::read_pose_csv(poses);
    return run;
  }

  // Every pose is on the truth of its frame; returns the sequence numbers of the good poses.
  static std::vector<std::uint64_t> checked_poses(const IrlocdRun& run, std::int64_t clock_shift_ns = 0) {
    std::vector<std::uint64_t> posed;
    for (const PoseEstimate& pose : run.poses) {
      if (!pose.ok) continue;
      const sim::TruthRow& truth = truth_.at(pose.seq);
      EXPECT_LT(std::hypot(pose.x - truth.x, pose.y - truth.y), kFalsePoseM) << "false pose at frame " << pose.seq;
      if (clock_shift_ns == 0) {
        EXPECT_EQ(pose.t_ns, truth.t_ns);
      }
      posed.push_back(pose.seq);
    }
    return posed;
  }
  static std::uint64_t first_pose_from(const std::vector<std::uint64_t>& posed, std::uint64_t seq) {
    for (const std::uint64_t s : posed) {
      if (s >= seq) return s;
    }
    return UINT64_MAX;
  }

  static test::TempDir* data_;
  static std::map<std::uint64_t, sim::TruthRow> truth_;
  test::TempDir dir_;
};

test::TempDir* IrlocdFaults::data_ = nullptr;
std::map<std::uint64_t, sim::TruthRow> IrlocdFaults::truth_;

TEST_F(IrlocdFaults, WithoutFaultsEveryLedOnFrameIsPosed) {
  const IrlocdRun run = replay("");
  ASSERT_EQ(run.status, 0) << run.stderr_text;
  EXPECT_EQ(checked_poses(run).size(), 80u);
}

TEST_F(IrlocdFaults, ACameraLostForHalfASecondIsReopenedAndPosesResume) {
  const auto start = std::chrono::steady_clock::now();
  const IrlocdRun run = replay("lost@40+500");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_EQ(run.status, 0) << run.stderr_text;
  EXPECT_THAT(run.stderr_text, HasSubstr("camera (injected fault): disconnected before frame 40: no pose until it is back"));
  EXPECT_THAT(run.stderr_text, HasSubstr("camera back after"));
  const std::vector<std::uint64_t> posed = checked_poses(run);
  // Frames exposed while it was away (0.5 s = 15 frames) are gone; the next pair is posed.
  EXPECT_EQ(first_pose_from(posed, 40), 56u);
  EXPECT_EQ(posed.size(), 80u - 8u);
  EXPECT_LT(seconds, 10.0);  // the reopen is retried every 0.5 s, not given up or hung
}

TEST_F(IrlocdFaults, DeadLedsGiveNoPoseAndPosesResumeWhenTheyLightAgain) {
  const IrlocdRun run = replay("dark@40+30");
  ASSERT_EQ(run.status, 0) << run.stderr_text;
  const std::vector<std::uint64_t> posed = checked_poses(run);
  EXPECT_EQ(first_pose_from(posed, 40), 70u);
  EXPECT_EQ(posed.size(), 80u - 15u);
  for (const PoseEstimate& pose : run.poses) {
    if (pose.seq >= 40 && pose.seq < 70) {
      EXPECT_FALSE(pose.ok) << pose.seq;
    }
  }
}

TEST_F(IrlocdFaults, LedsOutOfPhaseGiveNoFalsePose) {
  const IrlocdRun run = replay("desync@40+30");
  ASSERT_EQ(run.status, 0) << run.stderr_text;
  const std::vector<std::uint64_t> posed = checked_poses(run);
  EXPECT_EQ(first_pose_from(posed, 40), 70u);
  EXPECT_EQ(posed.size(), 80u - 15u);
}

// Back by 1 s at frame 40 (2.3 s: to before frames 10 to 39), then an hour forward.
TEST_F(IrlocdFaults, AFrameClockJumpingBackAndForwardCostsNoPose) {
  const IrlocdRun run = replay("jump@40-1,jump@100+3601");
  ASSERT_EQ(run.status, 0) << run.stderr_text;
  EXPECT_EQ(checked_poses(run, 1).size(), 80u);
  for (const PoseEstimate& pose : run.poses) {
    const std::int64_t shift = pose.seq >= 100 ? 3600'000'000'000 : pose.seq >= 40 ? -1'000'000'000 : 0;
    EXPECT_EQ(pose.t_ns, truth_.at(pose.seq).t_ns + shift) << pose.seq;
  }
}

// A monotonic frame clock counts from its start: a jump back past it is no clock's fault, and the
// plan is refused at the first frame (the dataset's is at 1 s), in one line naming the item.
TEST_F(IrlocdFaults, AClockJumpBelowZeroIsRefusedAtTheFirstFrame) {
  const IrlocdRun run = replay("jump@100+5,jump@40-3600");
  EXPECT_EQ(run.status, 1);
  EXPECT_EQ(run.stderr_text, "irlocd: error: --inject-faults jump@40-3600: takes the frame clock below 0 (the camera's first "
                             "frame is at 1000 ms; a monotonic clock counts from its start)\n");
  for (const PoseEstimate& pose : run.poses) EXPECT_GE(pose.t_ns, 0);
}

// A frame injected 29 s late: SIGTERM during the wait ends irlocd within a fraction of a second,
// cleanly.
TEST_F(IrlocdFaults, SigtermEndsALateFramesWait) {
  test::ChildOptions options;
  options.stderr_file = dir_.path() / "stderr.txt";
  test::ChildProcess irlocd({IRLOCD_PATH, "--config", (dataset() / "config.yaml").string(), "--camera", "dir:" + dataset().string(),
                             "--serial", "none", "--pose-csv", (dir_.path() / "pose.csv").string(), "--inject-faults", "late@4+29000"},
                            options);
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  ASSERT_TRUE(irlocd.running());
  const auto signalled = std::chrono::steady_clock::now();
  irlocd.signal(SIGTERM);
  EXPECT_EQ(irlocd.wait(), 0) << test::read_text(dir_.path() / "stderr.txt");
  EXPECT_LT(std::chrono::steady_clock::now() - signalled, std::chrono::seconds(2));
}

TEST_F(IrlocdFaults, AStarvedCpuDropsAndDelaysFramesWithoutAFalsePose) {
  // Seven frames lost in a burst (the parity of the stream flips), then a frame 0.3 s late.
  const IrlocdRun run = replay("drop@40+7,late@60+300");
  ASSERT_EQ(run.status, 0) << run.stderr_text;
  const std::vector<std::uint64_t> posed = checked_poses(run);
  EXPECT_EQ(first_pose_from(posed, 40), 48u);
  EXPECT_EQ(posed.size(), 80u - 4u);
}

TEST_F(IrlocdFaults, ABadFaultPlanIsOneLineNamingTheItem) {
  const IrlocdRun run = replay("lost@40");
  EXPECT_EQ(run.status, 1);
  EXPECT_EQ(run.stderr_text, "irlocd: error: --inject-faults lost@40: expected KIND@SEQ+AMOUNT\n");
  EXPECT_TRUE(run.poses.empty());
}

int count_of(const std::string& text, const std::string& part) {
  int count = 0;
  for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++count;
  return count;
}

// irlocd on the simulated live camera, as a child process: its config, pose CSV, statistics and
// stderr in `dir`.
test::ChildProcess start_live_irlocd(const std::filesystem::path& dir, const std::string& camera, const std::string& faults,
                                     const std::vector<std::string>& serial = {"--serial", "none"}) {
  const std::filesystem::path config = dir / "config.yaml";
  std::ofstream(dir / "calib.yaml") << "image_width: 64\nimage_height: 48\ncamera_matrix: {rows: 3, cols: 3, data: "
                                       "[40, 0, 31.5, 0, 40, 23.5, 0, 0, 1]}\ndistortion_model: plumb_bob\n"
                                       "distortion_coefficients: {rows: 1, cols: 5, data: [0, 0, 0, 0, 0]}\n";
  std::ofstream(dir / "map.yaml") << "dot_markers:\n  - {id: 1782, origin: [1.0, 2.0, 2.6], yaw: 0.0}\n";
  std::ofstream(config) << "camera:\n  calibration: calib.yaml\n  mount: {preset: up, xyz: [0, 0, 0.3]}\n"
                           "robot:\n  dof: 3\nmap: map.yaml\n";
  std::vector<std::string> arguments = {IRLOCD_PATH, "--config", config.string(), "--camera", camera,
                                        "--pose-csv", (dir / "pose.csv").string(), "--stats", (dir / "stats.json").string()};
  arguments.insert(arguments.end(), serial.begin(), serial.end());
  if (!faults.empty()) arguments.insert(arguments.end(), {"--inject-faults", faults});
  test::ChildOptions options;
  options.stderr_file = dir / "stderr.txt";
  return test::ChildProcess(std::move(arguments), options);
}

TEST_F(IrlocdFaults, LiveLedsThatDieAreRejectedAndTheStrobeRecovers) {
  // 600 frames at 60 fps; the LEDs stay dark for 200 of them, then light out of phase for 100.
  test::ChildProcess irlocd = start_live_irlocd(dir_.path(), "sim:600:unpaced", "dark@100+200,desync@400+100");
  ASSERT_EQ(irlocd.wait(), 0) << test::read_text(dir_.path() / "stderr.txt");
  const std::string errors = test::read_text(dir_.path() / "stderr.txt");
  EXPECT_THAT(errors, HasSubstr("no LED contrast in 60 pairs in a row"));
  // Out of phase, and back in phase: each time two swapped pairs, then the schedule follows.
  EXPECT_EQ(count_of(errors, "strobe resynchronised"), 2) << errors;
  const nlohmann::json stats = nlohmann::json::parse(test::read_text(dir_.path() / "stats.json"));
  // Dark: about 100 pairs rejected; out of phase: rejected until the schedule follows (2 pairs),
  // then the pipeline's own phase flip is verified too.
  EXPECT_GE(stats["strobe_rejected"].get<int>(), 100);
  EXPECT_LE(stats["strobe_rejected"].get<int>(), 112);
  // The strobe verdicts in --stats: the dark pairs without contrast, the two resynchronisations.
  EXPECT_GE(stats["strobe"]["no_contrast"].get<int>(), 95);
  EXPECT_EQ(stats["strobe"]["resyncs"].get<int>(), 2);
  EXPECT_EQ(stats["dropped_frames"].get<int>(), 0);
}

TEST_F(IrlocdFaults, FramesStopsALiveCameraAfterThatManyFrames) {
  test::ChildProcess irlocd = start_live_irlocd(dir_.path(), "sim:600:unpaced", "", {"--serial", "none", "--frames", "150"});
  ASSERT_EQ(irlocd.wait(), 0) << test::read_text(dir_.path() / "stderr.txt");
  EXPECT_THAT(test::read_text(dir_.path() / "stderr.txt"), HasSubstr("irlocd: stopped: 150 frames"));
  const nlohmann::json stats = nlohmann::json::parse(test::read_text(dir_.path() / "stats.json"));
  EXPECT_EQ(stats["frames"].get<int>(), 150);
  EXPECT_EQ(stats["dropped_frames"].get<int>(), 0);
  // 75 pairs, each with a verdict; the LEDs are in phase and lit, so nearly all are verified.
  const nlohmann::json& strobe = stats["strobe"];
  const int verdicts = strobe["verified"].get<int>() + strobe["swapped"].get<int>() + strobe["no_contrast"].get<int>();
  EXPECT_GE(verdicts, 74);
  EXPECT_LE(verdicts, 75);
  EXPECT_GE(strobe["verified"].get<int>(), 72);
}

TEST_F(IrlocdFaults, SignalsAtAnyMomentEndCleanlyWithWholeRows) {
  std::mt19937 random(11);
  std::uniform_int_distribution<int> moment(0, 400);
  int clean = 0;
  for (const int number : {SIGTERM, SIGINT, SIGTERM, SIGINT, SIGTERM, SIGINT}) {
    test::TempDir dir;
    test::ChildProcess irlocd = start_live_irlocd(dir.path(), "sim", "");
    // SIGHUP first (it reopens the serial device, here none, and must not stop irlocd), then the stop.
    std::this_thread::sleep_for(std::chrono::milliseconds(moment(random)));
    irlocd.signal(SIGHUP);
    std::this_thread::sleep_for(std::chrono::milliseconds(moment(random)));
    irlocd.signal(number);
    const int status = irlocd.wait();
    const std::filesystem::path pose_csv = dir.path() / "pose.csv";
    if (status == 128 + SIGHUP || status == 128 + number) {
      // Before the handlers were installed: ended by the signal, nothing written yet.
      EXPECT_FALSE(std::filesystem::exists(pose_csv));
      continue;
    }
    ASSERT_EQ(status, 0) << test::read_text(dir.path() / "stderr.txt");
    ++clean;
    if (std::filesystem::exists(pose_csv)) {
      const std::string text = test::read_text(pose_csv);
      ASSERT_FALSE(text.empty());
      EXPECT_EQ(text.back(), '\n');
      EXPECT_NO_THROW(sim::read_pose_csv(pose_csv));
    }
  }
  EXPECT_GE(clean, 4);  // most signals come after start-up's first milliseconds
}

// Whatever the master side has now or within `timeout_ms` (one read: the stream never goes quiet).
std::vector<std::uint8_t> read_some(const test::PseudoTerminal& pty, int timeout_ms) {
  std::vector<std::uint8_t> bytes(4096);
  pollfd request{pty.master_fd(), POLLIN, 0};
  if (::poll(&request, 1, timeout_ms) <= 0 || !(request.revents & POLLIN)) return {};
  const ssize_t got = ::read(pty.master_fd(), bytes.data(), bytes.size());
  bytes.resize(got > 0 ? static_cast<std::size_t>(got) : 0);
  return bytes;
}

// A USB serial adapter unplugged and plugged in again while irlocd streams to it (a pty behind a
// symlink, as udev names /dev/serial/by-id/...): one line each way, the stream back within a
// second of the replug and starting with a whole message; SIGHUP reopens it at once.
TEST_F(IrlocdFaults, ASerialAdapterUnpluggedAndPluggedInAgainGetsTheStreamBack) {
  const std::filesystem::path link = dir_.path() / "ttyUSB0";
  auto pty = std::make_unique<test::PseudoTerminal>();
  std::filesystem::create_symlink(pty->slave_path(), link);
  test::ChildProcess irlocd = start_live_irlocd(dir_.path(), "sim", "", {"--serial", link.string(), "--protocol", "stargazer"});
  std::this_thread::sleep_for(std::chrono::milliseconds(700));
  ASSERT_FALSE(read_some(*pty, 300).empty()) << test::read_text(dir_.path() / "stderr.txt");

  pty.reset();  // unplugged: the far end is gone, writes fail with EIO
  std::filesystem::remove(link);
  std::this_thread::sleep_for(std::chrono::milliseconds(800));
  pty = std::make_unique<test::PseudoTerminal>();  // plugged in again: a new device behind the name
  std::filesystem::create_symlink(pty->slave_path(), link);
  const auto replugged = std::chrono::steady_clock::now();
  std::vector<std::uint8_t> bytes;
  while (bytes.empty() && std::chrono::steady_clock::now() - replugged < std::chrono::seconds(3)) bytes = read_some(*pty, 50);
  const double recovery = std::chrono::duration<double>(std::chrono::steady_clock::now() - replugged).count();
  std::printf("serial stream back %.2f s after the replug\n", recovery);
  ASSERT_FALSE(bytes.empty()) << "no stream after the replug";
  EXPECT_LT(recovery, 1.5);
  EXPECT_EQ(bytes.front(), '~') << "the first message on the new device is torn";

  irlocd.signal(SIGHUP);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  EXPECT_FALSE(read_some(*pty, 300).empty()) << "no stream after SIGHUP";
  irlocd.signal(SIGTERM);
  EXPECT_EQ(irlocd.wait(), 0);
  const std::string errors = test::read_text(dir_.path() / "stderr.txt");
  EXPECT_THAT(errors, HasSubstr("irlocd: serial " + link.string() + " lost (Input/output error)"));
  EXPECT_THAT(errors, HasSubstr("irlocd: serial " + link.string() + " back after"));
  EXPECT_THAT(errors, HasSubstr("irlocd: SIGHUP: serial device reopened"));
}

}  // namespace
}  // namespace irloc
