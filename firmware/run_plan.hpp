#pragma once
// What one irlocd run is asked to do, resolved from the command line, the board file and the
// config, and checked before any device is opened: the first stage of run_daemon.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "firmware/daemon.hpp"
#include "firmware/live/live_drawing.hpp"
#include "firmware/live/live_server.hpp"
#include "firmware/serial_spec.hpp"
#include "hal/sim/fault_plan.hpp"
#include "io/config/board_file.hpp"
#include "io/config/config_file.hpp"

namespace irloc::firmware {

struct RunPlan {
  std::optional<io::BoardConfig> board;
  std::filesystem::path config_file;
  io::RobotConfig config;  // with the board's line time where the config gives none
  bool outside_in = false;  // mode: outside_in: a fixed camera, no strobe, every frame an attempt
  std::string camera_spec;  // --camera, else the board's libcamera
  bool live = false;        // a camera, not a recording
  std::string serial_argument;  // "none", "PATH[:BAUD]" or "udp:HOST:PORT"
  std::optional<SerialSpec> serial;
  std::string protocol;  // "mavlink" or "stargazer"
  std::vector<hal::Fault> faults;
  std::optional<LiveServerSettings> live_view;
  LiveImage annotate_image = LiveImage::on;
};

// Reads the board and config files and checks every option against them and each other.
// Throws io::InputError naming the option or the file and field.
RunPlan resolve_run(const DaemonOptions& options);

}  // namespace irloc::firmware
