#pragma once
// irlocd's machine-readable run statistics (`--stats FILE`), for irloc-sim and other tools that
// should not parse the human stderr lines. JSON, written once at the end of the run:
//
//   {"frames": N, "pose_attempts": N, "poses_ok": N, "poses_revised": N, "unpaired": N, "strobe_rejected": N,
//    "serial_dropped": N, "stopped": false,
//    "stages": [{"name": "front_end", "total_ms": T, "mean_ms": T / pose_attempts}, ...],
//    "attempts_wall": {"total_ms": T, "mean_ms": T / pose_attempts},
//    "front_end_vs_memcpy": {"samples": N, "front_end_ms": T, "memcpy_pair_ms": T, "ratio": R},
//    "resources_at_start": {"resident_kib": N, "open_fds": N}, "resources_at_end": {...},
//    "allocations_after_startup": N, "survey": {"markers_added": N, "markers_moved": N, "conflicts": N}}
//
// attempts_wall is the Localizer's wall time over the attempts whose stages are summed, so the
// stages' total_ms add up to its total_ms (the rest is the Localizer's own bookkeeping).
// front_end_vs_memcpy (firmware/front_end_probe.hpp): medians over sampled pairs of the front_end
// stage and of a memcpy of the same pair; absent when no pair was computed.
// resources_at_start is read when start-up is done (READY=1), resources_at_end after the last
// frame; allocations_after_startup (heap allocations in between) only from irlocd-soak, the
// build with an allocation counter; survey (the events reported on stderr) only with --survey.
//
// Stages are in pipeline order. The file is replaced atomically (io::replace_file_atomically).

#include <filesystem>

#include "firmware/daemon.hpp"

namespace irloc::firmware {

// Throws io::InputError naming the file when it cannot be written.
void write_stats_file(const std::filesystem::path& path, const DaemonSummary& summary);

}  // namespace irloc::firmware
