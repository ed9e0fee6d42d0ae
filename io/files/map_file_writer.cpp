#include "io/files/map_file_writer.hpp"

#include <charconv>

#include <yaml-cpp/yaml.h>

#include "io/files/output_file.hpp"

namespace irloc::io {
namespace {

// Shortest text that reads back as the same double (yaml-cpp's own formatting rounds).
std::string exact(double value) {
  char text[32];
  const std::to_chars_result result = std::to_chars(text, text + sizeof text, value);
  return {text, result.ptr};
}

template <typename Vector>
void emit_numbers(YAML::Emitter& out, const Vector& values) {
  out << YAML::Flow << YAML::BeginSeq;
  for (Eigen::Index i = 0; i < values.size(); ++i) out << exact(values[i]);
  out << YAML::EndSeq;
}

void emit_dot_marker(YAML::Emitter& out, const DotMarker& marker) {
  out << YAML::BeginMap;
  out << YAML::Key << "id" << YAML::Value << marker.id;
  out << YAML::Key << "origin" << YAML::Value;
  emit_numbers(out, marker.origin);
  out << YAML::Key << "yaw" << YAML::Value << exact(marker.yaw);
  out << YAML::Key << "pitch" << YAML::Value << exact(marker.pitch);
  out << YAML::Key << "radius" << YAML::Value << exact(marker.radius);
  if (marker.fixed) out << YAML::Key << "fixed" << YAML::Value << true;
  if (marker.sigma) {
    out << YAML::Key << "sigma" << YAML::Value;
    emit_numbers(out, *marker.sigma);
  }
  out << YAML::EndMap;
}

void emit_square_marker(YAML::Emitter& out, const SquareMarker& marker) {
  out << YAML::BeginMap;
  out << YAML::Key << "name" << YAML::Value << YAML::DoubleQuoted << marker.name;
  out << YAML::Key << "corners" << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (const Eigen::Vector3d& corner : marker.corners) emit_numbers(out, corner);
  out << YAML::EndSeq;
  out << YAML::Key << "tape_width" << YAML::Value << exact(marker.tape_width);
  out << YAML::Key << "dash" << YAML::Value << exact(marker.dash);
  out << YAML::Key << "gap" << YAML::Value << exact(marker.gap);
  out << YAML::EndMap;
}

void emit_led_landmark(YAML::Emitter& out, const LedLandmark& landmark) {
  out << YAML::BeginMap;
  out << YAML::Key << "name" << YAML::Value << YAML::DoubleQuoted << landmark.name;
  out << YAML::Key << "position" << YAML::Value;
  emit_numbers(out, landmark.position);
  if (landmark.direction) {
    out << YAML::Key << "direction" << YAML::Value;
    emit_numbers(out, *landmark.direction);
  }
  if (landmark.half_angle) out << YAML::Key << "half_angle" << YAML::Value << exact(*landmark.half_angle);
  out << YAML::EndMap;
}

template <typename Item, typename Emit>
void emit_list(YAML::Emitter& out, const char* key, const std::vector<Item>& items, Emit emit) {
  if (items.empty()) return;
  out << YAML::Key << key << YAML::Value << YAML::BeginSeq;
  for (const Item& item : items) emit(out, item);
  out << YAML::EndSeq;
}


}  // namespace

std::string marker_map_yaml(const MarkerMap& map) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  emit_list(out, "dot_markers", map.dot_markers, emit_dot_marker);
  emit_list(out, "square_markers", map.square_markers, emit_square_marker);
  emit_list(out, "led_landmarks", map.led_landmarks, emit_led_landmark);
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

void write_marker_map(const std::filesystem::path& path, const MarkerMap& map) {
  replace_file_atomically(path, marker_map_yaml(map), 0644, "the map");
}

}  // namespace irloc::io
