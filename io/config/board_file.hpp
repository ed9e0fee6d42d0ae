#pragma once
// Reads a board file (boards/NAME.yaml, docs/hardware.md): which camera, lens calibration, strobe
// line and serial port a robot's computer has. Data only; irlocd turns it into devices.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace irloc::io {

struct BoardCamera {
  std::string id;                     // libcamera camera ID; empty: the first camera
  std::vector<std::string> formats;   // pixel formats, best first
  std::int64_t frame_duration_us = 0;
  std::int32_t exposure_us = 0;
  double analogue_gain = 1;
  unsigned int buffers = 6;
  std::filesystem::path calibration;  // the lens's nominal calibration (ROS camera_info)
  // The sensor mode's rolling shutter, row r exposed r * line_time_ns after row 0 (0: global
  // shutter); used when libcamera reports none and the robot config sets none.
  std::int64_t line_time_ns = 0;
};

struct BoardStrobe {
  std::string chip;
  unsigned int line = 0;
  bool active_low = false;
  unsigned int latency_frames = 1;
  int noise_level = 12;
  double min_contrast_ratio = 3;
};

struct BoardSerial {
  std::string device;
  int baud = 115200;
  std::string protocol = "mavlink";  // mavlink | stargazer
};

struct BoardMavlink {
  int system_id = 1;
  int component_id = 197;
  double position_sigma_m = 0.02;
  double angle_sigma_rad = 0.02;
};

struct BoardConfig {
  std::string name;
  std::string description;
  BoardCamera camera;
  std::optional<BoardStrobe> strobe;  // absent: LEDs not switched (always lit or none)
  std::optional<BoardSerial> serial;  // absent: no pose stream unless --serial gives one
  BoardMavlink mavlink;
  std::optional<std::filesystem::path> config;  // default robot config when --config is not given
  int realtime_priority = 0;                     // SCHED_FIFO priority, 0 = normal scheduling
};

// Strict: a missing required key, a wrong value or an unknown key throws InputError
// "FILE:LINE: FIELD: problem". Relative paths are relative to the board file's folder.
BoardConfig load_board(const std::filesystem::path& path);

}  // namespace irloc::io
