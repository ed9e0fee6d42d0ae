#pragma once
// Runs the pipeline on a rendered dataset exactly as replay on a robot does: the irlocd binary
// installed beside irloc-sim, as a child process, with the dataset's config.

#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace irloc::sim {

using SourceOutcomes = std::map<std::string, std::map<std::string, std::size_t>>;

struct PipelineRun {
  double seconds = 0;  // wall-clock time of the whole irlocd run
  std::string log;     // what irlocd wrote to stderr (its summary line, or its error)
  // Mean time per pose attempt of each pipeline stage, ms, in pipeline order, as irlocd reports it.
  std::vector<std::pair<std::string, double>> stage_ms;
  // Per pose source, its attempts by outcome (irlocd --stats `sources`).
  SourceOutcomes source_outcomes;

  // The last line of the log: irlocd's summary.
  std::string summary_line() const { return log.substr(log.find_last_of('\n') + 1); }
};

// The `sources` object of an irlocd `--stats` file: source name -> outcome -> attempts. Throws
// io::InputError naming the file when it is missing or not such a file.
SourceOutcomes read_source_outcomes(const std::filesystem::path& stats_file);

// The mean stage times of an irlocd `--stats` file (firmware/stats_file.hpp), in pipeline order.
// Throws io::InputError naming the file when it is missing or not such a file.
std::vector<std::pair<std::string, double>> read_stage_times(const std::filesystem::path& stats_file);

// The irlocd beside the running executable (both are built into build/bin).
std::filesystem::path irlocd_beside_this_program();

// Runs `irlocd --config DIR/config.yaml --camera dir:DIR --serial none --pose-csv POSE_CSV
// --stats irlocd_stats.json EXTRA_ARGS...` (beside POSE_CSV) and waits for it. Throws io::InputError with irlocd's own message when it fails.
PipelineRun run_irlocd(const std::filesystem::path& irlocd, const std::filesystem::path& dataset,
                       const std::filesystem::path& pose_csv, const std::vector<std::string>& extra_args = {});

}  // namespace irloc::sim
