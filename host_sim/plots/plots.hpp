#pragma once
// PNG pictures of a run and of the planning tools, drawn with cairo (host_sim/plots/canvas.hpp):
// one source file per picture or pair of pictures.

#include <filesystem>
#include <string>
#include <vector>

#include "algo/map/marker_map.hpp"
#include "algo/pipeline/pose_estimate.hpp"
#include "host_sim/plots/calibration_residuals.hpp"
#include "host_sim/render/dataset_render.hpp"
#include "host_sim/metrics/camera_handover.hpp"
#include "host_sim/metrics/metrics.hpp"
#include "host_sim/render/wall_camera.hpp"

namespace irloc::sim {

// Top view: the true path, the ok pose estimates (gross errors marked) and the map's markers.
void plot_trajectory(const std::filesystem::path& png, const std::vector<TruthRow>& truth,
                     const std::vector<PoseEstimate>& poses, const Metrics& metrics, const MarkerMap& map);

// Position and yaw error of each ok pose over time, with the frames that gave no pose.
void plot_errors(const std::filesystem::path& png, const std::vector<TruthRow>& truth,
                 const std::vector<PoseEstimate>& poses, const Metrics& metrics);

// Several wall cameras (outside-in), along time: for each camera where it has the robot whole in
// view (a light band) and where it posed it (dark ticks), the combined stream's choice (ticks in
// the chosen camera's colour), and below each camera's position error of its ok poses.
// truth[i] and poses[i] are camera i's; `names` labels the cameras.
void plot_camera_handover(const std::filesystem::path& png, const std::vector<std::vector<OutsideInTruth>>& truth,
                          const std::vector<std::vector<PoseEstimate>>& poses, const CameraHandOver& combined,
                          const std::vector<std::string>& names, double gross_position);

// Top view of an outside-in room: each wall camera's floor footprint (what its image covers, cut
// at `reach` metres), its position and floor reference rectangle, the true path, and the combined
// stream's poses in the colour of the camera that gave them.
void plot_camera_room(const std::filesystem::path& png, const std::vector<WallCamera>& cameras,
                      const std::vector<std::array<Eigen::Vector2d, 4>>& floor_references, const CameraHandOver& combined,
                      const std::vector<std::string>& names, double reach = 12);

// A scalar field over a rectangle of the x-y plane, values row-major from (x0, y0) upward,
// `columns` x `rows` cells; colour scale from `low` to `high`. Marks are drawn as small white
// circles (markers, landmarks, the robot).
// Top view of a survey: the map it started from (the drawing: grey outlines), the surveyed map
// (blue, with its 1-sigma ellipses magnified `sigma_scale` times), the truth when there is one
// (green crosses; a real run has none) and, in red, arrows from the drawing to the estimate for
// markers that moved more than move_threshold.
void plot_survey_map(const std::filesystem::path& png, const MarkerMap& drawing, const MarkerMap& estimate,
                     const MarkerMap* truth, double sigma_scale = 100, double move_threshold = 0.4);

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

// The dots' reprojection residuals over the image before and after a calibration, side by side:
// the mean residual of the dots in each cell of a grid as an arrow (one scale for both).
void plot_calibration_residuals(const std::filesystem::path& png, const std::vector<DotResidualRow>& residuals,
                                int image_width, int image_height);

}  // namespace irloc::sim
