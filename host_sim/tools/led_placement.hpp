#pragma once
// The LED landmark paper's placement study (its Fig. 5), extended: for each floor cell, the
// expected 1-sigma horizontal position error of the LED source at the worst of `headings` robot
// headings, from the least-squares covariance of the LEDs the camera sees there (in the image,
// inside their emission cones) with `pixel_sigma` px of centre noise, under the scenario's
// robot.dof. Cells where some heading sees too few LEDs for the dof are NaN (grey: no pose).

#include "host_sim/plots/plots.hpp"
#include "host_sim/scenario/scenario.hpp"

namespace irloc::sim {

HeatMap led_position_error_map(const Scenario& scenario, double cell, int headings, double pixel_sigma);

}  // namespace irloc::sim
