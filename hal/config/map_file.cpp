#include "hal/config/map_file.hpp"

#include <cmath>
#include <numbers>
#include <set>

#include "hal/config/yaml_reader.hpp"

namespace irloc::hal {
namespace {

Eigen::Vector3d vector3(YamlMap& map, const std::string& key) {
  const std::vector<double> v = map.numbers(key, 3);
  return {v[0], v[1], v[2]};
}

double positive(YamlMap& map, const std::string& key, double default_value) {
  const double value = map.optional_number(key).value_or(default_value);
  if (!(value > 0)) map.fail_key(key, "must be positive");
  return value;
}

std::string item_field(const std::string& list, std::size_t index) {
  return list + "[" + std::to_string(index) + "]";
}

DotMarker read_dot_marker(YamlMap& item) {
  DotMarker marker;
  const long long id = item.integer("id");
  if (id < 0 || id > 4095) item.fail_key("id", "must be 0..4095, got " + std::to_string(id));
  marker.id = static_cast<int>(id);
  marker.origin = vector3(item, "origin");
  marker.yaw = item.number("yaw");
  marker.pitch = positive(item, "pitch", marker.pitch);
  marker.radius = positive(item, "radius", marker.radius);
  if (2 * marker.radius >= marker.pitch) item.fail_key("radius", "dots of this radius overlap at this pitch");
  if (item.has("fixed")) {
    const std::string fixed = item.text("fixed");
    if (fixed != "true" && fixed != "false") item.fail_key("fixed", "expected true or false, got '" + fixed + "'");
    marker.fixed = fixed == "true";
  }
  if (item.has("sigma")) {
    const std::vector<double> sigma = item.numbers("sigma", 4);
    for (const double value : sigma) {
      if (!(value >= 0)) item.fail_key("sigma", "expected [sx, sy, sz, syaw], each >= 0");
    }
    marker.sigma = Eigen::Vector4d(sigma[0], sigma[1], sigma[2], sigma[3]);
  }
  return marker;
}

SquareMarker read_square_marker(YamlMap& item) {
  SquareMarker marker;
  marker.name = item.text("name");
  const std::vector<YAML::Node> corners = item.items("corners");
  if (corners.size() != 4) item.fail_key("corners", "expected 4 corners [x, y, z], c0 -> c1 the solid side");
  for (std::size_t i = 0; i < 4; ++i) {
    if (!corners[i].IsSequence() || corners[i].size() != 3) item.fail(corners[i], "corners", "expected [x, y, z]");
    for (std::size_t axis = 0; axis < 3; ++axis) {
      marker.corners[i][static_cast<Eigen::Index>(axis)] = as_number(item, corners[i][axis], "corners");
    }
  }
  for (std::size_t i = 0; i < 4; ++i) {
    if ((marker.corners[i] - marker.corners[(i + 1) % 4]).norm() < 0.1) {
      item.fail_key("corners", "corners c" + std::to_string(i) + " and c" + std::to_string((i + 1) % 4) +
                                   " are less than 0.1 m apart");
    }
  }
  marker.tape_width = positive(item, "tape_width", marker.tape_width);
  marker.dash = positive(item, "dash", marker.dash);
  marker.gap = positive(item, "gap", marker.gap);
  return marker;
}

LedLandmark read_led_landmark(YamlMap& item) {
  LedLandmark landmark;
  landmark.name = item.text("name");
  landmark.position = vector3(item, "position");
  if (item.has("direction")) {
    const Eigen::Vector3d direction = vector3(item, "direction");
    if (direction.norm() < 1e-9) item.fail_key("direction", "must not be the zero vector");
    landmark.direction = direction.normalized();
  } else {
    item.ignore("direction");
  }
  if (const std::optional<double> half_angle = item.optional_number("half_angle")) {
    if (!(*half_angle > 0 && *half_angle <= std::numbers::pi)) item.fail_key("half_angle", "must be in (0, pi] radians");
    landmark.half_angle = half_angle;
  }
  return landmark;
}

// Reads every item of a list with `read`, each strictly.
template <typename Read>
auto read_list(YamlMap& root, const std::string& key, Read read) {
  std::vector<decltype(read(std::declval<YamlMap&>()))> result;
  const std::vector<YAML::Node> items = root.items(key);
  for (std::size_t i = 0; i < items.size(); ++i) {
    YamlMap item(items[i], root.file(), item_field(root.field(key), i));
    result.push_back(read(item));
    item.reject_unknown_keys();
  }
  return result;
}

}  // namespace

MarkerMap load_marker_map(const std::filesystem::path& path) {
  YamlMap root(load_yaml_file(path), path.string(), "");
  return read_marker_map(root);
}

MarkerMap read_marker_map(YamlMap& root) {
  MarkerMap map;
  map.dot_markers = read_list(root, "dot_markers", read_dot_marker);
  map.square_markers = read_list(root, "square_markers", read_square_marker);
  map.led_landmarks = read_list(root, "led_landmarks", read_led_landmark);
  root.reject_unknown_keys();

  std::set<int> ids;
  for (std::size_t i = 0; i < map.dot_markers.size(); ++i) {
    if (!ids.insert(map.dot_markers[i].id).second) {
      root.fail_key("dot_markers", "id " + std::to_string(map.dot_markers[i].id) + " appears twice");
    }
  }
  if (map.dot_markers.empty() && map.square_markers.empty() && map.led_landmarks.empty()) {
    root.fail("the map has no markers (expected dot_markers, square_markers or led_landmarks)");
  }
  return map;
}

}  // namespace irloc::hal
