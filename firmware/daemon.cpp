#include "firmware/daemon.hpp"

#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <thread>
#include <tuple>
#include <utility>

#include "algo/pipeline/localizer.hpp"
#include "firmware/calibration_run.hpp"
#include "firmware/camera_source.hpp"
#include "firmware/frame_loop.hpp"
#include "firmware/loop_outputs.hpp"
#include "firmware/live/annotated_frames.hpp"
#include "firmware/live/http_token.hpp"
#include "firmware/live/live_server.hpp"
#include "firmware/live/paced_camera.hpp"
#include "firmware/protocol/mavlink_pose_stream.hpp"
#include "firmware/protocol/stargazer_pose_stream.hpp"
#include "firmware/realtime.hpp"
#include "firmware/run_plan.hpp"
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

std::unique_ptr<PoseStreamEncoder> make_encoder(const RunPlan& plan, std::optional<int> component_id) {
  const std::string& protocol = plan.protocol;
  const std::optional<io::BoardConfig>& board = plan.board;
  const io::RobotConfig& config = plan.config;
  const LocalizerSetup& setup = config.setup;
  const int baud = plan.serial->baud;
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
void check_run_files(const DaemonOptions& options, const RunPlan& plan, const hal::Camera& camera) {
  io::RunFiles files;
  files.inputs(camera.input_files());
  files.inputs({plan.config_file, plan.config.calibration_file});
  if (!plan.config.map_file.empty()) files.input(plan.config.map_file);
  if (plan.board) files.inputs({*options.board, plan.board->camera.calibration});
  // The live view's token (made, if absent, when the plan was made): read, never replaced.
  if (plan.live_view && plan.live_view->token) files.input(options.http_token);
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

// One irlocd run in its stages: resolve (RunPlan), open the devices, open the outputs, make the
// localizer and the loop with its observers, run the frame loop, summarize. A member is set by its stage and
// lives until the run ends; the constructor does all start-up, run() the rest.
class DaemonRun {
 public:
  DaemonRun(const DaemonOptions& options, ServiceNotifier& notifier)
      : options_(options), notifier_(notifier), plan_(resolve_run(options)) {
    open_devices();
    check_run_files(options_, plan_, *camera_);
    open_outputs();
    make_localizer();
    attach_observers();
  }

  DaemonSummary run();

 private:
  void open_devices();
  void open_camera_stack();
  void open_outputs();
  void make_localizer();
  void attach_observers();
  // One frame and what follows it (service watchdog, serial health, status line); false when
  // the run is over, with summary.stopped set.
  bool step(DaemonSummary& summary);
  void after_step();
  void summarize(DaemonSummary& summary);

  const DaemonOptions& options_;
  ServiceNotifier& notifier_;
  RunPlan plan_;
  // Devices.
  std::unique_ptr<hal::SerialPort> serial_;
  std::unique_ptr<hal::Strobe> gpio_strobe_;
  std::unique_ptr<hal::Camera> camera_;
  std::optional<io::BoardStrobe> strobe_settings_;
  std::atomic<bool> leds_enabled_{true};  // the live view's LED switch
  // The GPIO line or the camera's own LEDs, with the schedule, until the loop takes it; none in
  // replay and outside-in.
  std::optional<LiveStrobing> live_strobing_;
  // Outputs.
  std::optional<io::PoseCsvWriter> pose_csv_;
  std::optional<io::DatasetWriter> recorder_;
  std::unique_ptr<PoseStreamEncoder> encoder_;
  std::optional<SerialLink> link_;
  std::optional<ScopedWarningListener> warnings_to_link_;
  // The localizer and the observers of its attempts.
  std::optional<Localizer> localizer_;
  std::optional<CalibrationRun> calibration_;
  std::optional<SurveyWriter> survey_;
  std::optional<MountWatchMonitor> mount_watch_;
  std::optional<LiveSlot> live_slot_;
  std::optional<LivePublisher> live_publisher_;
  std::optional<AnnotatedFrames> annotated_;
  // The loop's outputs and observers.
  std::optional<RecordingOutput> recording_;
  std::optional<PoseCsvOutput> pose_csv_output_;
  std::optional<PoseStreamOutput> pose_stream_;
  LatencyHistogram no_pose_stream_;  // the latency without a pose stream: empty
  std::optional<FrameLoop> loop_;
  std::unique_ptr<LiveServer> live_server_;
  // The loop's state.
  LinkHealth health_ = LinkHealth::starting;
  std::optional<StatusLine> status_;
  std::optional<SerialWatch> serial_watch_;
};

// Devices in the order a user fixes them: serial, strobe, then the camera (slowest to start).
void DaemonRun::open_devices() {
  serial_ = open_serial(plan_.serial);
  // Outside-in: the fixed camera has no strobe to drive; every frame is one pose attempt.
  if (plan_.board && !plan_.outside_in) strobe_settings_ = plan_.board->strobe;
  if (!plan_.outside_in) gpio_strobe_ = open_strobe(plan_.camera_spec, strobe_settings_);
  open_camera_stack();
  apply_camera_settings(options_, *camera_, leds_enabled_);
  if (plan_.outside_in) return;
  hal::Strobe* strobe = gpio_strobe_ ? gpio_strobe_.get() : camera_->built_in_strobe();
  if (strobe == nullptr) return;  // a replayed dataset: its frames are labelled
  if (!strobe_settings_) strobe_settings_.emplace();  // the simulator without a board
  live_strobing_.emplace(LiveStrobing{*strobe, StrobeSync(strobe_settings_->latency_frames), leds_enabled_});
}

// The camera, with the fault injector and the pacing of a replay around it where asked.
void DaemonRun::open_camera_stack() {
  CameraRequest request;
  request.width = plan_.config.setup.camera.width;
  request.height = plan_.config.setup.camera.height;
  request.size_source = plan_.config.calibration_file.string();
  request.board_camera = plan_.board ? &plan_.board->camera : nullptr;
  request.strobe_latency_frames = strobe_settings_ ? strobe_settings_->latency_frames : io::BoardStrobe{}.latency_frames;
  request.stop = options_.stop;
  camera_ = open_camera(plan_.camera_spec, request);
  if (!plan_.faults.empty()) {
    // A device camera (libcamera) is really closed and reopened when a `lost` fault is over.
    const bool device = plan_.live && !camera_drives_its_leds(plan_.camera_spec);
    camera_ = std::make_unique<hal::FaultInjectingCamera>(std::move(camera_), std::move(plan_.faults), options_.stop, device);
  }
  if ((plan_.live_view || options_.paced) && !plan_.live) camera_ = std::make_unique<PacedCamera>(std::move(camera_), options_.stop);
  // The outside-in source's background and silhouette work on 8-bit grey (docs/outside_in.md).
  if (plan_.outside_in && camera_->frames_are_16_bit()) {
    throw io::InputError("--camera " + plan_.camera_spec + ": its frames are 16-bit, but mode: outside_in (" +
                         plan_.config_file.string() + ") works on 8-bit frames only (grey, or YUYV's luma)");
  }
}

void DaemonRun::open_outputs() {
  if (options_.pose_csv) pose_csv_.emplace(*options_.pose_csv);
  if (options_.record) recorder_.emplace(*options_.record, camera_->maxval());
  if (!serial_) return;
  encoder_ = make_encoder(plan_, options_.component_id);
  link_.emplace(*serial_, *encoder_, stderr);
  warnings_to_link_.emplace(&*link_);
}

// The marker paths check the map against the camera when they are set up (markers above it,
// squares square); what they refuse is a problem of the map as this calibration and config
// describe the camera (a calibration that sees no ceiling is refused earlier, by its reader).
void DaemonRun::make_localizer() {
  io::RobotConfig& config = plan_.config;
  if (live_strobing_) {
    config.setup.strobe_check.noise_level = strobe_settings_->noise_level;
    config.setup.strobe_check.min_contrast_ratio = strobe_settings_->min_contrast_ratio;
  }
  if (options_.survey) config.setup.dot.observe_every_marker = true;
  try {
    localizer_.emplace(std::move(config.setup));
  } catch (const std::invalid_argument& e) {
    throw io::InputError(config.map_file.string() + ": " + e.what() + " (camera as calibrated in " +
                         config.calibration_file.string() + " and mounted in " + plan_.config_file.string() + ")");
  }
}

void DaemonRun::attach_observers() {
  Localizer& localizer = *localizer_;
  const io::RobotConfig& config = plan_.config;
  FrameLoopIo io;
  io.every_frame = plan_.outside_in;
  if (recorder_) io.frames.add(&recording_.emplace(*recorder_));
  if (pose_csv_) io.poses.add(&pose_csv_output_.emplace(*pose_csv_));
  if (link_) io.poses.add(&pose_stream_.emplace(*link_, *camera_));
  if (options_.calibrate) io.attempts.add(&calibration_.emplace(*options_.calibrate, plan_.config_file, config.map_file, localizer));
  if (options_.survey) io.attempts.add(&survey_.emplace(*options_.survey, config.map_file, localizer, stderr));
  // The watch trusts the map, as a calibration does; a survey does not.
  if (config.mount_watch.enabled && !calibration_ && !options_.survey) {
    io.attempts.add(&mount_watch_.emplace(localizer, localizer.setup().camera, localizer.setup().mount,
                                          localizer.setup().dof, config.mount_watch, stderr));
  }
  if (plan_.live_view) {
    live_slot_.emplace(camera_->width(), camera_->height(), camera_->maxval());
    io.attempts.add(&live_publisher_.emplace(*live_slot_, localizer));
  }
  if (options_.annotate) {
    io.attempts.add(&annotated_.emplace(*options_.annotate, localizer, camera_->width(), camera_->height(),
                                        camera_->maxval(), plan_.annotate_image));
  }
  // The loop keeps the schedule and its figures (loop_->strobe_sync()): no second copy stays here.
  loop_.emplace(*camera_, localizer, io, std::exchange(live_strobing_, std::nullopt));
  if (live_publisher_) live_publisher_->watch(*loop_);
  if (annotated_) annotated_->watch(*loop_);
  if (live_slot_) {
    live_server_ = start_live_server(*plan_.live_view, options_, *live_slot_, localizer,
                                     {camera_->controls(), loop_->strobe_sync() ? &leds_enabled_ : nullptr});
  }
}

bool DaemonRun::step(DaemonSummary& summary) {
  const bool stop_requested = options_.stop && options_.stop->load();
  if (stop_requested) {
    summary.stopped = true;
    return false;
  }
  try {
    if (!loop_->step()) {
      summary.stopped = options_.stop && options_.stop->load();
      return false;
    }
    if (options_.max_frames && loop_->stats().frames >= *options_.max_frames) {
      summary.stopped = true;
      return false;
    }
  } catch (const hal::DeviceLost& lost) {
    health_ = LinkHealth::critical;
    if (!wait_for_camera(*camera_, lost, options_.stop, notifier_, link_ ? &*link_ : nullptr)) return true;
    loop_->restart_stream();
  }
  after_step();
  return true;
}

void DaemonRun::after_step() {
  notifier_.pet(ServiceNotifier::Clock::now());
  if (link_) {
    const LinkHealth now_health = loop_->strobe_unverified() ? LinkHealth::critical : LinkHealth::active;
    if (now_health != health_) link_->set_health(health_ = now_health);
    if (options_.reopen_serial && options_.reopen_serial->exchange(false)) {
      link_->reopen_now();
      print_warning(stderr, "SIGHUP: serial device %s", link_->connected() ? "reopened" : "not there; retrying");
    }
    serial_watch_->update(*link_);
  }
  if (plan_.live) {
    status_->update(loop_->stats(), loop_->strobe_sync() ? &loop_->strobe_sync()->stats() : nullptr,
                    link_ ? link_->messages_dropped() : 0, mount_watch_ ? &mount_watch_->state() : nullptr,
                    pose_stream_ ? pose_stream_->latency() : no_pose_stream_, StatusLine::Clock::now());
  }
}

DaemonSummary DaemonRun::run() {
  const int priority = options_.realtime_priority.value_or(plan_.board ? plan_.board->realtime_priority : 0);
  if (priority > 0) enter_realtime(priority);
  // The per-frame loop: nothing in it allocates (recording excepted).
  status_.emplace(stderr, std::chrono::seconds(1));
  serial_watch_.emplace(plan_.serial_argument);
  DaemonSummary summary;
  summary.line_time_ns = localizer_->setup().line_time_ns;
  summary.resources_at_start = read_process_resources();
  const std::uint64_t allocations_at_start = options_.allocations_so_far ? options_.allocations_so_far() : 0;
  notifier_.ready();
  while (step(summary)) {
  }
  loop_->finish();
  if (options_.allocations_so_far) summary.allocations_after_startup = options_.allocations_so_far() - allocations_at_start;
  if (live_server_ && !plan_.live && !summary.stopped) linger_after_replay(*live_slot_, options_.stop, notifier_);
  live_server_.reset();
  summary.resources_at_end = read_process_resources();
  notifier_.stopping();
  summarize(summary);
  return summary;
}

void DaemonRun::summarize(DaemonSummary& summary) {
  if (survey_) {
    survey_->finish();
    using Kind = irloc::survey::SurveyEvent::Kind;
    summary.survey = DaemonSummary::SurveyCounts{survey_->reported(Kind::added), survey_->reported(Kind::moved),
                                                 survey_->reported(Kind::conflict)};
  }
  const FrameLoopStats& stats = loop_->stats();
  summary.frames = stats.frames;
  summary.dropped_frames = stats.dropped_frames;
  if (loop_->strobe_sync()) summary.strobe = loop_->strobe_sync()->stats();
  summary.pose_attempts = stats.pose_attempts;
  summary.poses_ok = stats.poses_ok;
  summary.poses_revised = stats.poses_revised;
  summary.unpaired = stats.unpaired;
  summary.strobe_rejected = stats.strobe_rejected;
  summary.stage_totals = stats.stage_totals;
  summary.attempts_wall_ms = stats.attempts_wall_ms;
  summary.front_end_vs_memcpy = loop_->front_end_vs_memcpy();
  summary.serial_dropped = link_ ? link_->messages_dropped() : 0;
  const LatencyHistogram& latency = pose_stream_ ? pose_stream_->latency() : no_pose_stream_;
  if (latency.count() > 0) summary.latency = LatencySummary{latency.count(), *latency.quantile_ms(0.5), *latency.quantile_ms(0.99)};
  summary.source_outcomes = stats.source_outcomes;
  summary.outputs_failed = stats.outputs_failed + (survey_ && survey_->last_write_failed() ? 1 : 0);
  if (calibration_) std::fprintf(stderr, "irlocd: %s\n", calibration_->finish().c_str());
}

}  // namespace

DaemonSummary run_daemon(const DaemonOptions& options) {
  ServiceNotifier notifier;
  DaemonRun run(options, notifier);
  return run.run();
}

}  // namespace irloc::firmware
