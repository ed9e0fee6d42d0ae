#pragma once
// irlocd's machine-readable run statistics (`--stats FILE`), for irloc-sim and other tools that
// should not parse the human stderr lines. JSON, written once at the end of the run:
//
//   {"frames": N, "pose_attempts": N, "poses_ok": N, "unpaired": N, "strobe_rejected": N,
//    "serial_dropped": N, "stopped": false,
//    "stages": [{"name": "front_end", "total_ms": T, "mean_ms": T / pose_attempts}, ...],
//    "resources_at_start": {"resident_kib": N, "open_fds": N}, "resources_at_end": {...},
//    "allocations_after_startup": N, "survey": {"markers_added": N, "markers_moved": N, "conflicts": N}}
//
// resources_at_start is read when start-up is done (READY=1), resources_at_end after the last
// frame; allocations_after_startup (heap allocations in between) only from irlocd-soak, the
// build with an allocation counter; survey (the events reported on stderr) only with --survey.
//
// Stages are in pipeline order. The file is replaced atomically (hal::replace_file_atomically).

#include <filesystem>

#include "firmware/daemon.hpp"

namespace irloc::firmware {

// Throws hal::InputError naming the file when it cannot be written.
void write_stats_file(const std::filesystem::path& path, const DaemonSummary& summary);

}  // namespace irloc::firmware
