#include "hal/config/board_file.hpp"


#include "hal/config/yaml_reader.hpp"

namespace irloc::hal {
namespace {

std::filesystem::path relative_to(const std::filesystem::path& file, const std::string& value) {
  const std::filesystem::path path(value);
  return path.is_absolute() ? path : file.parent_path() / path;
}

long long integer_in(YamlMap& map, const std::string& key, long long low, long long high) {
  const long long value = map.integer(key);
  if (value < low || value > high) {
    map.fail_key(key, "must be in [" + std::to_string(low) + ", " + std::to_string(high) + "], got " + std::to_string(value));
  }
  return value;
}

double positive_number(YamlMap& map, const std::string& key) {
  const double value = map.number(key);
  if (value <= 0) map.fail_key(key, "must be positive");
  return value;
}

bool boolean(YamlMap& map, const std::string& key) {
  const std::string value = map.text(key);
  if (value == "true") return true;
  if (value == "false") return false;
  map.fail_key(key, "expected true or false, got '" + value + "'");
}

BoardCamera read_camera(YamlMap& camera, const std::filesystem::path& file) {
  BoardCamera result;
  const std::string driver = camera.text("driver");
  if (driver != "libcamera") camera.fail_key("driver", "unknown camera driver '" + driver + "' (expected libcamera)");
  if (camera.has("id")) {
    result.id = camera.text("id");
  } else {
    camera.ignore("id");
  }
  for (const YAML::Node& item : camera.items("formats")) {
    if (!item.IsScalar()) camera.fail(item, "formats", "expected a list of pixel format names");
    result.formats.push_back(item.Scalar());
  }
  if (result.formats.empty()) camera.fail_key("formats", "required: a list of pixel formats, best first");
  result.frame_duration_us = integer_in(camera, "frame_duration_us", 1000, 1'000'000);
  result.exposure_us = static_cast<std::int32_t>(integer_in(camera, "exposure_us", 1, 1'000'000));
  if (result.exposure_us > result.frame_duration_us) camera.fail_key("exposure_us", "longer than frame_duration_us");
  result.analogue_gain = positive_number(camera, "analogue_gain");
  if (camera.has("buffers")) {
    result.buffers = static_cast<unsigned int>(integer_in(camera, "buffers", 4, 32));
  } else {
    camera.ignore("buffers");
  }
  result.calibration = relative_to(file, camera.text("calibration"));
  camera.reject_unknown_keys();
  return result;
}

BoardStrobe read_strobe(YamlMap& strobe) {
  BoardStrobe result;
  result.chip = strobe.text("chip");
  result.line = static_cast<unsigned int>(integer_in(strobe, "line", 0, 1023));
  result.active_low = boolean(strobe, "active_low");
  result.latency_frames = static_cast<unsigned int>(integer_in(strobe, "latency_frames", 0, 4));
  result.noise_level = static_cast<int>(integer_in(strobe, "noise_level", 0, 65535));
  const double ratio = strobe.number("min_contrast_ratio");
  if (ratio < 1) strobe.fail_key("min_contrast_ratio", "must be at least 1");
  result.min_contrast_ratio = ratio;
  strobe.reject_unknown_keys();
  return result;
}

BoardSerial read_serial(YamlMap& serial) {
  BoardSerial result;
  result.device = serial.text("device");
  result.baud = static_cast<int>(integer_in(serial, "baud", 1200, 4'000'000));
  result.protocol = serial.text("protocol");
  if (result.protocol != "mavlink" && result.protocol != "stargazer") {
    serial.fail_key("protocol", "unknown protocol '" + result.protocol + "' (expected mavlink or stargazer)");
  }
  serial.reject_unknown_keys();
  return result;
}

BoardMavlink read_mavlink(YamlMap& mavlink) {
  BoardMavlink result;
  result.system_id = static_cast<int>(integer_in(mavlink, "system_id", 1, 255));
  result.component_id = static_cast<int>(integer_in(mavlink, "component_id", 1, 255));
  result.position_sigma_m = positive_number(mavlink, "position_sigma_m");
  result.angle_sigma_rad = positive_number(mavlink, "angle_sigma_rad");
  mavlink.reject_unknown_keys();
  return result;
}

}  // namespace

BoardConfig load_board(const std::filesystem::path& path) {
  YamlMap root(load_yaml_file(path), path.string(), "");
  BoardConfig board;
  board.name = root.text("name");
  board.description = root.text("description");
  YamlMap camera = root.map("camera");
  board.camera = read_camera(camera, path);
  if (root.has("strobe")) {
    YamlMap strobe = root.map("strobe");
    board.strobe = read_strobe(strobe);
  } else {
    root.ignore("strobe");
  }
  if (root.has("serial")) {
    YamlMap serial = root.map("serial");
    board.serial = read_serial(serial);
  } else {
    root.ignore("serial");
  }
  if (root.has("mavlink")) {
    YamlMap mavlink = root.map("mavlink");
    board.mavlink = read_mavlink(mavlink);
  } else {
    root.ignore("mavlink");
  }
  if (root.has("config")) {
    board.config = relative_to(path, root.text("config"));
  } else {
    root.ignore("config");
  }
  if (root.has("realtime_priority")) {
    board.realtime_priority = static_cast<int>(integer_in(root, "realtime_priority", 0, 99));
  } else {
    root.ignore("realtime_priority");
  }
  root.reject_unknown_keys();
  return board;
}

}  // namespace irloc::hal
