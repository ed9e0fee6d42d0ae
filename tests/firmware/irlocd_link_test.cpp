// irlocd's pose-stream link as a process, over a real pseudo-terminal, with clients that behave
// as the other end does:
// - MAVLink, read by node-mavlink (an independent decoder) while the camera is lost for 2.5 s:
//   heartbeats keep coming about once a second, CRITICAL while it is lost, a STATUSTEXT says why,
//   and a TIMESYNC request node-mavlink sends is answered on irlocd's clock.
// - StarGazer: a host driver written from the public drivers' behaviour (pyStargazer: characters
//   10 ms apart, an acknowledgement awaited 1 s, five tries; parameters read, written and saved,
//   then CalcStart) completes its start-up and then parses the result messages; none comes between
//   CalcStop and CalcStart. The run's capture-to-write latency is in the status line and --stats.

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <fstream>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "host_sim/render/synthetic_dataset.hpp"
#include "tests/firmware/protocol/node_mavlink_decoder.hpp"
#include "tests/support/child_process.hpp"
#include "tests/support/pseudo_terminal.hpp"
#include "tests/support/temp_dir.hpp"

namespace irloc::test {
namespace {

using Clock = std::chrono::steady_clock;

std::vector<std::string> lines_of(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<std::string> split(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> fields;
  for (std::string field; in >> field;) fields.push_back(field);
  return fields;
}

class IrlocdLink : public ::testing::Test {
 protected:
  void SetUp() override {
    sim::SyntheticDatasetOptions options;
    options.frames = 4;
    sim::write_synthetic_dataset(dir_.path(), options);
    config_ = (dir_ / "config.yaml").string();
  }
  ChildProcess start_irlocd(std::vector<std::string> arguments) {
    arguments.insert(arguments.begin(), {IRLOCD_PATH, "--config", config_});
    ChildOptions options;
    options.stderr_file = dir_ / "stderr.txt";
    return ChildProcess(std::move(arguments), options);
  }
  TempDir dir_;
  std::string config_;
};

std::int64_t monotonic_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch()).count();
}

TEST_F(IrlocdLink, HeartbeatsGoOnCriticalWhileTheCameraIsLostWithTheReasonAndTimesyncIsAnswered) {
  PseudoTerminal pty;
  NodeMavlinkDecoder decoder(pty.master_fd(), dir_ / "decoded.txt", {"--timesync", "424242"});
  const std::int64_t started_ns = monotonic_ns();
  // 300 frames at 60 fps, the camera gone for 2.5 s from frame 60 (the paced simulated camera
  // then catches up: about 5 s in all).
  ChildProcess irlocd = start_irlocd({"--camera", "sim:300", "--inject-faults", "lost@60+2500", "--serial",
                                      pty.slave_path() + ":921600", "--component-id", "198"});
  EXPECT_EQ(irlocd.wait(), 0);
  const std::int64_t ended_ns = monotonic_ns();
  const std::vector<std::string> lines = decoder.finish();

  ASSERT_FALSE(lines.empty());
  EXPECT_EQ(lines.back().substr(0, 10), "END valid=");
  EXPECT_NE(lines.back().find(" invalid=0 unknown=0 crc_errors=0"), std::string::npos) << lines.back();
  std::vector<int> statuses;
  std::vector<long long> arrivals_ms;
  std::string text;
  int timesync_answers = 0;
  for (const std::string& line : lines) {
    const std::vector<std::string> f = split(line);
    if (f[0] == "HEARTBEAT") {
      EXPECT_EQ(f[3], "198");
      statuses.push_back(std::stoi(f[8]));
      arrivals_ms.push_back(std::stoll(f[10]));
    } else if (f[0] == "STATUSTEXT") {
      const std::size_t quote = line.find('"');
      text += line.substr(quote + 1, line.size() - quote - 2) + (f[5] == "0" ? "\n" : "");
    } else if (f[0] == "TIMESYNC") {
      ++timesync_answers;
      EXPECT_EQ(f[5], "424242");  // ts1 as sent
      EXPECT_EQ(f[6], "255");     // to the requester
      EXPECT_EQ(f[7], "190");
      const std::int64_t tc1 = std::stoll(f[4]);  // irlocd's CLOCK_MONOTONIC, the test's too
      EXPECT_GT(tc1, started_ns);
      EXPECT_LT(tc1, ended_ns);
    }
  }
  EXPECT_EQ(timesync_answers, 1);
  // About 5 s: at least 4 heartbeats, never more than 1.5 s apart.
  ASSERT_GE(statuses.size(), 4u);
  for (std::size_t k = 1; k < arrivals_ms.size(); ++k) EXPECT_LE(arrivals_ms[k] - arrivals_ms[k - 1], 1500) << k;
  // STANDBY (3) at most before the first frame, then ACTIVE (4); CRITICAL (5) while lost: at
  // least two heartbeats in the 2.5 s; ACTIVE again at the end.
  int critical = 0;
  for (const int status : statuses) critical += status == 5 ? 1 : 0;
  EXPECT_GE(critical, 2);
  EXPECT_EQ(statuses.back(), 4);
  EXPECT_NE(std::find(statuses.begin(), statuses.end(), 4), statuses.end());
  EXPECT_NE(text.find("camera (injected fault): disconnected before frame 60: no pose until it is back; reopening every 0.5 s"),
            std::string::npos) << text;
  EXPECT_NE(text.find("camera back after "), std::string::npos) << text;
}

// A StarGazer host driver as the public drivers behave (pyStargazer's StarGazer class).
class StarGazerDriver {
 public:
  explicit StarGazerDriver(const PseudoTerminal& pty) : pty_(pty) {}

