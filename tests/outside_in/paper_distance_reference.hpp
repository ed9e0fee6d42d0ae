#pragma once
// The single-webcam paper's distance formulas (Li et al., Sensors 2014, docs/references.md), as
// reference implementations for the tests: IBDMS (eq. 18) and PLDMS (eqs. 19-22).
//
// Reading of eq. 18: an image row of a camera without roll images a floor line at one depth along
// the optical axis; a floor span of known width D_N across that row covers N pixels, so the depth
// is D_N * (N_Hmax / 2) * cot(theta_H / 2) / N, theta_H the full horizontal field of view and
// N_Hmax the image width (the pinhole focal length written with the webcam's data-sheet values),
// less the constant h_s. The paper's camera looks level, so depth is distance from the wall; for a
// camera pitched down, the floor distance follows from the depth, the height and the pitch.
// PLDMS: along the same row the floor maps to pixels affinely, so a point's offset from one of two
// parallel floor lines D_N apart is D_N * N_H(PR) / N_H(PQ) (eq. 22), P and Q where the lines
// cross the row (eqs. 19-21).
#include <cmath>

#include <Eigen/Core>

namespace irloc::test::paper {

// Eq. 18: the depth of the floor line imaged at a row (m).
inline double ibdms_depth(double span_m, double span_px, double image_width_px, double horizontal_fov_rad,
                          double camera_offset_m = 0) {
  return span_m / span_px * (image_width_px / 2) / std::tan(horizontal_fov_rad / 2) - camera_offset_m;
}

// Eqs. 19-20: the column where the image line through a and b crosses row v.
inline double column_at_row(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double v) {
  return a.x() + (v - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
}

// Eq. 22: the floor offset of a pixel from line P, on the row where P and Q are D_N apart (m).
inline double pldms_offset(double span_m, double p_column, double q_column, double column) {
  return span_m * (column - p_column) / (q_column - p_column);
}

// A wall camera pitched down by `pitch` at `height`: the floor distance in front of it from the
// depth of a floor point (its ray is at depth z: z = d cos(pitch) + height sin(pitch)).
inline double floor_distance_from_depth(double depth_m, double height_m, double pitch_rad) {
  return (depth_m - height_m * std::sin(pitch_rad)) / std::cos(pitch_rad);
}

}  // namespace irloc::test::paper
