#include "host_sim/tools/dot_tools.hpp"

#include <cstdio>
#include <functional>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "algo/markers/dot/dot_marker_source.hpp"
#include "algo/markers/dot/grey_level_model.hpp"
#include "algo/pipeline/localizer.hpp"
#include "io/config/config_file.hpp"
#include "io/files/output_file.hpp"
#include "io/input_error.hpp"
#include "hal/replay/dataset_camera.hpp"

namespace irloc::sim {
namespace {

// Every strobe pair of the dataset through a Localizer made from setup; visit sees each result.
void replay(io::RobotConfig config, const std::filesystem::path& dataset,
            const std::function<void(const PoseEstimate&, const dot::DotMarkerSource&)>& visit) {
  hal::DatasetCamera camera(dataset, config.setup.camera.width, config.setup.camera.height,
                            config.calibration_file.string());
  if (config.setup.map.dot_markers.empty()) throw io::InputError(config.map_file.string() + ": the map has no dot markers");
  Localizer localizer(std::move(config.setup));
  StrobePairer pairer;
  const auto attempt = [&](const StrobePair& pair) { visit(localizer.process(pair), *localizer.find_source<dot::DotMarkerSource>()); };
  Frame frame;
  while (camera.next(frame)) {
    if (const std::optional<StrobePair> pair = pairer.push(frame)) attempt(*pair);
  }
  if (const std::optional<StrobePair> pair = pairer.flush()) attempt(*pair);
}

}  // namespace

ConfidenceFit fit_confidence(const std::filesystem::path& config, const std::filesystem::path& dataset) {
  io::RobotConfig robot = io::load_robot_config(config);
  const dot::GreyLevelModel start = robot.setup.dot.grey_levels;
  // Every candidate counts, so clutter must reach the candidate stage: no floor on the pose.
  robot.setup.dot.confidence_floor = 0;
  std::vector<double> intensities;
  replay(std::move(robot), dataset, [&](const PoseEstimate&, const dot::DotMarkerSource& path) {
    for (const dot::DotCandidate& candidate : path.last_candidates()) intensities.push_back(candidate.mean_intensity);
  });
  if (intensities.size() < 20) {
    throw io::InputError(dataset.string() + ": only " + std::to_string(intensities.size()) +
                          " dot candidates in the dataset; at least 20 are needed to fit the grey-level model");
  }
  return {dot::fit_grey_level_model(intensities, start), intensities.size()};
}

std::string grey_levels_yaml(const dot::GreyLevelModel& model) {
  char text[256];
  std::snprintf(text, sizeof text,
                "dot:\n  grey_levels:\n    dot: {weight: %.4f, mean: %.2f, sigma: %.2f}\n"
                "    clutter: {weight: %.4f, mean: %.2f, sigma: %.2f}\n",
                model.dot.weight, model.dot.mean, model.dot.sigma, model.clutter.weight, model.clutter.mean,
                model.clutter.sigma);
  return text;
}

MountCalibration calibrate_mount(const std::filesystem::path& config, const std::filesystem::path& dataset) {
  io::RobotConfig robot = io::load_robot_config(config);
  MountCalibration result;
  result.z = robot.setup.mount.translation.z();
  robot.setup.mount.translation.x() = 0;
  robot.setup.mount.translation.y() = 0;
  std::vector<dot::PlanarPose> poses;
  replay(std::move(robot), dataset, [&](const PoseEstimate& estimate, const dot::DotMarkerSource&) {
    if (estimate.ok) poses.push_back({estimate.x, estimate.y, estimate.yaw});
  });
  result.poses = poses.size();
  result.fit = dot::fit_mount_offset(poses);
  if (!result.fit.ok) {
    throw io::InputError(dataset.string() + ": no mount fit from " + std::to_string(poses.size()) +
                          " dot poses turning " + std::to_string(result.fit.turned) +
                          " rad (need >= 8 poses over at least half a turn of spinning in place)");
  }
  return result;
}

void write_mount(const std::filesystem::path& config, const std::filesystem::path& out, const MountCalibration& mount) {
  YAML::Node root = YAML::LoadFile(config.string());
  YAML::Node xyz(YAML::NodeType::Sequence);
  xyz.SetStyle(YAML::EmitterStyle::Flow);
  xyz.push_back(mount.fit.offset.x());
  xyz.push_back(mount.fit.offset.y());
  xyz.push_back(mount.z);
  root["camera"]["mount"]["xyz"] = xyz;
  YAML::Emitter emitter;
  emitter.SetDoublePrecision(6);
  emitter << root;
  io::replace_file_atomically(out, std::string(emitter.c_str()) + "\n", 0644, "the config");
}

}  // namespace irloc::sim
