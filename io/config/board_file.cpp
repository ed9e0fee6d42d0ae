#include "io/config/board_file.hpp"

#include "io/config/config_file.hpp"
#include "io/config/yaml_reader.hpp"
#include "hal/serial_bauds.hpp"

namespace irloc::io {
namespace {

BoardCamera read_camera(YamlMap& camera) {
  BoardCamera result;
  const std::string driver = camera.text("driver");
  if (driver != "libcamera") camera.fail_key("driver", "unknown camera driver '" + driver + "' (expected libcamera)");
  if (camera.has("id")) result.id = camera.text("id");
  for (const YAML::Node& item : camera.items("formats")) {
    if (!item.IsScalar()) camera.fail(item, "formats", "expected a list of pixel format names");
    result.formats.push_back(item.Scalar());
  }
  if (result.formats.empty()) camera.fail_key("formats", "required: a list of pixel formats, best first");
  result.frame_duration_us = camera.integer("frame_duration_us", 1000, 1'000'000);
  result.exposure_us = static_cast<std::int32_t>(camera.integer("exposure_us", 1, 1'000'000));
  if (result.exposure_us > result.frame_duration_us) camera.fail_key("exposure_us", "longer than frame_duration_us");
  result.analogue_gain = camera.number("analogue_gain", {1, 64});
  result.buffers = static_cast<unsigned int>(camera.integer("buffers", 4, 32, result.buffers));
  result.calibration = camera.path("calibration");
  result.line_time_ns = read_line_time(camera);
  camera.reject_unknown_keys();
  return result;
}

BoardStrobe read_strobe(YamlMap& strobe) {
  BoardStrobe result;
  result.chip = strobe.text("chip");
  result.line = static_cast<unsigned int>(strobe.integer("line", 0, 1023));
  result.active_low = strobe.boolean("active_low");
  result.latency_frames = static_cast<unsigned int>(strobe.integer("latency_frames", 0, 4));
  result.noise_level = static_cast<int>(strobe.integer("noise_level", 0, 65535));
  result.min_contrast_ratio = strobe.number("min_contrast_ratio", {1, 1000});
  strobe.reject_unknown_keys();
  return result;
}

BoardSerial read_serial(YamlMap& serial) {
  BoardSerial result;
  result.device = serial.text("device");
  result.baud = static_cast<int>(serial.integer("baud", 1200, 4'000'000));
  if (!hal::is_supported_baud(result.baud)) serial.fail_key("baud", hal::unsupported_baud_message(std::to_string(result.baud)));
  result.protocol = serial.text("protocol");
  if (result.protocol != "mavlink" && result.protocol != "stargazer") {
    serial.fail_key("protocol", "unknown protocol '" + result.protocol + "' (expected mavlink or stargazer)");
  }
  serial.reject_unknown_keys();
  return result;
}

BoardMavlink read_mavlink(YamlMap& mavlink) {
  BoardMavlink result;
  result.system_id = static_cast<int>(mavlink.integer("system_id", 1, 255));
  result.component_id = static_cast<int>(mavlink.integer("component_id", 1, 255));
  result.position_sigma_m = mavlink.number("position_sigma_m", {1e-6, 100});
  result.angle_sigma_rad = mavlink.number("angle_sigma_rad", {1e-6, 3.2});
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
  board.camera = read_camera(camera);
  if (std::optional<YamlMap> strobe = root.optional_map("strobe")) board.strobe = read_strobe(*strobe);
  if (std::optional<YamlMap> serial = root.optional_map("serial")) board.serial = read_serial(*serial);
  if (std::optional<YamlMap> mavlink = root.optional_map("mavlink")) board.mavlink = read_mavlink(*mavlink);
  if (root.has("config")) board.config = root.path("config");
  board.realtime_priority = static_cast<int>(root.integer("realtime_priority", 0, 99, board.realtime_priority));
  root.reject_unknown_keys();
  return board;
}

}  // namespace irloc::io
