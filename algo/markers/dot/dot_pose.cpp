#include "algo/markers/dot/dot_pose.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "algo/geometry/p3p.hpp"

namespace irloc::dot {
namespace {

inline constexpr std::size_t kMaxDots = kMaxMarkersInView * kCellCount;

// Tilt of the base z axis from W's z, radians: the level prior that ranks dof 6 candidates.
double tilt(const RigidTransform& world_from_base) {
  return std::acos(std::clamp(world_from_base.rotation(2, 2), -1.0, 1.0));
}

double ranking_cost(const PoseFit& fit, const RefinementOptions& options) {
  const double data = fit.cost / (options.pixel_sigma * options.pixel_sigma);
  if (options.dof != Dof::full6) return data;
  const double level = tilt(fit.world_from_base) / options.level_prior_sigma;
  return data + level * level;
}

// The marker closest to the image centre among those still used.
int central_marker(std::span<const MarkerObservation> markers, const Eigen::Vector2d& centre) {
  int best = -1;
  double best_distance = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < markers.size(); ++k) {
    if (!markers[k].used) continue;
    const double d = (markers[k].centre_pixel - centre).squaredNorm();
    if (d < best_distance) {
      best_distance = d;
      best = static_cast<int>(k);
    }
  }
  return best;
}

// P3P on the reference marker's O, X, Y, each solution refined with every used marker's dots.
PoseFit fit_used_markers(std::span<const MarkerObservation> markers, const MarkerObservation& reference,
                         const CameraModel& camera, const RigidTransform& base_from_camera,
                         const RefinementOptions& options) {
  StaticVector<Eigen::Vector3d, kMaxDots> world;
  StaticVector<Eigen::Vector2d, kMaxDots> pixels;
  for (const MarkerObservation& marker : markers) {
    if (!marker.used) continue;
    for (std::size_t k = 0; k < marker.dot_count; ++k) {
      world.push_back(marker.world[k]);
      pixels.push_back(marker.pixels[k]);
    }
  }
  std::array<Eigen::Vector3d, 3> triangle_world, triangle_bearings;
  for (std::size_t k = 0; k < reference.dot_count; ++k) {
    const int slot = reference.cells[k] == kCellO ? 0 : reference.cells[k] == kCellX ? 1 : reference.cells[k] == kCellY ? 2 : -1;
    if (slot < 0) continue;
    triangle_world[static_cast<std::size_t>(slot)] = reference.world[k];
    triangle_bearings[static_cast<std::size_t>(slot)] = reference.bearings[k];
  }
  P3PSolutions solutions;
  solve_p3p(triangle_world, triangle_bearings, solutions);

  const RigidTransform camera_from_base = base_from_camera.inverse();
  PoseFit best;
  double best_cost = std::numeric_limits<double>::infinity();
  for (const RigidTransform& camera_from_world : solutions) {
    const RigidTransform initial = camera_from_world.inverse() * camera_from_base;
    const PoseFit fit = refine_pose({world.begin(), world.size()}, {pixels.begin(), pixels.size()}, camera,
                                    base_from_camera, initial, options);
    if (!fit.ok) continue;
    const double cost = ranking_cost(fit, options);
    if (cost < best_cost) {
      best_cost = cost;
      best = fit;
    }
  }
  return best;
}

// RMS reprojection error of one marker's dots under a pose, px; infinity when a dot leaves the model.
double marker_rms(const MarkerObservation& marker, const CameraModel& camera, const RigidTransform& base_from_camera,
                  const RigidTransform& world_from_base) {
  const RigidTransform camera_from_world = (world_from_base * base_from_camera).inverse();
  double sum = 0;
  for (std::size_t k = 0; k < marker.dot_count; ++k) {
    Eigen::Vector2d projected;
    if (!camera.project(camera_from_world * marker.world[k], projected)) return std::numeric_limits<double>::infinity();
    sum += (projected - marker.pixels[k]).squaredNorm();
  }
  return std::sqrt(sum / marker.dot_count);
}

}  // namespace

DotPoseResult solve_dot_pose(std::span<MarkerObservation> markers, const CameraModel& camera,
                             const RigidTransform& base_from_camera, const DotPoseOptions& options) {
  DotPoseResult result;
  for (MarkerObservation& marker : markers) marker.used = true;
  const Eigen::Vector2d centre(camera.intrinsics().cx, camera.intrinsics().cy);
  // Each pass drops at most the worst-fitting marker, so there are at most as many passes as markers.
  for (std::size_t pass = 0; pass < markers.size(); ++pass) {
    const int reference = central_marker(markers, centre);
    if (reference < 0) break;
    PoseFit fit = fit_used_markers(markers, markers[static_cast<std::size_t>(reference)], camera, base_from_camera,
                                   options.refinement);
    if (!fit.ok) {
      // The reference's P3P gave nothing usable: try the next marker as reference.
      markers[static_cast<std::size_t>(reference)].used = false;
      continue;
    }
    int worst = -1;
    double worst_rms = options.marker_gate_px;
    int used = 0;
    for (std::size_t k = 0; k < markers.size(); ++k) {
      if (!markers[k].used) continue;
      ++used;
      const double rms = marker_rms(markers[k], camera, base_from_camera, fit.world_from_base);
      if (rms > worst_rms) {
        worst_rms = rms;
        worst = static_cast<int>(k);
      }
    }
    if (worst < 0) {
      result.fit = fit;
      result.reference_marker = reference;
      result.markers_used = used;
      return result;
    }
    markers[static_cast<std::size_t>(worst)].used = false;
  }
  for (MarkerObservation& marker : markers) marker.used = false;
  return result;
}

}  // namespace irloc::dot
