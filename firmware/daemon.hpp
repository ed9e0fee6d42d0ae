#pragma once
// irlocd's start-up and run: devices from the command line and the board file, then the frame
// loop until the stream ends or a stop is requested.

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "algo/frames/stage_times.hpp"
#include "algo/source/outcome_counts.hpp"
#include "firmware/front_end_probe.hpp"
#include "firmware/process_resources.hpp"
#include "firmware/strobe_sync.hpp"

namespace irloc::firmware {

struct DaemonOptions {
  std::optional<std::filesystem::path> config;  // required unless the board names one
  std::optional<std::filesystem::path> board;   // boards/NAME.yaml
  std::string camera;    // "dir:DATASET", "libcamera[:ID]", "sim[:FRAMES]"; empty: the board's camera
  std::string serial;    // "none" or "PATH[:BAUD]"; empty: the board's serial, else none
  std::string protocol;  // "mavlink" or "stargazer"; empty: the board's, else mavlink
  std::optional<std::filesystem::path> pose_csv;
  std::optional<std::filesystem::path> stats;   // written by the caller at the end; checked with the other outputs
  std::optional<std::filesystem::path> record;  // write every frame as a dataset (docs/formats.md)
  std::optional<std::filesystem::path> calibrate;  // self-calibrate at the end into this folder (docs/calibration.md)
  std::optional<int> realtime_priority;         // overrides the board's
  std::optional<int> component_id;              // MAVLink component ID (1-255); overrides the board's
  std::optional<std::filesystem::path> survey;  // map building: the map file to write (docs/survey.md)
  std::optional<std::string> inject_faults;     // faults to inject into the camera (hal/sim/fault_plan.hpp)
  // The live view (docs/hardware.md): "ADDR:PORT" to serve it on; empty: off.
  std::string http;
  bool http_read_only = false;                  // the live view without its controls
  std::filesystem::path http_token = "/var/lib/irlocd/http-token";  // the controls' secret off loopback
  // Setup controls saved from the live view: applied at start when the file exists; "save" writes it.
  std::optional<std::filesystem::path> camera_settings;
  std::optional<std::filesystem::path> annotate;  // every attempt drawn as the live view draws it, as JPEGs here
  std::string annotate_image = "on";             // "on" or "difference"
  bool paced = false;  // replay a recording at its recorded pace (and measure capture-to-write latency)
  std::optional<std::uint64_t> max_frames;  // stop after this many frames, as a stop request does
  const std::atomic<bool>* stop = nullptr;      // set by SIGINT/SIGTERM: finish cleanly
  std::atomic<bool>* reopen_serial = nullptr;   // set by SIGHUP: close and open the serial device now
  // The process's heap allocations so far, where counted (the soak build, irlocd-soak); null: not counted.
  std::uint64_t (*allocations_so_far)() = nullptr;
};

// Capture (the frame's t_ns) to the serial write of its pose, over the run; live cameras only.
struct LatencySummary {
  std::uint64_t poses = 0;
  double median_ms = 0;
  double p99_ms = 0;
};

struct DaemonSummary {
  std::uint64_t frames = 0;
  std::uint64_t dropped_frames = 0;  // gaps in the camera's sequence numbers
  std::uint64_t pose_attempts = 0;  // one per LED-on frame
  std::uint64_t poses_ok = 0;
  std::uint64_t poses_revised = 0;  // revisable poses sent as the next attempt revised them
  std::uint64_t unpaired = 0;       // LED-on frames without an adjacent LED-off frame
  std::uint64_t strobe_rejected = 0;
  std::uint64_t serial_dropped = 0;
  std::uint64_t outputs_failed = 0;  // --record, --pose-csv or --survey lost data (the disk filled)
  bool stopped = false;             // ended by a stop request, not by the end of the stream
  StageClock::Times stage_totals;   // per pipeline stage: its total time over all attempts, ms
  double attempts_wall_ms = 0;      // the Localizer's wall time over the same attempts, ms
  std::optional<FrontEndVsMemcpy> front_end_vs_memcpy;
  std::optional<LatencySummary> latency;
  std::optional<StrobeSyncStats> strobe;  // live strobing: the pairs' brightness verdicts
  OutcomeCounts source_outcomes;    // per source: its attempts by outcome
  std::int64_t line_time_ns = 0;    // the rolling shutter assumed where a frame reports none
  // At the end of start-up (when READY=1 is sent) and after the last frame.
  ProcessResources resources_at_start;
  ProcessResources resources_at_end;
  std::optional<std::uint64_t> allocations_after_startup;  // with DaemonOptions::allocations_so_far
  // With --survey: the markers reported added, moved and seen at two places (one stderr line each).
  struct SurveyCounts {
    std::uint64_t added = 0, moved = 0, conflicts = 0;
  };
  std::optional<SurveyCounts> survey;
};

// Runs until the camera's stream ends or `stop` is set. Throws io::InputError for bad input or
// a missing device; whatever was written before the error stays written. A camera lost while
// running is reopened (every 0.5 s, until it is back or a stop is requested). A live camera prints
// a status line on stderr every second.
DaemonSummary run_daemon(const DaemonOptions& options);

}  // namespace irloc::firmware
