#pragma once
// The closed form of a level robot's pose (dof 3 and 4: x, y, z, yaw with roll = pitch = 0) from
// two known points seen along two bearings: the hypothesis generator of the LED search under
// those dofs (the paper's Table 3 case with two LEDs). The base's level frame fixes the vertical:
// the height difference of the points and their horizontal distance give the two ranges (a
// quadratic, at most two roots), then the yaw aligns the horizontal directions and the position
// follows. Degenerate when both bearings are horizontal (points at the camera's height): the
// ranges are then unobservable from two points. No heap.

#include <array>

#include <Eigen/Core>

#include "algo/core/static_vector.hpp"
#include "algo/geometry/rigid_transform.hpp"

namespace irloc::led {

// T_W_B candidates, level (roll = pitch = 0).
using LevelPoseSolutions = StaticVector<RigidTransform, 2>;

// world: the two points in W. bearings: their directions in the camera frame C (unit).
// base_from_camera: the mount T_B_C. Clears solutions, fills it; returns its size.
// max_vertex_angle (radians): where noise on the bearings leaves no exact solution, the nearest
// pose is given if it sees the second point within this angle of its bearing (0: never).
int solve_level_two_point(const std::array<Eigen::Vector3d, 2>& world, const std::array<Eigen::Vector3d, 2>& bearings,
                          const RigidTransform& base_from_camera, LevelPoseSolutions& solutions,
                          double max_vertex_angle = 0);

}  // namespace irloc::led
