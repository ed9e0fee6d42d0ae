#pragma once
// The floor reference of an outside-in set-up as an installer measures it: four tile corners on
// the floor and where the wall camera sees them, to 0.1 px (a careful click on a still frame).
#include <array>

#include <Eigen/Core>

#include "algo/markers/outside_in/floor_geometry.hpp"
#include "host_sim/render/wall_camera.hpp"

namespace irloc::sim {

inline outside_in::FloorReference measured_floor_reference(const WallCamera& camera, const std::array<Eigen::Vector2d, 4>& world) {
  outside_in::FloorReference reference;
  reference.world.assign(world.begin(), world.end());
  const WallProjection view(camera);
  for (const Eigen::Vector2d& point : world) {
    const Eigen::Vector2d pixel = view.project({point.x(), point.y(), 0});
    reference.pixels.push_back((pixel * 10).array().round() / 10);
  }
  return reference;
}

}  // namespace irloc::sim