  // send_command / write_parameter: up to five tries, each typed 10 ms a character, then up to
  // 1 s for `~!MESSAGE``.
  bool command(const std::string& message, int tries = 5) {
    for (int attempt = 0; attempt < tries; ++attempt) {
      type("~#" + message + "`");
      if (wait_for("~!" + message + "`", std::chrono::seconds(1))) return true;
    }
    return false;
  }
  // read_parameter: `~@NAME``, the acknowledgement, then `~$NAME|VALUE``.
  std::optional<std::string> read(const std::string& name) {
    for (int attempt = 0; attempt < 5; ++attempt) {
      type("~@" + name + "`");
      if (!wait_for("~!" + name + "`", std::chrono::seconds(1))) continue;
      const std::regex value("~\\$" + name + "\\|([^`]*)`");
      const Clock::time_point until = Clock::now() + std::chrono::seconds(1);
      while (Clock::now() < until) {
        const std::optional<std::string> message = next_message(until);
        std::smatch match;
        if (message && std::regex_match(*message, match, value)) return match[1].str();
      }
    }
    return std::nullopt;
  }
  // save_settings: SetEnd, then `~!ParameterUpdate``.
  bool save() { return command("SetEnd") && wait_for("~!ParameterUpdate`", std::chrono::seconds(5)); }

  // The next whole message (`~` .. back-quote) before `until`.
  std::optional<std::string> next_message(Clock::time_point until) {
    while (true) {
      const std::size_t start = buffer_.find('~');
      const std::size_t end = start == std::string::npos ? std::string::npos : buffer_.find('`', start);
      if (end != std::string::npos) {
        std::string message = buffer_.substr(start, end - start + 1);
        buffer_.erase(0, end + 1);
        received_.push_back(message);
        return message;
      }
      if (Clock::now() >= until) return std::nullopt;
      const std::vector<std::uint8_t> bytes = pty_.read_available(20);
      buffer_.append(bytes.begin(), bytes.end());
    }
  }
  const std::vector<std::string>& received() const { return received_; }

