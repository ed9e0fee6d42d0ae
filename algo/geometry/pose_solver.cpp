#include "algo/geometry/pose_solver.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "algo/core/static_vector.hpp"
#include "algo/geometry/p3p.hpp"
#include "algo/geometry/planar_fit.hpp"

namespace irloc {
namespace {

// true when every point lies on one horizontal plane (within 1 mm); its height in ceiling_z.
bool on_horizontal_plane(std::span<const Eigen::Vector3d> points, double& ceiling_z) {
  double low = points[0].z(), high = points[0].z();
  for (const Eigen::Vector3d& p : points) {
    low = std::min(low, p.z());
    high = std::max(high, p.z());
  }
  ceiling_z = 0.5 * (low + high);
  return high - low <= 1e-3;
}

// A well-spread triple: the first point, the point farthest from it, and the point farthest
// from the line through those two.
PointTriple spread_triple(std::span<const Eigen::Vector3d> points) {
  PointTriple triple = {0, 1, 2};
  double best = -1;
  for (std::size_t i = 1; i < points.size(); ++i) {
    const double d = (points[i] - points[0]).squaredNorm();
    if (d > best) best = d, triple[1] = i;
  }
  const Eigen::Vector3d axis = points[triple[1]] - points[0];
  best = -1;
  for (std::size_t i = 1; i < points.size(); ++i) {
    if (i == triple[1]) continue;
    const double area = axis.cross(points[i] - points[0]).squaredNorm();
    if (area > best) best = area, triple[2] = i;
  }
  return triple;
}

// Angle between the base z axis and W's z axis.
double tilt(const RigidTransform& world_from_base) {
  return std::acos(std::clamp(world_from_base.rotation(2, 2), -1.0, 1.0));
}

}  // namespace

PoseFit estimate_pose(std::span<const Eigen::Vector3d> world_points, std::span<const Eigen::Vector2d> pixels,
                      const CameraModel& camera, const RigidTransform& base_from_camera,
                      const RefinementOptions& options, std::optional<PointTriple> p3p_triple) {
  StaticVector<PoseFit, 5> fits;
  if (world_points.size() != pixels.size() || world_points.size() < 2) return {};

  double ceiling_z = 0;
  if (on_horizontal_plane(world_points, ceiling_z)) {
    const std::size_t count = std::min(world_points.size(), kMaxCeilingPoints);
    StaticVector<Eigen::Vector3d, kMaxCeilingPoints> bearings;
    for (std::size_t i = 0; i < count; ++i) {
      Eigen::Vector3d bearing;
      if (camera.unproject(pixels[i], bearing)) bearings.push_back(bearing);
    }
    RigidTransform initial;
    if (bearings.size() == count &&
        level_pose_from_ceiling(world_points.first(count), {bearings.begin(), bearings.end()}, ceiling_z,
                                base_from_camera, options.dof == Dof::planar3 ? Dof::planar3 : Dof::height4,
                                initial)) {
      // Under dof 6 this level start leads to the minimum nearest level.
      fits.push_back(refine_pose(world_points, pixels, camera, base_from_camera, initial, options));
    }
  }
  if (world_points.size() >= 3) {
    const PointTriple triple = p3p_triple.value_or(spread_triple(world_points));
    std::array<Eigen::Vector3d, 3> world, bearings;
    bool all_valid = true;
    for (int k = 0; k < 3; ++k) {
      world[k] = world_points[triple[k]];
      all_valid = all_valid && camera.unproject(pixels[triple[k]], bearings[k]);
    }
    P3PSolutions solutions;
    if (all_valid) solve_p3p(world, bearings, solutions);
    const RigidTransform camera_from_base = base_from_camera.inverse();
    for (const RigidTransform& camera_from_world : solutions) {
      const RigidTransform world_from_base = camera_from_world.inverse() * camera_from_base;
      fits.push_back(refine_pose(world_points, pixels, camera, base_from_camera, world_from_base, options));
    }
  }

  // -2 log posterior up to a constant: the pixels' likelihood and, under dof 6, the level prior.
  auto score = [&](const PoseFit& fit) {
    const double pixels_term = fit.cost / (options.pixel_sigma * options.pixel_sigma);
    if (options.dof != Dof::full6) return pixels_term;
    const double tilt_term = tilt(fit.world_from_base) / options.level_prior_sigma;
    return pixels_term + tilt_term * tilt_term;
  };
  const PoseFit* best = nullptr;
  for (const PoseFit& fit : fits) {
    if (fit.ok && (!best || score(fit) < score(*best))) best = &fit;
  }
  if (!best) return {};
  return *best;
}

}  // namespace irloc
