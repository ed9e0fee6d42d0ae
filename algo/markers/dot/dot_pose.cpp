#include "algo/markers/dot/dot_pose.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "algo/geometry/pose_solver.hpp"

namespace irloc::dot {
namespace {

inline constexpr std::size_t kMaxDots = kMaxMarkersInView * kCellCount;

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

// Every used marker's dots, P3P starts from the reference marker's O, X, Y.
PoseFit fit_used_markers(std::span<const MarkerObservation> markers, const MarkerObservation& reference,
                         const CameraModel& camera, const RigidTransform& base_from_camera,
                         const RefinementOptions& options) {
  StaticVector<Eigen::Vector3d, kMaxDots> world;
  StaticVector<Eigen::Vector2d, kMaxDots> pixels;
  PointTriple direction_dots{};
  int found = 0;
  for (const MarkerObservation& marker : markers) {
    if (!marker.used) continue;
    for (std::size_t k = 0; k < marker.dot_count; ++k) {
      if (&marker == &reference) {
        const int cell = marker.cells[k];
        const int slot = cell == kCellO ? 0 : cell == kCellX ? 1 : cell == kCellY ? 2 : -1;
        if (slot >= 0) {
          direction_dots[static_cast<std::size_t>(slot)] = world.size();
          ++found;
        }
      }
      world.push_back(marker.world[k]);
      pixels.push_back(marker.pixels[k]);
    }
  }
  if (found != 3) return {};
  return estimate_pose({world.begin(), world.size()}, {pixels.begin(), pixels.size()}, camera, base_from_camera,
                       options, direction_dots);
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