 private:
  void type(const std::string& message) {
    for (const char c : message) {
      ASSERT_EQ(::write(pty_.master_fd(), &c, 1), 1);
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }
  bool wait_for(const std::string& wanted, Clock::duration timeout) {
    const Clock::time_point until = Clock::now() + timeout;
    while (const std::optional<std::string> message = next_message(until)) {
      if (*message == wanted) return true;
    }
    return false;
  }

  const PseudoTerminal& pty_;
  std::string buffer_;
  std::vector<std::string> received_;
};

TEST_F(IrlocdLink, AStarGazerDriversStartUpCompletesAndItThenParsesResults) {
  PseudoTerminal pty;
  ChildProcess irlocd = start_irlocd({"--camera", "sim", "--serial", pty.slave_path() + ":115200", "--protocol",
                                      "stargazer", "--stats", (dir_ / "stats.json").string()});
  StarGazerDriver driver(pty);
  ASSERT_TRUE(driver.command("CalcStop"));
  const std::size_t stopped_at = driver.received().size();
  EXPECT_EQ(driver.read("Version"), "irloc 0.1.0");
  EXPECT_EQ(driver.read("BaudRate"), "115200");
  EXPECT_EQ(driver.read("MarkMode"), "Map");
  EXPECT_TRUE(driver.command("MarkHeight|2500"));
  EXPECT_TRUE(driver.command("HeightFix|No"));
  // Refused: no acknowledgement (every retry of a driver meets the same; one try here).
  EXPECT_FALSE(driver.command("MarkType|HLD1L", 1));
  EXPECT_TRUE(driver.save());
  EXPECT_EQ(driver.read("MarkHeight"), "2500");
  ASSERT_TRUE(driver.command("CalcStart"));
  const std::size_t started_at = driver.received().size();
  // pyStargazer's patterns for the results.
  const std::regex map_mode(R"(~\^I([0-9]+)\|([\+\-][0-9]+\.?[0-9]+)\|([\+\-][0-9]+\.?[0-9]+)\|([\+\-][0-9]+\.?[0-9]+)\|([0-9]+\.?[0-9]+)`)");
  const std::regex dead_zone(R"(~\*DeadZone`)");
  // At least 20 results over 2.5 s: the status line, once a second, then has an interval with
  // poses sent in it whatever the machine's load.
  int results = 0;
  const Clock::time_point calc_started = Clock::now();
  const Clock::time_point until = calc_started + std::chrono::seconds(10);
  while (results < 20 || Clock::now() - calc_started < std::chrono::milliseconds(2500)) {
    const std::optional<std::string> message = driver.next_message(until);
    ASSERT_TRUE(message) << "no results after CalcStart";
    EXPECT_TRUE(std::regex_match(*message, map_mode) || std::regex_match(*message, dead_zone)) << *message;
    ++results;
  }
  irlocd.signal(SIGTERM);
  EXPECT_EQ(irlocd.wait(), 0);

  for (std::size_t k = stopped_at; k < started_at; ++k) {
    EXPECT_EQ(driver.received()[k].rfind("~*DeadZone", 0), std::string::npos) << "a result while stopped: " << k;
    EXPECT_EQ(driver.received()[k].rfind("~^", 0), std::string::npos) << "a result while stopped: " << k;
  }
  const std::vector<std::string> log = lines_of(dir_ / "stderr.txt");
  const auto logged = [&](const std::string& text) {
    return std::any_of(log.begin(), log.end(), [&](const std::string& line) { return line.find(text) != std::string::npos; });
  };
  EXPECT_TRUE(logged("irlocd: StarGazer host command MarkType refused: irloc's markers are its own"));
  // Capture to write, per result message, on the status line and in --stats.
  EXPECT_TRUE(logged(", latency "));
  const nlohmann::json stats = nlohmann::json::parse(std::ifstream(dir_ / "stats.json"));
  ASSERT_TRUE(stats.contains("capture_to_write_ms")) << stats.dump();
  EXPECT_GE(stats["capture_to_write_ms"]["poses"].get<int>(), 20);
  EXPECT_GT(stats["capture_to_write_ms"]["median"].get<double>(), 0.0);
  EXPECT_GE(stats["capture_to_write_ms"]["p99"].get<double>(), stats["capture_to_write_ms"]["median"].get<double>());
}

}  // namespace
}  // namespace irloc::test
