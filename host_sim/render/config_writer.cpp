#include "host_sim/render/config_writer.hpp"

#include <cstdio>
#include <sstream>

#include "io/files/output_file.hpp"
#include "io/config/camera_info_writer.hpp"
#include "io/input_error.hpp"

namespace irloc::sim {
namespace {

std::string number(double value) { return io::yaml_number(value); }

std::string list(std::initializer_list<double> values) {
  std::string text = "[";
  for (const double value : values) text += (text.size() > 1 ? ", " : "") + number(value);
  return text + "]";
}

std::string vector3(const Eigen::Vector3d& v) { return list({v.x(), v.y(), v.z()}); }

// A YAML double-quoted string, so that any name reads back as itself.
std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

std::string map_yaml(const MarkerMap& map) {
  std::ostringstream out;
  out << "# Written by irloc-sim from the scenario's map.\n";
  if (!map.dot_markers.empty()) out << "dot_markers:\n";
  for (const DotMarker& m : map.dot_markers) {
    out << "  - id: " << m.id << "\n    origin: " << vector3(m.origin) << "\n    yaw: " << number(m.yaw)
        << "\n    pitch: " << number(m.pitch) << "\n    radius: " << number(m.radius) << "\n";
  }
  if (!map.square_markers.empty()) out << "square_markers:\n";
  for (const SquareMarker& m : map.square_markers) {
    out << "  - name: " << quoted(m.name) << "\n    corners: [" << vector3(m.corners[0]) << ", " << vector3(m.corners[1]) << ", "
        << vector3(m.corners[2]) << ", " << vector3(m.corners[3]) << "]\n    tape_width: " << number(m.tape_width)
        << "\n    dash: " << number(m.dash) << "\n    gap: " << number(m.gap) << "\n";
  }
  if (!map.led_landmarks.empty()) out << "led_landmarks:\n";
  for (const LedLandmark& m : map.led_landmarks) {
    out << "  - name: " << quoted(m.name) << "\n    position: " << vector3(m.position) << "\n";
    if (m.direction) out << "    direction: " << vector3(*m.direction) << "\n";
    if (m.half_angle) out << "    half_angle: " << number(*m.half_angle) << "\n";
  }
  return out.str();
}

}  // namespace

void write_replay_config(const std::filesystem::path& dir, const Scenario& scenario) {
  if (scenario.map.dot_markers.empty() && scenario.map.square_markers.empty() && scenario.map.led_landmarks.empty()) {
    throw io::InputError(scenario.name + ": map: the scenario has no markers, so irlocd cannot replay it");
  }
  io::replace_file_atomically(dir / "calib.yaml", io::camera_info_yaml(scenario.camera.intrinsics, "irloc_sim", "Written by irloc-sim from the scenario's camera."));
  io::replace_file_atomically(dir / "map.yaml", map_yaml(scenario.map));
  const Eigen::Matrix3d& r = scenario.camera.mount.linear();
  const Eigen::Vector3d& t = scenario.camera.mount.translation();
  io::replace_file_atomically(dir / "config.yaml",
             "# Written by irloc-sim: replay with\n#   irlocd --config config.yaml --camera dir:. --serial none\n"
             "camera:\n  calibration: calib.yaml\n  mount:\n    rotation: " +
                 list({r(0, 0), r(0, 1), r(0, 2), r(1, 0), r(1, 1), r(1, 2), r(2, 0), r(2, 1), r(2, 2)}) +
                 "\n    xyz: " + vector3(t) +
                 (scenario.camera.line_time_ns > 0 ? "\n  line_time_ns: " + std::to_string(scenario.camera.line_time_ns) : std::string()) +
                 // The camera's depth, for which the sources size their images (8 is the default).
                 (scenario.camera.bit_depth != 8 ? "\n  pixel_bits: " + std::to_string(scenario.camera.bit_depth) : std::string()) +
                 "\nrobot:\n  dof: " + std::to_string(static_cast<int>(scenario.dof)) +
                 (scenario.max_side_speed ? "\n  max_side_speed: " + number(*scenario.max_side_speed) : std::string()) +
                 "\nmap: map.yaml\n");
}

}  // namespace irloc::sim
