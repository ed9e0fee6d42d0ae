#include "firmware/stats_file.hpp"

#include <string>

#include <nlohmann/json.hpp>

#include "io/files/output_file.hpp"

namespace irloc::firmware {

void write_stats_file(const std::filesystem::path& path, const DaemonSummary& summary) {
  nlohmann::json stages = nlohmann::json::array();
  for (const StageTime& stage : summary.stage_totals) {
    const double mean = summary.pose_attempts > 0 ? stage.milliseconds / static_cast<double>(summary.pose_attempts) : 0;
    stages.push_back({{"name", stage.name}, {"total_ms", stage.milliseconds}, {"mean_ms", mean}});
  }
  // {"led": {"found": 90, "ambiguous": 3, ...}, "dot": {...}}: each source's attempts by outcome.
  nlohmann::json sources = nlohmann::json::object();
  for (const OutcomeCount& entry : summary.source_outcomes.counts()) {
    sources[std::string(to_string(entry.source))][entry.outcome] = entry.count;
  }
  const auto resources = [](const ProcessResources& r) { return nlohmann::json{{"resident_kib", r.resident_kib}, {"open_fds", r.open_fds}}; };
  nlohmann::json stats = {{"frames", summary.frames},
                                {"dropped_frames", summary.dropped_frames},
                                {"pose_attempts", summary.pose_attempts},
                                {"poses_ok", summary.poses_ok},
                                {"poses_revised", summary.poses_revised},
                                {"unpaired", summary.unpaired},
                                {"strobe_rejected", summary.strobe_rejected},
                                {"serial_dropped", summary.serial_dropped},
                                {"stopped", summary.stopped},
                                {"line_time_ns", summary.line_time_ns},
                                {"stages", stages},
                                {"attempts_wall", {{"total_ms", summary.attempts_wall_ms},
                                                   {"mean_ms", summary.pose_attempts > 0 ? summary.attempts_wall_ms / static_cast<double>(summary.pose_attempts) : 0}}},
                                {"sources", sources},
                                {"resources_at_start", resources(summary.resources_at_start)},
                                {"resources_at_end", resources(summary.resources_at_end)}};
  if (summary.latency) {
    stats["capture_to_write_ms"] = {{"poses", summary.latency->poses}, {"median", summary.latency->median_ms}, {"p99", summary.latency->p99_ms}};
  }
  if (const auto& probe = summary.front_end_vs_memcpy) {
    stats["front_end_vs_memcpy"] = {{"samples", probe->samples},
                                    {"front_end_ms", probe->front_end_ms},
                                    {"memcpy_pair_ms", probe->memcpy_pair_ms},
                                    {"ratio", probe->ratio}};
  }
  if (summary.strobe) {
    stats["strobe"] = {{"verified", summary.strobe->verified},
                       {"swapped", summary.strobe->swapped},
                       {"no_contrast", summary.strobe->no_contrast},
                       {"resyncs", summary.strobe->resyncs}};
  }
  if (summary.allocations_after_startup) stats["allocations_after_startup"] = *summary.allocations_after_startup;
  if (summary.survey) {
    stats["survey"] = {{"markers_added", summary.survey->added},
                       {"markers_moved", summary.survey->moved},
                       {"conflicts", summary.survey->conflicts}};
  }
  io::replace_file_atomically(path, stats.dump(2) + "\n", 0644, "the statistics");
}

}  // namespace irloc::firmware
