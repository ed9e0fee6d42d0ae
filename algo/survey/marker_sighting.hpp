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

// How the fit's pose answers a pixel error that every dot carries with one covariance F (2 x 2,
// px^2, in the image's axes u, v), shared along an axis by dots at the same place across it (an
// image column shares its u error) and independent between dots apart: its covariance is
// F(0,0) along_u + F(1,1) along_v + F(0,1) coupling. A fixed error across the line of travel
// lies along one image axis.
struct PixelErrorResponse {
  CeilingCovariance along_u = CeilingCovariance::Zero();
  CeilingCovariance along_v = CeilingCovariance::Zero();
  CeilingCovariance coupling = CeilingCovariance::Zero();
  CeilingCovariance covariance(const Eigen::Matrix2d& pixel_error) const {
    return pixel_error(0, 0) * along_u + pixel_error(1, 1) * along_v + pixel_error(0, 1) * coupling;
  }
};

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
  PixelErrorResponse pixel_error_response;  // at the fitted pose, over the dots fitted
};

// dots: the observations of one marker (same landmark, distinct cells). false when there are too
// few dots or the fit fails. The robot is taken as level (dof 3 or 4; docs/survey.md): its
// height relative to the marker is free.
bool fit_sighting(std::span<const PointObservation> dots, double pitch, const CameraModel& camera,
                  const RigidTransform& base_from_camera, const SurveyConfig& config, MarkerSighting& sighting);

}  // namespace irloc::survey
