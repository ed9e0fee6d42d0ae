// irloc-sim calibrate-mount: the camera's offset on the robot from a spin-in-place dataset, written
// into a copy of the config.

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <system_error>
#include <vector>

#include "io/config/config_file.hpp"
#include "io/files/run_files.hpp"
#include "host_sim/commands/commands.hpp"
#include "host_sim/tools/dot_tools.hpp"

namespace irloc::sim {
namespace {

// Every file in a dataset folder: what a replay of it reads.
std::vector<std::filesystem::path> dataset_files(const std::filesystem::path& dataset) {
  std::vector<std::filesystem::path> files;
  std::error_code error;
  for (const std::filesystem::directory_entry& entry : std::filesystem::directory_iterator(dataset, error)) {
    files.push_back(entry.path());
  }
  return files;
}

// A replay config's own files: the config, its calibration and its map.
std::vector<std::filesystem::path> config_files(const std::filesystem::path& config) {
  const io::RobotConfig robot = io::load_robot_config(config);
  std::vector<std::filesystem::path> files = {config, robot.calibration_file};
  if (!robot.map_file.empty()) files.push_back(robot.map_file);
  return files;
}

}  // namespace

void add_calibrate_mount_command(CommandLine& command_line) {
  struct Options {
    std::string config, dataset, out;
  };
  auto options = std::make_shared<Options>();
  Subcommand command = command_line.add("calibrate-mount", "camera offset from a spin-in-place dataset");
  command.text("--config", options->config, "config YAML", Need::required);
  command.text("--dataset", options->dataset, "spin-in-place dataset folder", Need::required);
  command.text("--out", options->out, "config to write (never --config itself, nor another input)", Need::required);
  command.action([options] {
    io::RunFiles files;
    files.inputs(config_files(options->config));
    files.inputs(dataset_files(options->dataset));
    files.output_file("--out", options->out);
    files.check();
    const MountCalibration mount = calibrate_mount(options->config, options->dataset);
    write_mount(options->config, options->out, mount);
    std::printf("irloc-sim calibrate-mount: %zu poses, turned %.1f rad, circle radius %.4f m (rms %.4f m); "
                "mount xyz [%.4f, %.4f, %.4f] written to %s\n",
                mount.poses, mount.fit.turned, mount.fit.radius, mount.fit.circle_rms, mount.fit.offset.x(),
                mount.fit.offset.y(), mount.z, options->out.c_str());
  });
}

}  // namespace irloc::sim
