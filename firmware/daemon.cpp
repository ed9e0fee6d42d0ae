#include "firmware/daemon.hpp"

#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <thread>
#include <tuple>

#include "algo/pipeline/localizer.hpp"
#include "firmware/calibration_run.hpp"
#include "firmware/camera_source.hpp"
#include "firmware/frame_loop.hpp"
#include "firmware/live/annotated_frames.hpp"
#include "firmware/live/http_token.hpp"
#include "firmware/live/live_server.hpp"
#include "firmware/live/paced_camera.hpp"
#include "firmware/protocol/mavlink_pose_stream.hpp"
#include "firmware/protocol/stargazer_pose_stream.hpp"
#include "firmware/realtime.hpp"
#include "firmware/serial_spec.hpp"
#include "firmware/mount_watch_monitor.hpp"
#include "firmware/service_notifier.hpp"
#include "firmware/status_line.hpp"
#include "firmware/strobe_source.hpp"
#include "firmware/survey_writer.hpp"
#include "firmware/warning_log.hpp"
#include "firmware/serial_link.hpp"
#include "io/config/board_file.hpp"
#include "io/config/calibration_file.hpp"
#include "io/config/camera_settings_file.hpp"
#include "io/config/config_file.hpp"
#include "hal/device_lost.hpp"
#include "io/files/run_files.hpp"
#include "hal/sim/fault_injecting_camera.hpp"
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

std::unique_ptr<PoseStreamEncoder> make_encoder(const std::string& protocol, const std::optional<io::BoardConfig>& board,
                                                std::optional<int> component_id, const io::RobotConfig& config, int baud) {
  const LocalizerSetup& setup = config.setup;
  if (protocol == "stargazer") {
    return std::make_unique<StarGazerPoseStream>(setup.map, setup.mount.translation.z(), "irloc " IRLOC_VERSION, baud);
  }
  if (protocol != "mavlink") throw io::InputError("--protocol " + protocol + ": unknown (expected mavlink or stargazer)");
  MavlinkStreamSettings settings;
  if (board) {
    settings.address.system_id = static_cast<std::uint8_t>(board->mavlink.system_id);
    settings.address.component_id = static_cast<std::uint8_t>(board->mavlink.component_id);
    settings.position_floor_m = board->mavlink.position_sigma_m;
    settings.angle_floor_rad = board->mavlink.angle_sigma_rad;
  }
  if (component_id) settings.address.component_id = static_cast<std::uint8_t>(*component_id);
  if (config.ekf_origin) {
    settings.ekf_origin = GeoOrigin{config.ekf_origin->latitude_deg, config.ekf_origin->longitude_deg, config.ekf_origin->altitude_m};
  }
  if (config.odometry) settings.pose_message = MavlinkPoseMessage::odometry;
  settings.fixed_frame = setup.outside_in.has_value();
  return std::make_unique<MavlinkPoseStream>(settings);
}

// Every file the run reads and writes, checked by the one output policy before any work.
void check_run_files(const DaemonOptions& options, const std::filesystem::path& config_file, const io::RobotConfig& config,
                     const std::optional<io::BoardConfig>& board, const hal::Camera& camera) {
  io::RunFiles files;
  files.inputs(camera.input_files());
  files.inputs({config_file, config.calibration_file});
  if (!config.map_file.empty()) files.input(config.map_file);
  if (board) files.inputs({*options.board, board->camera.calibration});
  if (options.pose_csv) files.output_file("--pose-csv", *options.pose_csv);
  if (options.survey) files.output_file("--survey", *options.survey);
  if (options.stats) files.output_file("--stats", *options.stats);
  // The live view's save replaces it; it is read at start, and may be nothing else.
  if (options.camera_settings && !options.http.empty() && !options.http_read_only) {
    files.output_file("--camera-settings", *options.camera_settings);
  }
  if (options.calibrate) files.output_folder("--calibrate", *options.calibrate, CalibrationRun::kOutputFiles);
  if (options.record) files.new_folder("--record", *options.record);
  if (options.annotate) files.new_folder("--annotate", *options.annotate);
  files.check();
}

