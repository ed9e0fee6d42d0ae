#include "host_sim/run/pipeline_process.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <sstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/input_error.hpp"

extern char** environ;

namespace irloc::sim {

std::filesystem::path irlocd_beside_this_program() {
  std::error_code error;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) throw io::InputError("/proc/self/exe: cannot find this program's folder: " + error.message());
  return self.parent_path() / "irlocd";
}

PipelineRun run_irlocd(const std::filesystem::path& irlocd, const std::filesystem::path& dataset,
                       const std::filesystem::path& pose_csv, const std::vector<std::string>& extra_args) {
  if (!std::filesystem::exists(irlocd)) {
    throw io::InputError(irlocd.string() + ": irlocd not found beside irloc-sim (build both: make)");
  }
  const std::filesystem::path log_path = pose_csv.parent_path() / "irlocd.log";
  const std::filesystem::path stats_path = pose_csv.parent_path() / "irlocd_stats.json";
  std::vector<std::string> args = {irlocd.string(), "--config", (dataset / "config.yaml").string(),
                                   "--camera", "dir:" + dataset.string(), "--serial", "none",
                                   "--pose-csv", pose_csv.string(), "--stats", stats_path.string()};
  args.insert(args.end(), extra_args.begin(), extra_args.end());
  std::vector<char*> argv;
  for (std::string& arg : args) argv.push_back(arg.data());
  argv.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  const auto start = std::chrono::steady_clock::now();
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) throw io::InputError(irlocd.string() + ": cannot start: " + std::strerror(spawned));
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw io::InputError(irlocd.string() + ": lost the child process: " + std::strerror(errno));
  }
  PipelineRun run;
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::ifstream log(log_path);
  std::ostringstream text;
  text << log.rdbuf();
  run.log = text.str();
  while (!run.log.empty() && run.log.back() == '\n') run.log.pop_back();
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw io::InputError("irlocd failed on " + dataset.string() + ": " + run.log);
  }
  run.stage_ms = read_stage_times(stats_path);
  run.source_outcomes = read_source_outcomes(stats_path);
  return run;
}

SourceOutcomes read_source_outcomes(const std::filesystem::path& stats_file) {
  std::ifstream in(stats_file);
  if (!in) throw io::InputError(stats_file.string() + ": cannot read irlocd's statistics");
  SourceOutcomes outcomes;
  try {
    const nlohmann::json stats = nlohmann::json::parse(in);
    for (const auto& [source, counts] : stats.at("sources").items()) {
      for (const auto& [outcome, count] : counts.items()) outcomes[source][outcome] = count.get<std::size_t>();
    }
  } catch (const nlohmann::json::exception& e) {
    throw io::InputError(stats_file.string() + ": not irlocd's statistics: " + e.what());
  }
  return outcomes;
}

std::vector<std::pair<std::string, double>> read_stage_times(const std::filesystem::path& stats_file) {
  std::ifstream in(stats_file);
  if (!in) throw io::InputError(stats_file.string() + ": cannot read irlocd's statistics");
  std::vector<std::pair<std::string, double>> stages;
  try {
    const nlohmann::json stats = nlohmann::json::parse(in);
    for (const nlohmann::json& stage : stats.at("stages")) {
      stages.emplace_back(stage.at("name").get<std::string>(), stage.at("mean_ms").get<double>());
    }
  } catch (const nlohmann::json::exception& e) {
    throw io::InputError(stats_file.string() + ": not irlocd's statistics: " + e.what());
  }
  return stages;
}

}  // namespace irloc::sim
