#pragma once
// Annotated debug frames of a run: the LED-on image with the map's markers projected from the
// true pose (green) and from the pipeline's estimate (red), and the pose attempt's status,
// marker ID, confidence and error.

#include <filesystem>

#include "algo/geometry/camera_model.hpp"
#include "algo/map/marker_map.hpp"
#include "algo/pipeline/pose_estimate.hpp"
#include "host_sim/render/dataset_render.hpp"

namespace irloc::sim {

// Writes `png` from the PGM frame `pgm`. Throws io::InputError for an unreadable frame.
void write_debug_frame(const std::filesystem::path& png, const std::filesystem::path& pgm, const CameraModel& camera,
                       const Eigen::Isometry3d& t_b_c, const MarkerMap& map, const TruthRow& truth,
                       const PoseEstimate& estimate);

}  // namespace irloc::sim
