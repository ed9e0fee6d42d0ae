#include "algo/markers/dot/dot_pose.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

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

// Every used marker's dots, and where the reference marker's O, X, Y are among them (when given).
struct UsedDots {
  StaticVector<Eigen::Vector3d, kMaxDots> world;
  StaticVector<Eigen::Vector2d, kMaxDots> pixels;
  PointTriple direction_dots{};
  int direction_dots_found = 0;
};

void collect_used_dots(std::span<const MarkerObservation> markers, const MarkerObservation* reference, UsedDots& dots) {
  for (const MarkerObservation& marker : markers) {
    if (!marker.used) continue;
    for (std::size_t k = 0; k < marker.dot_count; ++k) {
      if (&marker == reference) {
        const int cell = marker.cells[k];
        const int slot = cell == kCellO ? 0 : cell == kCellX ? 1 : cell == kCellY ? 2 : -1;
        if (slot >= 0) {
          dots.direction_dots[static_cast<std::size_t>(slot)] = dots.world.size();
          ++dots.direction_dots_found;
        }
      }
      dots.world.push_back(marker.world[k]);
      dots.pixels.push_back(marker.pixels[k]);
    }
  }
}

// Every used marker's dots, P3P starts from the reference marker's O, X, Y.
PoseFit fit_used_markers(std::span<const MarkerObservation> markers, const MarkerObservation& reference,
                         const CameraModel& camera, const RigidTransform& base_from_camera,
                         const RefinementOptions& options) {
  UsedDots dots;
  collect_used_dots(markers, &reference, dots);
  const std::optional<PointTriple> triple =
      dots.direction_dots_found == 3 ? std::optional(dots.direction_dots) : std::nullopt;
  return estimate_pose({dots.world.begin(), dots.world.size()}, {dots.pixels.begin(), dots.pixels.size()}, camera,
                       base_from_camera, options, triple);
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

// The used marker that fits the pose worst, when its RMS is above the gate (else -1); used: how
// many markers are used.
int worst_marker(std::span<const MarkerObservation> markers, const CameraModel& camera,
                 const RigidTransform& base_from_camera, const RigidTransform& world_from_base, double gate_px,
                 int& used) {
  int worst = -1;
  double worst_rms = gate_px;
  used = 0;
  for (std::size_t k = 0; k < markers.size(); ++k) {
    if (!markers[k].used) continue;
    ++used;
    const double rms = marker_rms(markers[k], camera, base_from_camera, world_from_base);
    if (rms > worst_rms) {
      worst_rms = rms;
      worst = static_cast<int>(k);
    }
  }
  return worst;
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
    int used = 0;
    const int worst = worst_marker(markers, camera, base_from_camera, fit.world_from_base, options.marker_gate_px, used);
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

DotPoseResult refit_dot_pose(std::span<MarkerObservation> markers, const CameraModel& camera,
                             const RigidTransform& base_from_camera, const DotPoseOptions& options,
                             const DotPoseResult& last, const RigidTransform& start) {
  const bool every_marker_used =
      std::all_of(markers.begin(), markers.end(), [](const MarkerObservation& marker) { return marker.used; });
  if (!last.fit.ok || !every_marker_used) return solve_dot_pose(markers, camera, base_from_camera, options);
  UsedDots dots;
  collect_used_dots(markers, nullptr, dots);
  DotPoseResult result;
  result.fit = refine_pose({dots.world.begin(), dots.world.size()}, {dots.pixels.begin(), dots.pixels.size()}, camera,
                           base_from_camera, start, options.refinement);
  if (!result.fit.ok || worst_marker(markers, camera, base_from_camera, result.fit.world_from_base,
                                     options.marker_gate_px, result.markers_used) >= 0) {
    return solve_dot_pose(markers, camera, base_from_camera, options);
  }
  result.reference_marker = last.reference_marker;
  return result;
}

}  // namespace irloc::dot
