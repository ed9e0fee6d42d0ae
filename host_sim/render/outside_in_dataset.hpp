#pragma once
// Renders an outside-in scenario (`kind: outside_in`) to a frame dataset irlocd replays in
// `mode: outside_in`: 8-bit frames of the wall camera, truth.csv, calib.yaml, and config.yaml
// with the floor reference measured on the scenario's tile corners.

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

// The wall camera of the scenario (Scenario::outside_in must be set).
WallCamera wall_camera_of(const Scenario& scenario);

// Writes DIR (which must not hold files yet) and returns every frame's truth.
std::vector<OutsideInTruth> render_outside_in_dataset(const Scenario& scenario, const std::filesystem::path& dir,
                                                      const Progress& progress = {});

}  // namespace irloc::sim
