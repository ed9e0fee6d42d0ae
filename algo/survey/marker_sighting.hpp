#pragma once
// One marker seen in one frame: the robot's pose in the marker's level frame L (ceiling_pose.hpp),
// fitted to that marker's dots alone, with its covariance. The fits of different markers use
// disjoint pixels, so two markers' sightings in one frame are independent measurements.

#include <span>

#include "algo/geometry/camera_model.hpp"
#include "algo/geometry/pose.hpp"
#include "algo/geometry/rigid_transform.hpp"
#include "algo/markers/dot/dot_marker_layout.hpp"
#include "algo/source/source_result.hpp"
#include "algo/survey/ceiling_pose.hpp"
#include "algo/survey/survey_config.hpp"

namespace irloc::survey {

// Per cell (a column each), px.
using DotResiduals = Eigen::Matrix<double, 2, dot::kCellCount>;

struct MarkerSighting {
  int id = -1;
  CeilingPose base_in_marker = CeilingPose::Zero();       // T_L_B
  // For a pixel noise of 1 px; the estimator scales it by the noise it measures over many
  // sightings (one marker's few dots say too little about it).
  CeilingCovariance covariance = CeilingCovariance::Zero();
  double squared_residuals = 0;  // px^2, over 2 * dots - 4 degrees of freedom
  double redundancy = 0;
  // Each dot's reprojection residual at the fit, px, by its cell (cells: which are set): the
  // estimator compares them with the same dots' in the next sighting (the share of a dot's
  // centroid error that repeats).
  DotResiduals residuals = DotResiduals::Zero();
  dot::CellMask cells = 0;
};

// dots: the observations of one marker (same landmark, distinct cells). false when there are too
// few dots or the fit fails. The robot is taken as level (dof 3 or 4; docs/survey.md): its
// height relative to the marker is free.
bool fit_sighting(std::span<const PointObservation> dots, double pitch, const CameraModel& camera,
                  const RigidTransform& base_from_camera, const SurveyConfig& config, MarkerSighting& sighting);

}  // namespace irloc::survey
