#pragma once
// A drive under a grid of ceiling dot markers, observed by a camera whose true calibration is
// known: every dot of every marker fully in view, projected through the true calibration
// (algo/geometry/camera_model) with Gaussian pixel noise. The drive's starting poses are what
// the dot path would report with the calibration the robot believes: each frame's pose refined
// with that calibration (refine_pose).

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "algo/calibration/drive_observations.hpp"
#include "algo/geometry/camera_model.hpp"
#include "algo/geometry/pose.hpp"
#include "algo/geometry/pose_refinement.hpp"
#include "algo/map/marker_map.hpp"
#include "algo/markers/dot/dot_marker_layout.hpp"

namespace irloc::test {

inline constexpr double kCeilingZ = 2.6;
inline constexpr double kFramePeriod = 1.0 / 7.5;  // 7.5 pose attempts per second

// The `up` mount, 0.3 m above the base and 0.1 m forward of the axle.
inline RigidTransform true_mount() {
  RigidTransform mount;
  mount.rotation << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  mount.translation = Eigen::Vector3d(0.1, 0.02, 0.3);
  return mount;
}

// 640 x 480, about 63 deg x 50 deg, mild barrel distortion.
inline CameraIntrinsics true_camera() {
  CameraIntrinsics k;
  k.width = 640;
  k.height = 480;
  k.fx = 520;
  k.fy = 518;
  k.cx = 322.4;
  k.cy = 238.1;
  k.model = LensModel::plumb_bob;
  k.distortion = {-0.12, 0.05, 0, 0, 0};
  return k;
}

// Dot markers every 0.7 m over [-2, 3] x [-2, 3], yaws and IDs varied.
inline MarkerMap marker_grid() {
  MarkerMap map;
  int id = 17;
  for (double x = -2; x <= 3.01; x += 0.7) {
    for (double y = -2; y <= 3.01; y += 0.7) {
      DotMarker marker;
      marker.id = id;
      marker.origin = Eigen::Vector3d(x, y, kCeilingZ);
      marker.yaw = wrap_angle(0.37 * id);
      map.dot_markers.push_back(marker);
      id = (id * 37 + 11) % 4096;
    }
  }
  return map;
}

struct TimedPose {
  double t = 0;
  RigidTransform world_from_base;
};

inline RigidTransform planar_pose(double x, double y, double yaw) {
  return {rotation_from_rpy(0, 0, yaw), Eigen::Vector3d(x, y, 0)};
}

// A drive of a wheeled robot (no sideways motion): a 1 m radius circle at 0.3 m/s, a spin in
// place of half a turn, then 1.5 m straight ahead. With `turning` false: three straight legs
// along x, 0.4 m apart, a few seconds between them (the robot is carried back, no rotation).
inline std::vector<TimedPose> wheeled_drive(bool turning = true) {
  std::vector<TimedPose> drive;
  double t = 0;
  if (!turning) {
    for (int leg = 0; leg < 3; ++leg) {
      const double y = 0.4 * leg;
      for (double s = 0; s <= 2.0; s += 0.3 * kFramePeriod, t += kFramePeriod) drive.push_back({t, planar_pose(-0.5 + s, y, 0)});
      t += 5;
    }
    return drive;
  }
  const double radius = 1.0, speed = 0.3;
  const Eigen::Vector2d centre(0.5, 0.5);
  double phi = 0;
  for (; phi < 2 * std::numbers::pi; phi += speed / radius * kFramePeriod, t += kFramePeriod) {
    drive.push_back({t, planar_pose(centre.x() + radius * std::cos(phi), centre.y() + radius * std::sin(phi), phi + std::numbers::pi / 2)});
  }
  const Eigen::Vector2d spin_at(centre.x() + radius, centre.y());
  for (double yaw = std::numbers::pi / 2; yaw < 1.5 * std::numbers::pi; yaw += 0.6 * kFramePeriod, t += kFramePeriod) {
    drive.push_back({t, planar_pose(spin_at.x(), spin_at.y(), yaw)});
  }
  for (double s = 0; s < 1.5; s += speed * kFramePeriod, t += kFramePeriod) {
    drive.push_back({t, planar_pose(spin_at.x(), spin_at.y() - s, 1.5 * std::numbers::pi)});
  }
  return drive;
}

// A drive straight ahead along x at y = 0.3 m, without turning: `seconds` at `speed` from x = -2.
inline std::vector<TimedPose> straight_drive(double seconds, double speed) {
  std::vector<TimedPose> drive;
  for (double t = 0; t <= seconds; t += kFramePeriod) drive.push_back({t, planar_pose(-2 + speed * t, 0.3, 0)});
  return drive;
}

struct SyntheticDrive {
  calibration::DriveObservations observations;
  std::vector<RigidTransform> truth;  // per kept frame
};

// A dot's own systematic error, px: the same in every sighting (a detector's bias), drawn from
// N(0, sigma) per marker and cell.
inline Eigen::Vector2d dot_bias(int marker_id, int cell, double sigma) {
  std::mt19937 rng(static_cast<unsigned>(marker_id * 64 + cell + 1));
  std::normal_distribution<double> bias(0, sigma);
  const double u = bias(rng);
  return {u, bias(rng)};
}

// Observes the drive through the true calibration with pixel noise (and with each dot's own
// bias of `dot_bias_sigma`); starting poses from the believed calibration.
inline SyntheticDrive observe_drive(const std::vector<TimedPose>& drive, const MarkerMap& map,
                                    const CameraIntrinsics& camera, const RigidTransform& mount,
                                    const CameraIntrinsics& believed_camera, const RigidTransform& believed_mount,
                                    double pixel_sigma, unsigned seed, double dot_bias_sigma = 0) {
  SyntheticDrive result;
  const CameraModel truth_model(camera), believed_model(believed_camera);
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0, pixel_sigma);
  std::vector<PointObservation> dots;
  std::vector<Eigen::Vector3d> world;
  std::vector<Eigen::Vector2d> pixels;
  for (const TimedPose& timed : drive) {
    const RigidTransform camera_from_world = (timed.world_from_base * mount).inverse();
    dots.clear();
    for (const DotMarker& marker : map.dot_markers) {
      const dot::CellMask cells = dot::cells_from_id(marker.id);
      std::vector<PointObservation> marker_dots;
      bool whole = true;
      for (int cell = 0; cell < dot::kCellCount && whole; ++cell) {
        if (!((cells >> cell) & 1u)) continue;
        const Eigen::Vector3d point = dot::cell_in_world(marker, cell);
        Eigen::Vector2d pixel;
        whole = truth_model.project(camera_from_world * point, pixel) && truth_model.in_image(pixel);
        const Eigen::Vector2d error(noise(rng), noise(rng));
        marker_dots.push_back({marker.id, cell, pixel + error + dot_bias(marker.id, cell, dot_bias_sigma), point});
      }
      if (whole) dots.insert(dots.end(), marker_dots.begin(), marker_dots.end());
    }
    if (dots.size() < 8) continue;
    world.clear();
    pixels.clear();
    for (const PointObservation& dot : dots) {
      world.push_back(dot.world);
      pixels.push_back(dot.pixel);
    }
    RefinementOptions options;
    const PoseFit fit = refine_pose(world, pixels, believed_model, believed_mount, timed.world_from_base, options);
    if (!fit.ok) continue;
    result.observations.add(static_cast<std::int64_t>(std::llround(timed.t * 1e9)), fit.world_from_base, dots);
    result.truth.push_back(timed.world_from_base);
  }
  return result;
}

}  // namespace irloc::test
