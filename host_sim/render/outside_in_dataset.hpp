#pragma once
// Renders an outside-in scenario (`kind: outside_in`) to one frame dataset per wall camera, each
// what that camera's irlocd replays in `mode: outside_in`: 8-bit frames, truth.csv, calib.yaml,
// and config.yaml with the floor reference measured on the camera's tile corners. Every camera
// sees the same scene (robot, person, light) at the same instants.

#include <filesystem>
#include <vector>

#include "host_sim/render/dataset_render.hpp"
#include "host_sim/render/wall_camera.hpp"
#include "host_sim/scenario/scenario.hpp"

namespace irloc::sim {

// One frame's truth as the outside-in metrics need it: the pose, and how much of the robot shows.
struct OutsideInTruth {
  TruthRow pose;
  bool whole_in_view = false;   // every corner of the box inside the image
  double hidden_fraction = 0;   // of the box's pixels, the part behind a person
};

WallCamera wall_camera_of(const WallCameraSpec& camera);

// Writes dirs[i] (which must not hold files yet) for the scenario's camera i, one folder per
// camera (Scenario::outside_in must be set), and returns every frame's truth, by camera then frame.
std::vector<std::vector<OutsideInTruth>> render_outside_in_datasets(const Scenario& scenario,
                                                                    const std::vector<std::filesystem::path>& dirs,
                                                                    const Progress& progress = {});

}  // namespace irloc::sim
