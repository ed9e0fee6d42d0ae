#pragma once
// Active LED landmarks as the optics image them: a point source blurred by the lens's point-spread
// function (a circular Gaussian of `landmark_emitters.psf_sigma` pixels), integrated exactly over
// each pixel's area (error functions), centred on CameraModel::project of the LED's position; the
// spot's total carries the LED's intensity toward the camera over the squared distance. The true
// centre of each spot is therefore the camera model's projection, to well under 0.01 px for
// sigma >= 0.5 px. Used instead of the ray-traced emitter spheres when psf_sigma > 0; LEDs are not
// occluded by people in this mode.

#include <functional>
#include <span>

#include <Eigen/Geometry>

#include "algo/geometry/camera_model.hpp"
#include "host_sim/scenario/scenario.hpp"

namespace irloc::sim {

// Adds weight x the spots of every LED landmark seen from camera pose t_w_c to `radiance`
// (width x height mean radiances, row-major, as Renderer::render fills it).
void add_landmark_spots(const Scenario& scenario, const CameraModel& camera, const Eigen::Isometry3d& t_w_c,
                        double weight, std::span<float> radiance);

// The same under a rolling shutter: t_w_c_at_row(row) is the camera pose when image row `row` is
// exposed, and each spot is drawn from the pose of the row its centre lands in (found by
// fixed-point iteration from row 0).
using CameraPoseAtRow = std::function<Eigen::Isometry3d(double row)>;
void add_landmark_spots(const Scenario& scenario, const CameraModel& camera, const CameraPoseAtRow& t_w_c_at_row,
                        double weight, std::span<float> radiance);

}  // namespace irloc::sim
