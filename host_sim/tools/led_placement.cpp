#include "host_sim/tools/led_placement.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "algo/geometry/camera_model.hpp"
#include "algo/geometry/pose_refinement.hpp"
#include "host_sim/render/marker_view.hpp"
#include "host_sim/tools/planning.hpp"
#include "host_sim/render/radiometry.hpp"

namespace irloc::sim {

HeatMap led_position_error_map(const Scenario& scenario, double cell, int headings, double pixel_sigma) {
  // The floor grid of the coverage map, with the landmarks marked.
  HeatMap map = landmark_coverage(scenario, cell, 1);
  map.values.clear();
  map.discrete = false;
  map.unit = "mm";
  const CameraModel camera(scenario.camera.intrinsics);
  RigidTransform mount;
  mount.rotation = scenario.camera.mount.linear();
  mount.translation = scenario.camera.mount.translation();
  RefinementOptions options;
  options.dof = scenario.dof;
  options.loss = RobustLoss::none;
  options.pixel_sigma = pixel_sigma;
  const std::size_t needed = scenario.dof == Dof::full6 ? 3 : 2;
  double worst_seen = 0;
  for (int r = 0; r < map.rows; ++r) {
    for (int c = 0; c < map.columns; ++c) {
      const double x = map.x0 + (c + 0.5) * (map.x1 - map.x0) / map.columns;
      const double y = map.y0 + (r + 0.5) * (map.y1 - map.y0) / map.rows;
      double worst = 0;
      for (int k = 0; k < headings && std::isfinite(worst); ++k) {
        RigidTransform pose;
        pose.rotation = rotation_from_rpy(0, 0, 2 * std::numbers::pi * k / headings);
        pose.translation = {x, y, 0};
        Eigen::Isometry3d t_w_b = Eigen::Isometry3d::Identity();
        t_w_b.linear() = pose.rotation;
        t_w_b.translation() = pose.translation;
        const Eigen::Vector3d camera_centre = (t_w_b * scenario.camera.mount).translation();
        std::vector<Eigen::Vector3d> world;
        std::vector<Eigen::Vector2d> pixels;
        for (const LedLandmark& landmark : scenario.map.led_landmarks) {
          if (landmark_intensity(landmark, 1.0, camera_centre) <= 0) continue;
          const ProjectedPoint p = project_points(camera, t_w_b, scenario.camera.mount, {landmark.position}).front();
          if (!p.visible) continue;
          world.push_back(landmark.position);
          pixels.push_back(p.pixel);
        }
        const PoseFit fit = world.size() >= needed ? refine_pose(world, pixels, camera, mount, pose, options) : PoseFit{};
        const double sigma = fit.ok ? std::sqrt(fit.covariance(0, 0) + fit.covariance(1, 1)) : 0;
        worst = fit.ok && std::isfinite(sigma) ? std::max(worst, 1e3 * sigma) : std::numeric_limits<double>::quiet_NaN();
      }
      if (std::isfinite(worst)) worst_seen = std::max(worst_seen, worst);
      map.values.push_back(worst);
    }
  }
  map.low = 0;
  map.high = std::max(worst_seen, 1e-6);
  return map;
}

}  // namespace irloc::sim