// The camera stopped delivering: no pose until it is back (the serial stream goes quiet, which an
// autopilot's EKF takes as a sensor timeout), a reopen attempt every 0.5 s, and the service
// watchdog still petted (the loop is alive; a hung loop is what the watchdog is for). False when
// a stop request came first.
bool wait_for_camera(hal::Camera& camera, const hal::DeviceLost& lost, const std::atomic<bool>* stop,
                     ServiceNotifier& notifier, SerialLink* link) {
  using Clock = std::chrono::steady_clock;
  print_warning(stderr, "%s: no pose until it is back; reopening every 0.5 s", lost.what());
  if (link) link->set_health(LinkHealth::critical);
  const Clock::time_point since = Clock::now();
  const auto stopping = [&] { return stop && stop->load(); };
  while (!stopping()) {
    if (camera.reopen()) {
      print_warning(stderr, "camera back after %.1f s",
                   std::chrono::duration<double>(Clock::now() - since).count());
      return true;
    }
    for (int slice = 0; slice < 10 && !stopping(); ++slice) std::this_thread::sleep_for(std::chrono::milliseconds(50));
    notifier.pet(Clock::now());
  }
  return false;
}

// One stderr line when the serial device goes away and one when it is back (the port reopens it
// itself, hal/linux/termios_serial.hpp).
class SerialWatch {
 public:
  explicit SerialWatch(std::string name) : name_(std::move(name)) {}
  void update(SerialLink& link) {
    using Clock = std::chrono::steady_clock;
    if (link.connected() == connected_) return;
    connected_ = !connected_;
    if (!connected_) {
      lost_at_ = Clock::now();
      print_warning(stderr, "serial %s lost (%s): messages dropped until it is back; reopening every 0.5 s",
                   name_.c_str(), std::strerror(link.last_error()));
    } else {
      print_warning(stderr, "serial %s back after %.1f s", name_.c_str(),
                   std::chrono::duration<double>(Clock::now() - lost_at_).count());
    }
  }

 private:
  std::string name_;
  bool connected_ = true;
  std::chrono::steady_clock::time_point lost_at_{};
};

// The saved setup controls (--camera-settings), when the file exists: requested from the camera
// before its first frame; the LED switch as saved.
void apply_camera_settings(const DaemonOptions& options, hal::Camera& camera, std::atomic<bool>& leds_enabled) {
  if (!options.camera_settings || !std::filesystem::exists(*options.camera_settings)) return;
  const io::CameraSettings settings = io::read_camera_settings(*options.camera_settings, camera.controls());
  for (const hal::CameraControl control : hal::kCameraControls) {
    if (settings[control]) camera.controls()->request(control, *settings[control]);
  }
  leds_enabled.store(settings.leds);
}

// The live view's settings from the command line, checked before any work; the token is made
// (or read) for an address other than loopback.
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

std::unique_ptr<LiveServer> start_live_server(const LiveServerSettings& settings, const DaemonOptions& options, LiveSlot& slot,
                                              const Localizer& localizer, LiveControlTargets targets) {
  auto server = std::make_unique<LiveServer>(settings, slot, live_view_geometry(localizer), targets);
  const bool ipv6 = settings.host.find(':') != std::string::npos;
  const std::string token_note = settings.token ? " (controls need the token in " + options.http_token.string() + ")" : "";
  std::fprintf(stderr, "irlocd: live view on http://%s%s%s:%d/%s\n", ipv6 ? "[" : "", settings.host.c_str(), ipv6 ? "]" : "",
               server->port(), token_note.c_str());
  return server;
}

// A replay watched in the live view: its last attempt stays on view until a stop request.
void linger_after_replay(LiveSlot& slot, const std::atomic<bool>* stop, ServiceNotifier& notifier) {
  slot.mark_stream_ended();
  std::fprintf(stderr, "irlocd: the recording has ended; the live view stays up until irlocd is stopped\n");
  while (stop && !stop->load()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    notifier.pet(ServiceNotifier::Clock::now());
  }
}

}  // namespace

