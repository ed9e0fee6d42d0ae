#include "algo/markers/led/level_two_point.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "algo/geometry/pose.hpp"

namespace irloc::led {

int solve_level_two_point(const std::array<Eigen::Vector3d, 2>& world, const std::array<Eigen::Vector3d, 2>& bearings,
                          const RigidTransform& base_from_camera, LevelPoseSolutions& solutions,
                          double max_vertex_angle) {
  solutions.clear();
  // Bearings in the (level) base frame: L_k = p + Rz(yaw) (t_B_C + s_k b_k).
  std::array<Eigen::Vector3d, 2> b = {base_from_camera.rotation * bearings[0].normalized(),
                                      base_from_camera.rotation * bearings[1].normalized()};
  const Eigen::Vector3d difference = world[1] - world[0];
  const double rise = difference.z();
  const double span = difference.head<2>().norm();
  // Solve for the range along the bearing with the smaller vertical component; the other range
  // follows linearly from the rise: s_far b_far.z = rise_sign (rise) + s_near b_near.z.
  const bool swapped = std::abs(b[0].z()) > std::abs(b[1].z());
  const Eigen::Vector3d& near = swapped ? b[1] : b[0];  // s_near unknown
  const Eigen::Vector3d& far = swapped ? b[0] : b[1];
  const double signed_rise = swapped ? -rise : rise;   // z(far point) - z(near point)
  if (std::abs(far.z()) < 1e-9) return 0;
  // Horizontal offset far - near = A + s_near B, of length span.
  const Eigen::Vector2d a = (signed_rise / far.z()) * far.head<2>();
  const Eigen::Vector2d bb = (near.z() / far.z()) * far.head<2>() - near.head<2>();
  const double qa = bb.squaredNorm(), qb = 2 * a.dot(bb), qc = a.squaredNorm() - span * span;
  if (qa < 1e-18) return 0;
  // A negative discriminant is no pose, or the two roots merged under noise (both points near the
  // camera's height, or seen nearly edge-on). The vertex is then the nearest pose; it is given when
  // it sees the second point within max_vertex_angle of its bearing.
  const double discriminant = qb * qb - 4 * qa * qc;
  const bool vertex = discriminant < 0;
  if (vertex && max_vertex_angle <= 0) return 0;
  const double root = vertex ? 0 : std::sqrt(discriminant);
  for (const double s_near : {(-qb - root) / (2 * qa), (-qb + root) / (2 * qa)}) {
    const double s_far = (signed_rise + s_near * near.z()) / far.z();
    if (s_near <= 0 || s_far <= 0) continue;
    const double s0 = swapped ? s_far : s_near, s1 = swapped ? s_near : s_far;
    const Eigen::Vector2d base_offset = (s1 * b[1] - s0 * b[0]).head<2>();
    if (base_offset.norm() < 1e-9 || span < 1e-9) continue;
    const double yaw = std::atan2(difference.y(), difference.x()) - std::atan2(base_offset.y(), base_offset.x());
    RigidTransform pose;
    pose.rotation = rotation_from_rpy(0, 0, wrap_angle(yaw));
    pose.translation = world[0] - pose.rotation * (base_from_camera.translation + s0 * b[0]);
    if (vertex) {
      const Eigen::Vector3d seen = ((pose * base_from_camera).inverse() * world[1]).normalized();
      if (std::acos(std::clamp(seen.dot(bearings[1].normalized()), -1.0, 1.0)) > max_vertex_angle) break;
    }
    solutions.push_back(pose);
    if (discriminant <= 0) break;
  }
  return static_cast<int>(solutions.size());
}

}  // namespace irloc::led
