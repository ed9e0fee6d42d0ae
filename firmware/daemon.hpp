#pragma once
// irlocd's main loop: frames from a camera, strobe pairing, the localizer, pose outputs.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "algo/pipeline/stage_times.hpp"

namespace irloc::firmware {

struct DaemonOptions {
  std::filesystem::path config;
  std::string camera;    // "dir:DATASET"
  std::string serial;    // "none" or "PATH[:BAUD]"
  std::string protocol;  // "mavlink" or "stargazer"
  std::optional<std::filesystem::path> pose_csv;
};

struct DaemonSummary {
  std::uint64_t frames = 0;
  std::uint64_t pose_attempts = 0;  // one per LED-on frame
  std::uint64_t poses_ok = 0;
  std::uint64_t unpaired = 0;       // LED-on frames without an adjacent LED-off frame
  // Per pipeline stage: its name and its total time over all pose attempts, milliseconds.
  StageClock::Times stage_totals;
};

// Runs until the camera's stream ends. Throws hal::InputError for bad input; whatever was
// written before the error stays written.
DaemonSummary run_daemon(const DaemonOptions& options);

}  // namespace irloc::firmware
