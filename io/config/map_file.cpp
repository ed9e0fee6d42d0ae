#include "io/config/map_file.hpp"

#include <cmath>
#include <numbers>
#include <array>
#include <cstdio>
#include <map>
#include <string>

#include "io/config/yaml_reader.hpp"

namespace irloc::io {
namespace {

// Ranges of docs/formats.md: a site within 10 km of the world origin; marker sizes that a
// ceiling camera can see.
constexpr Range kWorldCoordinate{-10'000, 10'000};
constexpr Range kAngle{-7, 7};
constexpr Range kDotPitch{0.005, 1};
constexpr Range kDotRadius{0.001, 0.5};
constexpr Range kTapeWidth{0.005, 1};
constexpr Range kDashOrGap{0.01, 10};
constexpr Range kDirection{-1'000, 1'000};
constexpr Range kSigma{0, 1'000};  // a survey's 1-sigma of a marker: metres or radians

DotMarker read_dot_marker(YamlMap& item) {
  DotMarker marker;
  marker.id = static_cast<int>(item.integer("id", 0, 4095));
  marker.origin = item.vector3("origin", kWorldCoordinate);
  marker.yaw = item.number("yaw", kAngle);
  marker.pitch = item.number("pitch", kDotPitch, marker.pitch);
  marker.radius = item.number("radius", kDotRadius, marker.radius);
  if (2 * marker.radius >= marker.pitch) item.fail_key("radius", "dots of this radius overlap at this pitch");
  marker.fixed = item.boolean("fixed", false);
  if (item.has("sigma")) {
    const std::vector<double> sigma = item.numbers("sigma", 4, kSigma);
    marker.sigma = Eigen::Vector4d(sigma[0], sigma[1], sigma[2], sigma[3]);
  }
  return marker;
}

SquareMarker read_square_marker(YamlMap& item) {
  SquareMarker marker;
  marker.name = item.text("name");
  const std::vector<std::vector<double>> corners = item.points("corners", 3, kWorldCoordinate);
  if (corners.size() != 4) item.fail_key("corners", "expected 4 corners [x, y, z], c0 -> c1 the solid side");
  for (std::size_t i = 0; i < 4; ++i) marker.corners[i] = {corners[i][0], corners[i][1], corners[i][2]};
  for (std::size_t i = 0; i < 4; ++i) {
    if ((marker.corners[i] - marker.corners[(i + 1) % 4]).norm() < 0.1) {
      item.fail_key("corners", "corners c" + std::to_string(i) + " and c" + std::to_string((i + 1) % 4) +
                                   " are less than 0.1 m apart");
    }
  }
  marker.tape_width = item.number("tape_width", kTapeWidth, marker.tape_width);
  marker.dash = item.number("dash", kDashOrGap, marker.dash);
  marker.gap = item.number("gap", kDashOrGap, marker.gap);
  return marker;
}

LedLandmark read_led_landmark(YamlMap& item) {
  LedLandmark landmark;
  landmark.name = item.text("name");
  landmark.position = item.vector3("position", kWorldCoordinate);
  if (item.has("direction")) {
    const Eigen::Vector3d direction = item.vector3("direction", kDirection);
    if (direction.norm() < 1e-9) item.fail_key("direction", "must not be the zero vector");
    landmark.direction = direction.normalized();
  }
  landmark.half_angle = item.optional_number("half_angle", {1e-3, std::numbers::pi});
  return landmark;
}

// One rule for every kind of landmark: a landmark given twice (a dot marker's ID, an LED's name or
// its position) would be two answers to one question; the second is refused, naming the first.
template <typename Marker, typename Identity, typename Describe>
void refuse_repeats(YamlMap& root, const std::string& key, const std::vector<Marker>& markers, Identity identity,
                    Describe describe) {
  std::map<decltype(identity(markers.front())), std::size_t> first;
  for (std::size_t i = 0; i < markers.size(); ++i) {
    const auto [seen, inserted] = first.emplace(identity(markers[i]), i);
    if (!inserted) {
      root.fail_key(key, describe(markers[i]) + " appears twice (" + key + "[" + std::to_string(seen->second) + "] and [" +
                             std::to_string(i) + "])");
    }
  }
}

std::string position_text(const Eigen::Vector3d& p) {
  char text[96];
  std::snprintf(text, sizeof text, "position [%g, %g, %g]", p.x(), p.y(), p.z());
  return text;
}

// Reads every item of a list with `read`, each strictly.
template <typename Marker>
std::vector<Marker> read_list(YamlMap& root, const std::string& key, Marker (*read)(YamlMap&)) {
  std::vector<Marker> result;
  root.for_each_item(key, [&](YamlMap& item) { result.push_back(read(item)); });
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

  refuse_repeats(root, "dot_markers", map.dot_markers, [](const DotMarker& m) { return m.id; },
                 [](const DotMarker& m) { return "id " + std::to_string(m.id); });
  refuse_repeats(root, "led_landmarks", map.led_landmarks, [](const LedLandmark& l) { return l.name; },
                 [](const LedLandmark& l) { return "name " + l.name; });
  refuse_repeats(root, "led_landmarks", map.led_landmarks,
                 [](const LedLandmark& l) { return std::array{l.position.x(), l.position.y(), l.position.z()}; },
                 [](const LedLandmark& l) { return position_text(l.position); });
  if (map.dot_markers.empty() && map.square_markers.empty() && map.led_landmarks.empty()) {
    root.fail("the map has no markers (expected dot_markers, square_markers or led_landmarks)");
  }
  return map;
}

}  // namespace irloc::io
