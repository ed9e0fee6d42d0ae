#pragma once
// Reads a camera calibration: a ROS camera_info YAML file (docs/formats.md), or the YAML file
// OpenCV's calibration tools write (cv::FileStorage: "%YAML:1.0", !!opencv-matrix camera_matrix
// and distortion_coefficients; plumb_bob, or equidistant when fisheye_model: 1).

#include <filesystem>

#include "algo/geometry/camera_intrinsics.hpp"
#include "io/config/yaml_reader.hpp"

namespace irloc::io {

// Throws InputError naming the file, line and field of the first problem.
CameraIntrinsics load_camera_info(const std::filesystem::path& path);
// The same from a mapping inside another YAML file (the simulator's scenarios).
CameraIntrinsics read_camera_info(YamlMap& root);

}  // namespace irloc::io
