#pragma once
// Where the map's markers appear in the image for a given robot pose: the ground truth behind
// the wrong-ID metric and the overlays of the debug frames.

#include <set>
#include <vector>

#include <Eigen/Geometry>

#include "algo/geometry/camera_model.hpp"
#include "algo/map/marker_map.hpp"
#include "host_sim/scenario/scenario.hpp"

namespace irloc::sim {

struct ProjectedPoint {
  Eigen::Vector2d pixel;
  bool visible = false;  // in front of the lens and on the sensor
};

// Pixels of world points seen by `camera` mounted at T_B_C on a robot at T_W_B.
std::vector<ProjectedPoint> project_points(const CameraModel& camera, const Eigen::Isometry3d& t_w_b,
                                           const Eigen::Isometry3d& t_b_c, const std::vector<Eigen::Vector3d>& points);

// IDs of the dot markers whose every dot is visible at this pose.
std::set<int> visible_dot_markers(const CameraModel& camera, const Eigen::Isometry3d& t_w_b,
                                  const Eigen::Isometry3d& t_b_c, const MarkerMap& map);

// Whether a square marker's whole tape is on the sensor at this pose: every point of the tape's
// outer outline, at most 5 cm apart, projects onto it (occlusion by people not considered).
bool square_wholly_in_view(const CameraModel& camera, const Eigen::Isometry3d& t_w_b, const Eigen::Isometry3d& t_b_c,
                           const SquareMarker& marker);

// The largest fraction of any side of `marker` that people at `positions` (people[i] at
// positions[i]) hide from the camera centre: the share of 100 points along the side's centre line
// whose straight line to the camera passes through a person.
double most_hidden_side_fraction(const Eigen::Vector3d& camera_centre, const SquareMarker& marker,
                                 const std::vector<Occluder>& people, const std::vector<Eigen::Vector2d>& positions);

// How many LED landmarks project onto the sensor at this pose with the camera inside their
// emission cone (occlusion and brightness not considered).
int visible_led_landmarks(const CameraModel& camera, const Eigen::Isometry3d& t_w_b, const Eigen::Isometry3d& t_b_c,
                          const MarkerMap& map);

}  // namespace irloc::sim