DaemonSummary run_daemon(const DaemonOptions& options) {
  ServiceNotifier notifier;
  std::optional<io::BoardConfig> board;
  if (options.board) board = io::load_board(*options.board);
  const std::filesystem::path config_file = config_path(options, board);
  io::RobotConfig config = io::load_robot_config(config_file);
  if (board) check_calibration_size(*board, config);
  // The sensor mode's rolling shutter: the config's line time, else the board's (docs/formats.md);
  // a camera that reports its own per frame overrides both.
  if (board && config.setup.line_time_ns == 0) config.setup.line_time_ns = board->camera.line_time_ns;
  const bool outside_in = config.mode == io::RobotMode::outside_in;
  if (outside_in && (options.survey || options.calibrate)) {
    throw io::InputError(config_file.string() + ": mode: outside_in: " + (options.survey ? "--survey" : "--calibrate") +
                          " needs the camera on the robot (mode: on_robot)");
  }

  const std::string camera_spec = !options.camera.empty() ? options.camera : board ? "libcamera" : "";
  if (camera_spec.empty()) throw io::InputError("--camera: required without --board");
  const bool live = is_live_camera(camera_spec);
  const std::string protocol = protocol_name(options, board);
  const std::optional<SerialSpec> serial_spec = parse_serial_spec(serial_argument(options, board));
  std::vector<hal::Fault> faults;
  if (options.inject_faults) faults = hal::parse_fault_plan(*options.inject_faults);
  const std::optional<LiveServerSettings> live_settings = live_server_settings(options);
  const std::optional<LiveImage> annotate_image = live_image_named(options.annotate_image);
  if (!annotate_image) throw io::InputError("--annotate-image " + options.annotate_image + ": expected on or difference");

  // Devices in the order a user fixes them: serial, strobe, then the camera (slowest to start).
  const std::unique_ptr<hal::SerialPort> serial = open_serial(serial_spec);
  // Outside-in: the fixed camera has no strobe to drive; every frame is one pose attempt.
  std::optional<io::BoardStrobe> strobe_settings;
  if (board && !outside_in) strobe_settings = board->strobe;
  const std::unique_ptr<hal::Strobe> gpio_strobe = outside_in ? nullptr : open_strobe(camera_spec, strobe_settings);
  CameraRequest camera_request;
  camera_request.width = config.setup.camera.width;
  camera_request.height = config.setup.camera.height;
  camera_request.size_source = config.calibration_file.string();
  camera_request.board_camera = board ? &board->camera : nullptr;
  camera_request.strobe_latency_frames = strobe_settings ? strobe_settings->latency_frames : io::BoardStrobe{}.latency_frames;
  camera_request.stop = options.stop;
  std::unique_ptr<hal::Camera> camera = open_camera(camera_spec, camera_request);
  if (!faults.empty()) {
    // A device camera (libcamera) is really closed and reopened when a `lost` fault is over.
    const bool device = live && !camera_drives_its_leds(camera_spec);
    camera = std::make_unique<hal::FaultInjectingCamera>(std::move(camera), std::move(faults), options.stop, device);
  }
  if (options.paced && live) throw io::InputError("--paced: only for a recording (--camera dir:DATASET); a camera is paced by itself");
  if ((live_settings || options.paced) && !live) camera = std::make_unique<PacedCamera>(std::move(camera), options.stop);
  // The outside-in source's background and silhouette work on 8-bit grey (docs/outside_in.md).
  if (outside_in && camera->frames_are_16_bit()) {
    throw io::InputError("--camera " + camera_spec + ": its frames are 16-bit, but mode: outside_in (" +
                          config_file.string() + ") works on 8-bit frames only (grey, or YUYV's luma)");
  }
  std::atomic<bool> leds_enabled{true};
  apply_camera_settings(options, *camera, leds_enabled);
  hal::Strobe* strobe = outside_in ? nullptr : gpio_strobe ? gpio_strobe.get() : camera->built_in_strobe();
  if (strobe && !strobe_settings) strobe_settings.emplace();  // the simulator without a board

  check_run_files(options, config_file, config, board, *camera);
  std::optional<io::PoseCsvWriter> pose_csv;
  if (options.pose_csv) pose_csv.emplace(*options.pose_csv);
  std::optional<io::DatasetWriter> recorder;
  if (options.record) recorder.emplace(*options.record, camera->maxval());
  std::unique_ptr<PoseStreamEncoder> encoder;
  if (serial) encoder = make_encoder(protocol, board, options.component_id, config, serial_spec->baud);

  // The marker paths check the map against the camera when they are set up (markers above it,
  // squares square); what they refuse is a problem of the map as this calibration and config
  // describe the camera (a calibration that sees no ceiling is refused earlier, by its reader).
  if (strobe) {
    config.setup.strobe_check.noise_level = strobe_settings->noise_level;
    config.setup.strobe_check.min_contrast_ratio = strobe_settings->min_contrast_ratio;
  }
  std::optional<Localizer> localizer_storage;
  if (options.survey) config.setup.dot.observe_every_marker = true;
  try {
    localizer_storage.emplace(std::move(config.setup));
  } catch (const std::invalid_argument& e) {
    throw io::InputError(config.map_file.string() + ": " + e.what() + " (camera as calibrated in " +
                          config.calibration_file.string() + " and mounted in " + config_file.string() + ")");
  }
  Localizer& localizer = *localizer_storage;
  std::optional<CalibrationRun> calibration;
  if (options.calibrate) calibration.emplace(*options.calibrate, config_file, config.map_file, localizer);
  FrameLoopIo io;
  io.strobe = strobe;
  io.recorder = recorder ? &*recorder : nullptr;
  io.pose_csv = pose_csv ? &*pose_csv : nullptr;
  std::optional<SerialLink> link;
  if (serial) link.emplace(*serial, *encoder, stderr);
  const ScopedWarningListener warnings_to_link(link ? &*link : nullptr);
  io.link = link ? &*link : nullptr;
  io.every_frame = outside_in;
  std::optional<SurveyWriter> survey;
  if (options.survey) survey.emplace(*options.survey, config.map_file, localizer, stderr);
  std::optional<MountWatchMonitor> mount_watch;
  // The watch trusts the map, as a calibration does; a survey does not.
  if (config.mount_watch.enabled && !calibration && !options.survey) {
    mount_watch.emplace(localizer, localizer.setup().camera, localizer.setup().mount, localizer.setup().dof,
                        config.mount_watch, stderr);
  }
  AttemptObserverList observers;
  observers.add(calibration ? &*calibration : nullptr);
  observers.add(survey ? &*survey : nullptr);
  observers.add(mount_watch ? &*mount_watch : nullptr);
  std::optional<LiveSlot> live_slot;
  std::optional<LivePublisher> live_publisher;
  if (live_settings) {
    live_slot.emplace(camera->width(), camera->height(), camera->maxval());
    live_publisher.emplace(*live_slot, localizer);
    observers.add(&*live_publisher);
  }
  std::optional<AnnotatedFrames> annotated;
  if (options.annotate) {
    annotated.emplace(*options.annotate, localizer, camera->width(), camera->height(), camera->maxval(), *annotate_image);
    observers.add(&*annotated);
  }
  io.observer = &observers;
  if (strobe) io.leds_enabled = &leds_enabled;
  std::optional<StrobeSync> strobe_sync;
  if (strobe) strobe_sync.emplace(strobe_settings->latency_frames);
  FrameLoop loop(*camera, localizer, io, strobe_sync);
  if (live_publisher) live_publisher->watch(loop);
  if (annotated) annotated->watch(loop);
  std::unique_ptr<LiveServer> live_server;
  if (live_slot) {
    live_server = start_live_server(*live_settings, options, *live_slot, localizer,
                                    {camera->controls(), strobe ? &leds_enabled : nullptr});
  }

  const int priority = options.realtime_priority.value_or(board ? board->realtime_priority : 0);
  if (priority > 0) enter_realtime(priority);

  // The per-frame loop: nothing below allocates (recording excepted).
  StatusLine status(stderr, std::chrono::seconds(1));
  SerialWatch serial_watch(serial_argument(options, board));
  DaemonSummary summary;
  summary.line_time_ns = localizer.setup().line_time_ns;
  summary.resources_at_start = read_process_resources();
  const std::uint64_t allocations_at_start = options.allocations_so_far ? options.allocations_so_far() : 0;
  notifier.ready();
  LinkHealth health = LinkHealth::starting;
  while (true) {
    if (options.stop && options.stop->load()) {
      summary.stopped = true;
      break;
    }
    try {
      if (!loop.step()) {
        summary.stopped = options.stop && options.stop->load();
        break;
      }
      if (options.max_frames && loop.stats().frames >= *options.max_frames) {
        summary.stopped = true;
        break;
      }
    } catch (const hal::DeviceLost& lost) {
      health = LinkHealth::critical;
      if (!wait_for_camera(*camera, lost, options.stop, notifier, io.link)) continue;
      loop.restart_stream();
    }
    notifier.pet(ServiceNotifier::Clock::now());
    if (link) {
      const LinkHealth now_health = loop.strobe_unverified() ? LinkHealth::critical : LinkHealth::active;
      if (now_health != health) link->set_health(health = now_health);
      if (options.reopen_serial && options.reopen_serial->exchange(false)) {
        link->reopen_now();
        print_warning(stderr, "SIGHUP: serial device %s", link->connected() ? "reopened" : "not there; retrying");
      }
      serial_watch.update(*link);
    }
    if (live) {
      status.update(loop.stats(), loop.strobe_sync() ? &loop.strobe_sync()->stats() : nullptr,
                    link ? link->messages_dropped() : 0, mount_watch ? &mount_watch->state() : nullptr,
                    loop.latency(), StatusLine::Clock::now());
    }
  }
  if (options.allocations_so_far) summary.allocations_after_startup = options.allocations_so_far() - allocations_at_start;
  if (live_server && !live && !summary.stopped) linger_after_replay(*live_slot, options.stop, notifier);
  live_server.reset();
  summary.resources_at_end = read_process_resources();
  notifier.stopping();
  if (survey) {
    survey->finish();
    using Kind = irloc::survey::SurveyEvent::Kind;
    summary.survey = DaemonSummary::SurveyCounts{survey->reported(Kind::added), survey->reported(Kind::moved),
                                                 survey->reported(Kind::conflict)};
  }
  const FrameLoopStats& stats = loop.stats();
  summary.frames = stats.frames;
  summary.dropped_frames = stats.dropped_frames;
  if (loop.strobe_sync()) summary.strobe = loop.strobe_sync()->stats();
  summary.pose_attempts = stats.pose_attempts;
  summary.poses_ok = stats.poses_ok;
  summary.unpaired = stats.unpaired;
  summary.strobe_rejected = stats.strobe_rejected;
  summary.stage_totals = stats.stage_totals;
  summary.attempts_wall_ms = stats.attempts_wall_ms;
  summary.front_end_vs_memcpy = loop.front_end_vs_memcpy();
  summary.serial_dropped = link ? link->messages_dropped() : 0;
  if (loop.latency().count() > 0) {
    summary.latency = LatencySummary{loop.latency().count(), *loop.latency().quantile_ms(0.5), *loop.latency().quantile_ms(0.99)};
  }
  summary.source_outcomes = stats.source_outcomes;
  summary.outputs_failed = stats.outputs_failed + (survey && survey->last_write_failed() ? 1 : 0);
  if (calibration) std::fprintf(stderr, "irlocd: %s\n", calibration->finish().c_str());
  return summary;
}

}  // namespace irloc::firmware
