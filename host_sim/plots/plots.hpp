#pragma once
// PNG pictures of a run and of the planning tools, drawn with cairo.

#include <filesystem>
#include <string>
#include <vector>

#include "algo/map/marker_map.hpp"
#include "algo/pipeline/pose_estimate.hpp"
#include "host_sim/render/dataset_render.hpp"
#include "host_sim/metrics/metrics.hpp"

namespace irloc::sim {

// Top view: the true path, the ok pose estimates (gross errors marked) and the map's markers.
void plot_trajectory(const std::filesystem::path& png, const std::vector<TruthRow>& truth,
                     const std::vector<PoseEstimate>& poses, const Metrics& metrics, const MarkerMap& map);

// Position and yaw error of each ok pose over time, with the frames that gave no pose.
void plot_errors(const std::filesystem::path& png, const std::vector<TruthRow>& truth,
                 const std::vector<PoseEstimate>& poses, const Metrics& metrics);

// A scalar field over a rectangle of the x-y plane, values row-major from (x0, y0) upward,
// `columns` x `rows` cells; colour scale from `low` to `high`. Marks are drawn as small white
// circles (markers, landmarks, the robot).
struct HeatMap {
  std::vector<double> values;
  int columns = 0, rows = 0;
  double x0 = 0, y0 = 0, x1 = 1, y1 = 1;
  double low = 0, high = 1;
  std::string title, unit;
  std::vector<Eigen::Vector2d> marks;
  bool discrete = false;  // integer counts: one colour per value
};
void plot_heat_map(const std::filesystem::path& png, const HeatMap& map);

}  // namespace irloc::sim
