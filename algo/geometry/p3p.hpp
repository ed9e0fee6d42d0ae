#pragma once
// Perspective-three-point: the camera poses that see three known world points along three
// given bearing vectors. A solver of the Lambda Twist class (Persson & Nordberg, ECCV 2018):
// the two distance-difference conics are intersected through a degenerate member of their
// pencil, found as a real root of a cubic, so there is no quartic to solve.
//
// Every real solution with all three points in front of the camera (positive depth along
// the bearing) is returned, at most 4. No heap.

#include <array>

#include <Eigen/Core>

#include "algo/core/static_vector.hpp"
#include "algo/geometry/rigid_transform.hpp"

namespace irloc {

// T_C_W candidates: p_C = rotation * p_W + translation.
using P3PSolutions = StaticVector<RigidTransform, 4>;

// world: three distinct points in W (metres). bearings: their directions in the camera frame
// (any length > 0; normalized inside). Clears solutions, then fills it; returns its size.
// Degenerate input (coincident or exactly collinear points, parallel bearings) yields 0.
int solve_p3p(const std::array<Eigen::Vector3d, 3>& world, const std::array<Eigen::Vector3d, 3>& bearings,
              P3PSolutions& solutions);

}  // namespace irloc
