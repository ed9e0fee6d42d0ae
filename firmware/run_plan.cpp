#include "firmware/run_plan.hpp"

#include <tuple>

#include "firmware/camera_source.hpp"
#include "firmware/live/http_token.hpp"
#include "io/config/calibration_file.hpp"
#include "io/input_error.hpp"

namespace irloc::firmware {
namespace {

std::filesystem::path config_path(const DaemonOptions& options, const std::optional<io::BoardConfig>& board) {
  if (options.config) return *options.config;
  if (board && board->config) return *board->config;
  throw io::InputError(board ? "--config: required (the board file " + options.board->string() + " names no config)"
                             : "--config: required");
}

// The board's nominal lens and the robot's calibration must describe the same image.
void check_calibration_size(const io::BoardConfig& board, const io::RobotConfig& config) {
  const CameraIntrinsics lens = io::load_camera_info(board.camera.calibration);
  const CameraIntrinsics& robot = config.setup.camera;
  if (lens.width != robot.width || lens.height != robot.height) {
    throw io::InputError(config.calibration_file.string() + ": image is " + std::to_string(robot.width) + "x" +
                         std::to_string(robot.height) + " but board " + board.name + "'s camera (" +
                         board.camera.calibration.string() + ") is " + std::to_string(lens.width) + "x" +
                         std::to_string(lens.height));
  }
}

std::string serial_argument(const DaemonOptions& options, const std::optional<io::BoardConfig>& board) {
  if (!options.serial.empty()) return options.serial;
  if (board && board->serial) return board->serial->device + ":" + std::to_string(board->serial->baud);
  return "none";
}

std::string protocol_name(const DaemonOptions& options, const std::optional<io::BoardConfig>& board) {
  if (!options.protocol.empty()) return options.protocol;
  if (board && board->serial) return board->serial->protocol;
  return "mavlink";
}

// The live view's settings from the command line; the token is made (or read) for an address
// other than loopback.
std::optional<LiveServerSettings> live_server_settings(const DaemonOptions& options) {
  if (options.http.empty()) return std::nullopt;
  LiveServerSettings settings;
  std::tie(settings.host, settings.port) = parse_http_address(options.http);
  settings.read_only = options.http_read_only;
  settings.camera_settings = options.camera_settings;
  if (!is_loopback_address(settings.host) && !options.http_read_only) {
    settings.token = load_or_create_http_token(options.http_token);
  }
  return settings;
}

// The files: board, config, calibration, and what the mode allows.
void resolve_files(const DaemonOptions& options, RunPlan& plan) {
  if (options.board) plan.board = io::load_board(*options.board);
  plan.config_file = config_path(options, plan.board);
  plan.config = io::load_robot_config(plan.config_file);
  if (plan.board) check_calibration_size(*plan.board, plan.config);
  // The sensor mode's rolling shutter: the config's line time, else the board's (docs/formats.md);
  // a camera that reports its own per frame overrides both.
  if (plan.board && plan.config.setup.line_time_ns == 0) plan.config.setup.line_time_ns = plan.board->camera.line_time_ns;
  plan.outside_in = plan.config.mode == io::RobotMode::outside_in;
  if (plan.outside_in && (options.survey || options.calibrate)) {
    throw io::InputError(plan.config_file.string() + ": mode: outside_in: " + (options.survey ? "--survey" : "--calibrate") +
                         " needs the camera on the robot (mode: on_robot)");
  }
}

}  // namespace

RunPlan resolve_run(const DaemonOptions& options) {
  RunPlan plan;
  resolve_files(options, plan);
  plan.camera_spec = !options.camera.empty() ? options.camera : plan.board ? "libcamera" : "";
  if (plan.camera_spec.empty()) throw io::InputError("--camera: required without --board");
  plan.live = is_live_camera(plan.camera_spec);
  if (options.paced && plan.live) {
    throw io::InputError("--paced: only for a recording (--camera dir:DATASET); a camera is paced by itself");
  }
  plan.protocol = protocol_name(options, plan.board);
  plan.serial_argument = serial_argument(options, plan.board);
  plan.serial = parse_serial_spec(plan.serial_argument);
  if (options.inject_faults) plan.faults = hal::parse_fault_plan(*options.inject_faults);
  plan.live_view = live_server_settings(options);
  const std::optional<LiveImage> annotate_image = live_image_named(options.annotate_image);
  if (!annotate_image) throw io::InputError("--annotate-image " + options.annotate_image + ": expected on or difference");
  plan.annotate_image = *annotate_image;
  return plan;
}

}  // namespace irloc::firmware
