// irlocd as a user runs it on a robot, as a process: one-line start-up errors for missing
// devices, and a software-in-the-loop run (simulated camera and LEDs, a real pty as the serial
// port) that prints its status line every second, streams MAVLink, records a dataset and stops
// cleanly on SIGTERM and SIGINT.

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hal/replay/dataset_camera.hpp"
#include "host_sim/render/synthetic_dataset.hpp"
#include "tests/support/pseudo_terminal.hpp"
#include "tests/support/temp_dir.hpp"

extern char** environ;

namespace irloc::test {
namespace {

class Irlocd {
 public:
  Irlocd(std::vector<std::string> arguments, const std::filesystem::path& stderr_file) {
    arguments.insert(arguments.begin(), IRLOC_IRLOCD);
    std::vector<char*> argv;
    for (std::string& argument : arguments) argv.push_back(argument.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 2, stderr_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (posix_spawn(&pid_, argv[0], &actions, nullptr, argv.data(), environ) != 0) throw std::runtime_error("spawn failed");
    posix_spawn_file_actions_destroy(&actions);
  }
  void signal(int number) const { ::kill(pid_, number); }
  int wait() const {
    int status = 0;
    ::waitpid(pid_, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  }

 private:
  pid_t pid_ = -1;
};

std::vector<std::string> lines_of(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

struct ProcessResult {
  int status;
  std::vector<std::string> stderr_lines;
};

ProcessResult run_to_end(const std::vector<std::string>& arguments) {
  TempDir dir;
  const Irlocd irlocd(arguments, dir / "stderr.txt");
  const int status = irlocd.wait();
  return {status, lines_of(dir / "stderr.txt")};
}

class IrlocdLive : public ::testing::Test {
 protected:
  void SetUp() override {
    sim::SyntheticDatasetOptions options;
    options.frames = 4;
    sim::write_synthetic_dataset(dir_.path(), options);
    config_ = (dir_ / "config.yaml").string();
  }
  TempDir dir_;
  std::string config_;
};

TEST_F(IrlocdLive, MissingSerialDeviceIsOneLineAndExitOne) {
  const ProcessResult run = run_to_end({"--config", config_, "--camera", "sim:10", "--serial", "/dev/ttyIRLOC-absent:921600"});
  EXPECT_EQ(run.status, 1);
  EXPECT_EQ(run.stderr_lines, (std::vector<std::string>{"irlocd: error: serial /dev/ttyIRLOC-absent: cannot open: No such file or directory"}));
}

TEST_F(IrlocdLive, MissingGpioChipIsOneLineAndExitOne) {
  // A board whose strobe chip does not exist, with its serial port on a real pty.
  PseudoTerminal pty;
  std::ofstream(dir_ / "lens.yaml") << std::ifstream(dir_ / "calib.yaml").rdbuf();
  std::ofstream(dir_ / "board.yaml") << "name: test\ndescription: a board without its GPIO chip\n"
                                        "camera: {driver: libcamera, formats: [R8], frame_duration_us: 16667,\n"
                                        "         exposure_us: 1000, analogue_gain: 1, calibration: lens.yaml}\n"
                                        "strobe: {chip: gpiochip-irloc-absent, line: 17, active_low: false, latency_frames: 1,\n"
                                        "         noise_level: 12, min_contrast_ratio: 3}\n"
                                        "serial: {device: " << pty.slave_path() << ", baud: 115200, protocol: mavlink}\n";
  const ProcessResult run = run_to_end({"--board", (dir_ / "board.yaml").string(), "--config", config_});
  EXPECT_EQ(run.status, 1);
  EXPECT_EQ(run.stderr_lines,
            (std::vector<std::string>{"irlocd: error: strobe: gpiochip-irloc-absent: cannot open GPIO chip: No such file or directory"}));
}

TEST_F(IrlocdLive, LiveCameraWithoutABoardIsRefused) {
  const ProcessResult run = run_to_end({"--config", config_, "--camera", "libcamera"});
  EXPECT_EQ(run.status, 1);
  ASSERT_EQ(run.stderr_lines.size(), 1u);
  EXPECT_EQ(run.stderr_lines[0], "irlocd: error: --camera libcamera: a live camera needs the LED strobe of a board file (--board)");
}

TEST_F(IrlocdLive, ReplaySendsTheStarGazerStreamToASerialPort) {
  PseudoTerminal pty;
  const ProcessResult run = run_to_end({"--config", config_, "--camera", "dir:" + dir_.path().string(), "--serial",
                                        pty.slave_path() + ":115200", "--protocol", "stargazer"});
  EXPECT_EQ(run.status, 0);
  const std::vector<std::uint8_t> bytes = pty.read_available();
  // Four frames, two LED-on: two attempts, and the stub localizer finds nothing yet.
  EXPECT_EQ(std::string(bytes.begin(), bytes.end()), "~*DeadZone`~*DeadZone`");
}

void run_until_signal(const std::string& config, int signal_number, const TempDir& dir) {
  PseudoTerminal pty;
  const Irlocd irlocd({"--config", config, "--camera", "sim", "--serial", pty.slave_path() + ":921600", "--record",
                       (dir / "recorded").string()},
                      dir / "stderr.txt");
  const std::regex status_line(R"(irlocd: ([0-9]+\.[0-9]) fps, [0-9.]+ attempts/s, [0-9]+% ok, dropped frames [0-9]+, )"
                               R"(strobe rejected [0-9]+ \(resyncs [0-9]+\), serial dropped [0-9]+)");
  // Run until two status lines are out (about 2 s; at most 20 s on a loaded machine).
  const auto count_status_lines = [&] {
    int count = 0;
    for (const std::string& line : lines_of(dir / "stderr.txt")) count += line.find(" fps, ") != std::string::npos ? 1 : 0;
    return count;
  };
  std::vector<std::uint8_t> stream;
  for (int i = 0; i < 200 && count_status_lines() < 2; ++i) {
    const std::vector<std::uint8_t> bytes = pty.read_available(100);
    stream.insert(stream.end(), bytes.begin(), bytes.end());
  }
  irlocd.signal(signal_number);
  EXPECT_EQ(irlocd.wait(), 0);

  const std::vector<std::string> lines = lines_of(dir / "stderr.txt");
  ASSERT_GE(lines.size(), 2u);
  int status_lines = 0;
  for (const std::string& line : lines) {
    std::smatch match;
    if (!std::regex_match(line, match, status_line)) continue;
    ++status_lines;
    EXPECT_GT(std::stod(match[1]), 5.0) << line;  // paced at 60 fps; the sanitizer build is slower
    EXPECT_LE(std::stod(match[1]), 120.0) << line;  // a paced sensor catches up after a stall
  }
  EXPECT_GE(status_lines, 2);
  EXPECT_EQ(lines.back().rfind("irlocd: stopped: ", 0), 0u) << lines.back();
  // The stub localizer gives no poses yet, so the stream is HEARTBEATs: one per second.
  ASSERT_GE(stream.size(), 2u * 21u);
  EXPECT_EQ(stream[0], 0xFD);
  EXPECT_EQ(stream[7], 0);  // message id 0

  // The recording replays: frames.csv with alternating LED states from the strobe schedule.
  hal::DatasetCamera replay(dir / "recorded", 320, 240, "calib.yaml");
  EXPECT_GE(replay.frame_count(), 100u);
  Frame frame;
  while (replay.next(frame)) EXPECT_EQ(frame.led_on, frame.seq % 2 == 0);
}

TEST_F(IrlocdLive, SoftwareInTheLoopRunsStreamsRecordsAndStopsOnSigterm) { run_until_signal(config_, SIGTERM, dir_); }

TEST_F(IrlocdLive, SigintStopsCleanlyToo) { run_until_signal(config_, SIGINT, dir_); }

}  // namespace
}  // namespace irloc::test
