#pragma once
// Writes a camera calibration as a ROS camera_info YAML (docs/formats.md), the file
// load_camera_info reads back to the same numbers.

#include <string>

#include "algo/geometry/camera_intrinsics.hpp"

namespace irloc::io {

// The YAML text; `comment` (one line, may be empty) goes first as a YAML comment.
std::string camera_info_yaml(const CameraIntrinsics& intrinsics, const std::string& camera_name,
                             const std::string& comment);

// Shortest text that reads back to the same double.
std::string yaml_number(double value);

}  // namespace irloc::io
