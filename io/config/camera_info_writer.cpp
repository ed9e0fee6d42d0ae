#include "io/config/camera_info_writer.hpp"

#include <cstdio>
#include <sstream>

namespace irloc::io {

std::string yaml_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

std::string camera_info_yaml(const CameraIntrinsics& k, const std::string& camera_name, const std::string& comment) {
  std::ostringstream out;
  const char* model = k.model == LensModel::plumb_bob ? "plumb_bob" : k.model == LensModel::equidistant ? "equidistant" : "equisolid";
  const int coefficients = k.model == LensModel::plumb_bob ? 5 : k.model == LensModel::equidistant ? 4 : 0;
  if (!comment.empty()) out << "# " << comment << "\n";
  out << "image_width: " << k.width << "\nimage_height: " << k.height << "\ncamera_name: " << camera_name << "\n"
      << "camera_matrix:\n  rows: 3\n  cols: 3\n  data: [" << yaml_number(k.fx) << ", 0, " << yaml_number(k.cx) << ", 0, "
      << yaml_number(k.fy) << ", " << yaml_number(k.cy) << ", 0, 0, 1]\n"
      << "distortion_model: " << model << "\ndistortion_coefficients:\n  rows: 1\n  cols: " << coefficients << "\n  data: [";
  for (int i = 0; i < coefficients; ++i) out << (i ? ", " : "") << yaml_number(k.distortion[static_cast<std::size_t>(i)]);
  out << "]\n";
  return out.str();
}

}  // namespace irloc::io
