// irlocd as a user runs it on a robot, as a process: one-line start-up errors for missing
// devices, and a software-in-the-loop run (simulated camera and LEDs, a real pty as the serial
// port) that prints its status line every second, streams MAVLink, records a dataset and stops
// cleanly on SIGTERM and SIGINT; and under a service manager, systemd's notification protocol
// spoken to a socket the test plays systemd on.

#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <fstream>
#include <optional>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hal/replay/dataset_camera.hpp"
#include "host_sim/render/synthetic_dataset.hpp"
#include "tests/support/child_process.hpp"
#include "tests/support/pseudo_terminal.hpp"
#include "tests/support/temp_dir.hpp"

namespace irloc::test {
namespace {

// irlocd with `arguments`, its stderr to `stderr_file`; `environment`: NAME=VALUE entries added
// to this process's environment.
ChildProcess start_irlocd(std::vector<std::string> arguments, const std::filesystem::path& stderr_file,
                          std::vector<std::string> environment = {}) {
  arguments.insert(arguments.begin(), IRLOCD_PATH);
  ChildOptions options;
  options.stderr_file = stderr_file;
  options.environment = std::move(environment);
  return ChildProcess(std::move(arguments), options);
}

std::vector<std::string> lines_of(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

struct IrlocdExit {
  int status;
  std::vector<std::string> stderr_lines;
};

IrlocdExit run_irlocd(std::vector<std::string> arguments) {
  TempDir dir;
  arguments.insert(arguments.begin(), IRLOCD_PATH);
  const int status = run_to_end(std::move(arguments), dir / "stderr.txt").status;
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
  const IrlocdExit run = run_irlocd({"--config", config_, "--camera", "sim:10", "--serial", "/dev/ttyIRLOC-absent:921600"});
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
  const IrlocdExit run = run_irlocd({"--board", (dir_ / "board.yaml").string(), "--config", config_});
  EXPECT_EQ(run.status, 1);
  EXPECT_EQ(run.stderr_lines,
            (std::vector<std::string>{"irlocd: error: strobe: gpiochip-irloc-absent: cannot open GPIO chip: No such file or directory"}));
}

TEST_F(IrlocdLive, LiveCameraWithoutABoardIsRefused) {
  const IrlocdExit run = run_irlocd({"--config", config_, "--camera", "libcamera"});
  EXPECT_EQ(run.status, 1);
  ASSERT_EQ(run.stderr_lines.size(), 1u);
  EXPECT_EQ(run.stderr_lines[0], "irlocd: error: --camera libcamera: a live camera needs the LED strobe of a board file (--board)");
}

TEST_F(IrlocdLive, ReplaySendsTheStarGazerStreamToASerialPort) {
  PseudoTerminal pty;
  const IrlocdExit run = run_irlocd({"--config", config_, "--camera", "dir:" + dir_.path().string(), "--serial",
                                        pty.slave_path() + ":115200", "--protocol", "stargazer"});
  EXPECT_EQ(run.status, 0);
  const std::vector<std::uint8_t> bytes = pty.read_available();
  // Four frames, two LED-on: two attempts, and the stub localizer finds nothing yet.
  EXPECT_EQ(std::string(bytes.begin(), bytes.end()), "~*DeadZone`~*DeadZone`");
}

void run_until_signal(const std::string& config, int signal_number, const TempDir& dir) {
  PseudoTerminal pty;
  ChildProcess irlocd = start_irlocd({"--config", config, "--camera", "sim", "--serial", pty.slave_path() + ":921600",
                                      "--record", (dir / "recorded").string()},
                                     dir / "stderr.txt");
  const std::regex status_line(R"(irlocd: ([0-9]+\.[0-9]) fps, [0-9.]+ attempts/s, [0-9]+% ok, dropped frames [0-9]+, )"
                               R"(strobe rejected [0-9]+ \(resyncs [0-9]+\), serial dropped [0-9]+)"
                               R"((, mount tilt [0-9.]+ deg( OFF CALIBRATION)?)?)");
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

// Plays systemd's side of sd_notify(3): a unix datagram socket whose path goes in $NOTIFY_SOCKET.
class NotifySocket {
 public:
  explicit NotifySocket(std::filesystem::path path) : path_(std::move(path)) {
    socket_ = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    std::strncpy(address.sun_path, path_.c_str(), sizeof(address.sun_path) - 1);
    if (socket_ < 0 || ::bind(socket_, reinterpret_cast<const sockaddr*>(&address), sizeof(address)) != 0) {
      throw std::runtime_error("cannot bind " + path_.string());
    }
  }
  ~NotifySocket() { ::close(socket_); }
  std::string environment() const { return "NOTIFY_SOCKET=" + path_.string(); }

  // The next message, or nothing within `timeout`.
  std::optional<std::string> receive(std::chrono::milliseconds timeout) const {
    pollfd request{socket_, POLLIN, 0};
    if (::poll(&request, 1, static_cast<int>(timeout.count())) != 1) return std::nullopt;
    char buffer[256];
    const ssize_t length = ::recv(socket_, buffer, sizeof(buffer), 0);
    if (length < 0) return std::nullopt;
    return std::string(buffer, static_cast<std::size_t>(length));
  }

 private:
  std::filesystem::path path_;
  int socket_ = -1;
};

TEST_F(IrlocdLive, ServiceWatchdogIsPettedWhileFramesFlowAndNotWhenThePipelineStalls) {
  const NotifySocket systemd(dir_ / "notify");
  // 60 frames at 60 fps, then the simulated sensor hangs; a 200 ms watchdog asks for a pet at
  // least every 100 ms.
  ChildProcess irlocd = start_irlocd({"--config", config_, "--camera", "sim:stall-at=60", "--serial", "none"},
                                     dir_ / "stderr.txt", {systemd.environment(), "WATCHDOG_USEC=200000"});
  EXPECT_EQ(systemd.receive(std::chrono::seconds(20)), "READY=1");  // before any pet
  // While frames flow: pets, and never a silence as long as the watchdog (ASan build and a busy
  // machine included: 1 s), until the stall.
  int pets = 0;
  std::optional<std::string> message;
  const auto started = std::chrono::steady_clock::now();
  while ((message = systemd.receive(std::chrono::seconds(1))) && std::chrono::steady_clock::now() - started < std::chrono::seconds(30)) {
    EXPECT_EQ(*message, "WATCHDOG=1");
    ++pets;
  }
  EXPECT_FALSE(message) << "pets never stopped in 30 s";
  // 1 s of frames at 60 fps, a pet every 0.1 s: about 10 (at least 3 on a loaded machine).
  EXPECT_GE(pets, 3);
  EXPECT_LE(pets, 40);
  // Stalled, not dead: no pet for another second, the process still runs; systemd would now kill
  // and restart it. SIGTERM ends the stall here, and irlocd says STOPPING=1.
  EXPECT_EQ(systemd.receive(std::chrono::seconds(1)), std::nullopt);
  EXPECT_TRUE(irlocd.running());
  irlocd.signal(SIGTERM);
  EXPECT_EQ(systemd.receive(std::chrono::seconds(20)), "STOPPING=1");
  EXPECT_EQ(irlocd.wait(), 0);
}

TEST_F(IrlocdLive, WithoutAWatchdogOnlyReadyAndStoppingAreSent) {
  const NotifySocket systemd(dir_ / "notify");
  ChildProcess irlocd = start_irlocd({"--config", config_, "--camera", "sim:30", "--serial", "none"}, dir_ / "stderr.txt",
                                     {systemd.environment()});
  EXPECT_EQ(irlocd.wait(), 0);
  EXPECT_EQ(systemd.receive(std::chrono::seconds(1)), "READY=1");
  EXPECT_EQ(systemd.receive(std::chrono::seconds(1)), "STOPPING=1");
  EXPECT_EQ(systemd.receive(std::chrono::milliseconds(100)), std::nullopt);
}

TEST_F(IrlocdLive, AMalformedNotifySocketIsOneLineAndExitOne) {
  TempDir dir;
  ChildProcess irlocd = start_irlocd({"--config", config_, "--camera", "sim:10", "--serial", "none"}, dir / "stderr.txt",
                                     {"NOTIFY_SOCKET=relative/path"});
  EXPECT_EQ(irlocd.wait(), 1);
  EXPECT_EQ(lines_of(dir / "stderr.txt"),
            (std::vector<std::string>{"irlocd: error: NOTIFY_SOCKET=relative/path: expected an absolute socket path or @abstract name"}));
}

}  // namespace
}  // namespace irloc::test
