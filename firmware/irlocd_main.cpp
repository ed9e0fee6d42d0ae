// irlocd: the irloc daemon. Reads frames, finds ceiling markers, streams the robot's pose.

#include <cstdio>
#include <exception>

#include <CLI/CLI.hpp>

#include "firmware/daemon.hpp"
#include "hal/input_error.hpp"

int main(int argc, char** argv) {
  irloc::firmware::DaemonOptions options;
  std::string pose_csv;
  CLI::App app{"irlocd: robot pose from ceiling markers"};
  app.add_option("--config", options.config, "config YAML (camera, robot, map)")->required();
  app.add_option("--camera", options.camera, "frame source: dir:DATASET replays a dataset")->required();
  app.add_option("--serial", options.serial, "pose stream output: none, or PATH[:BAUD]")->default_val("none");
  app.add_option("--protocol", options.protocol, "serial protocol")
      ->check(CLI::IsMember({"mavlink", "stargazer"}))
      ->default_val("mavlink");
  app.add_option("--pose-csv", pose_csv, "write every pose attempt to this CSV file");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int status = app.exit(e);
    return status == 0 ? 0 : 2;
  }
  if (!pose_csv.empty()) options.pose_csv = pose_csv;

  try {
    const irloc::firmware::DaemonSummary summary = irloc::firmware::run_daemon(options);
    std::fprintf(stderr, "irlocd: %llu frames, %llu pose attempts (%llu without an LED-off partner), %llu poses ok\n",
                 static_cast<unsigned long long>(summary.frames), static_cast<unsigned long long>(summary.pose_attempts),
                 static_cast<unsigned long long>(summary.unpaired), static_cast<unsigned long long>(summary.poses_ok));
    if (!summary.stage_totals.empty() && summary.pose_attempts > 0) {
      std::fprintf(stderr, "irlocd: mean stage times per pose attempt (ms):");
      for (const irloc::StageTime& stage : summary.stage_totals) {
        std::fprintf(stderr, " %s %.4f", stage.name, stage.milliseconds / static_cast<double>(summary.pose_attempts));
      }
      std::fprintf(stderr, "\n");
    }
    return 0;
  } catch (const irloc::hal::InputError& e) {
    std::fprintf(stderr, "irlocd: error: %s\n", e.what());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "irlocd: internal error: %s\n", e.what());
  }
  return 1;
}
