// irlocd: the irloc daemon. Reads frames, finds ceiling markers, streams the robot's pose.

#include <cstdint>
#include <csignal>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "firmware/allocation_count.hpp"
#include "firmware/daemon.hpp"
#include "firmware/stats_file.hpp"
#include "io/config/config_reference.hpp"
#include "io/input_error.hpp"

namespace {

std::atomic<bool> stop_requested{false};
std::atomic<bool> serial_reopen_requested{false};

extern "C" void request_stop(int) { stop_requested.store(true); }
extern "C" void request_serial_reopen(int) { serial_reopen_requested.store(true); }

void install_signal_handlers() {
  struct sigaction action{};
  action.sa_handler = request_stop;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  // SIGHUP (systemctl reload): reopen the serial device at once, e.g. after replugging it.
  action.sa_handler = request_serial_reopen;
  sigaction(SIGHUP, &action, nullptr);
  // A closed pipe (stderr piped to a pager or `head` that quit, a UDP or serial far end gone) is
  // a failed write (EPIPE) that each output handles, never the end of a survey before its map is
  // written.
  action.sa_handler = SIG_IGN;
  sigaction(SIGPIPE, &action, nullptr);
}


// The command line as CLI11 parses it: a path given as a string (empty: not given), then moved
// into DaemonOptions by finish_options.
struct CommandLine {
  irloc::firmware::DaemonOptions options;
  std::string config, board, pose_csv, record, stats, calibrate, survey, inject_faults, http_token, camera_settings, annotate;
  int realtime_priority = -1;
  bool print_config = false;
};

// An empty file or device name is a mistake (an unset shell variable), never "none".
const CLI::Validator& non_empty() {
  static const CLI::Validator validator(
      [](std::string& value) { return value.empty() ? std::string("must not be empty") : std::string(); }, "NOT EMPTY");
  return validator;
}

// What the run reads: config, board, devices, and how it runs.
void add_input_options(CLI::App& app, CommandLine& line) {
  irloc::firmware::DaemonOptions& options = line.options;
  app.add_option("--config", line.config, "config YAML (camera calibration, mount, robot, map); default: the board's")
      ->check(non_empty());
  app.add_option("--board", line.board, "board file (boards/NAME.yaml): camera, strobe line, serial port")
      ->check(non_empty());
  app.add_option("--camera", options.camera, "frame source: dir:DATASET, libcamera, libcamera:ID, or sim[:FRAMES][:unpaced][:stall-at=SEQ] (simulated camera and LEDs); default: the board's")
      ->check(non_empty());
  app.add_option("--serial", options.serial, "pose stream output: none, PATH[:BAUD], or udp:HOST:PORT (the messages of each pose attempt in one datagram); default: the board's, else none")
      ->check(non_empty());
  app.add_option("--protocol", options.protocol, "serial protocol; default: the board's, else mavlink")
      ->check(CLI::IsMember({"mavlink", "stargazer"}));
  app.add_option("--component-id", options.component_id,
                 "MAVLink component ID of this irlocd (one per camera when several watch one robot); default: the board's, else 197")
      ->check(CLI::Range(1, 255));
  app.add_option("--inject-faults", line.inject_faults,
                 "software-in-the-loop tests: faults to inject into the camera, e.g. lost@300+1500,dark@600+40 (docs/hardware.md)")
      ->check(non_empty());
  app.add_flag("--paced", options.paced,
               "replay the dir: dataset at the pace it was recorded, as a camera delivers it (capture-to-write latency is then measured)");
  app.add_option("--frames", options.max_frames, "stop after this many frames, as SIGTERM does (a bounded run of a live camera)")
      ->check(CLI::Range(std::uint64_t{1}, std::numeric_limits<std::uint64_t>::max()));
  app.add_option("--camera-settings", line.camera_settings,
                 "setup controls (exposure, gain, frame duration, LEDs) applied at start when the file exists; the live view's save writes it")
      ->check(non_empty());
  app.add_option("--realtime-priority", line.realtime_priority, "SCHED_FIFO priority 1..99, 0 = normal; default: the board's")
      ->check(CLI::Range(0, 99));
  app.add_flag("--print-config", line.print_config,
               "print a complete config, every key at its default with what it does, its range and unit, and exit (docs/config.md)");
}

// What the run writes and serves.
void add_output_options(CLI::App& app, CommandLine& line) {
  irloc::firmware::DaemonOptions& options = line.options;
  app.add_option("--pose-csv", line.pose_csv, "write every pose attempt to this CSV file")->check(non_empty());
  app.add_option("--record", line.record, "write every frame to this folder as a dataset (frames.csv + PGM)")->check(non_empty());
  app.add_option("--stats", line.stats, "write the run's statistics (counts, stage times) to this JSON file at the end")
      ->check(non_empty());
  CLI::Option* calibrate_option = app.add_option("--calibrate", line.calibrate,
                 "self-calibrate intrinsics and mount from the drive's dot markers; write config, calibration and report to this folder")
      ->check(non_empty());
  // A calibration trusts the map, a survey trusts the calibration: one at a time.
  app.add_option("--survey", line.survey, "map building: estimate every dot marker's pose and write the map here (docs/survey.md)")
      ->check(non_empty())
      ->excludes(calibrate_option);
  app.add_option("--http", options.http,
                 "serve the live view (docs/hardware.md) on ADDR:PORT, e.g. 127.0.0.1:8080; an address other than loopback needs the token for the controls")
      ->check(non_empty());
  app.add_flag("--http-read-only", options.http_read_only, "the live view without its setup controls");
  app.add_option("--http-token", line.http_token, "the live view's token file, made at the first start off loopback; default /var/lib/irlocd/http-token")
      ->check(non_empty());
  app.add_option("--annotate", line.annotate, "write every pose attempt as a JPEG with the live view's drawing to this new folder")
      ->check(non_empty());
  app.add_option("--annotate-image", options.annotate_image, "the picture --annotate draws on: on (the LED-on frame, default) or difference")
      ->check(CLI::IsMember({"on", "difference"}));
}

void finish_options(CommandLine& line) {
  irloc::firmware::DaemonOptions& options = line.options;
  const auto set_path = [](std::optional<std::filesystem::path>& path, const std::string& text) {
    if (!text.empty()) path = text;
  };
  set_path(options.config, line.config);
  set_path(options.board, line.board);
  set_path(options.pose_csv, line.pose_csv);
  set_path(options.record, line.record);
  set_path(options.stats, line.stats);
  set_path(options.calibrate, line.calibrate);
  set_path(options.survey, line.survey);
  set_path(options.camera_settings, line.camera_settings);
  set_path(options.annotate, line.annotate);
  if (!line.inject_faults.empty()) options.inject_faults = line.inject_faults;
  if (!line.http_token.empty()) options.http_token = line.http_token;
  if (line.realtime_priority >= 0) options.realtime_priority = line.realtime_priority;
}

// The run's last lines on stderr: the mean stage times, then the summary line, which stays last.
void print_summary(const irloc::firmware::DaemonSummary& summary) {
  if (!summary.stage_totals.empty() && summary.pose_attempts > 0) {
    std::fprintf(stderr, "irlocd: mean stage times per pose attempt (ms):");
    for (const irloc::StageTime& stage : summary.stage_totals) {
      std::fprintf(stderr, " %s %.4f", stage.name, stage.milliseconds / static_cast<double>(summary.pose_attempts));
    }
    std::fprintf(stderr, "\n");
  }
  std::fprintf(stderr, "irlocd: %s%llu frames, %llu pose attempts (%llu without an LED-off partner), %llu poses ok%s\n",
               summary.stopped ? "stopped: " : "", static_cast<unsigned long long>(summary.frames),
               static_cast<unsigned long long>(summary.pose_attempts), static_cast<unsigned long long>(summary.unpaired),
               static_cast<unsigned long long>(summary.poses_ok),
               summary.outputs_failed > 0 ? "; an output failed (above): data was lost" : "");
}

int run(irloc::firmware::DaemonOptions& options) {
  install_signal_handlers();
  options.stop = &stop_requested;
  options.reopen_serial = &serial_reopen_requested;
  options.allocations_so_far = irloc::firmware::allocation_count();
  try {
    const irloc::firmware::DaemonSummary summary = irloc::firmware::run_daemon(options);
    if (options.stats) irloc::firmware::write_stats_file(*options.stats, summary);
    print_summary(summary);
    return summary.outputs_failed > 0 ? 1 : 0;
  } catch (const irloc::io::InputError& e) {
    std::fprintf(stderr, "irlocd: error: %s\n", e.what());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "irlocd: internal error: %s\n", e.what());
  }
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  CommandLine line;
  CLI::App app{"irlocd: robot pose from ceiling markers"};
  add_input_options(app, line);
  add_output_options(app, line);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int status = app.exit(e);
    return status == 0 ? 0 : 2;
  }
  if (line.print_config) {
    std::fputs(irloc::io::reference_config_yaml().c_str(), stdout);
    return 0;
  }
  finish_options(line);
  if (!line.options.config && !line.options.board) {
    std::fprintf(stderr, "irlocd: error: give --config (and --camera), or --board\n");
    return 2;
  }
  return run(line.options);
}
