#pragma once
// Reads the files a run compares: truth.csv of a rendered dataset and the pose CSV irlocd
// writes (docs/formats.md). Strict: a malformed row throws io::InputError "FILE:LINE: problem".

#include <filesystem>
#include <vector>

#include "algo/pipeline/pose_estimate.hpp"
#include "host_sim/render/dataset_render.hpp"

namespace irloc::sim {

std::vector<TruthRow> read_truth_csv(const std::filesystem::path& path);
std::vector<PoseEstimate> read_pose_csv(const std::filesystem::path& path);

}  // namespace irloc::sim
