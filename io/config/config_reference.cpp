#include "io/config/config_reference.hpp"

#include <algorithm>
#include <span>

#include "algo/calibration/mount_tilt_watch.hpp"
#include "algo/markers/dot/dot_source_config.hpp"
#include "algo/markers/led/led_config.hpp"
#include "algo/markers/outside_in/outside_in_config.hpp"
#include "algo/markers/square/square_config.hpp"
#include "io/config/config_file.hpp"
#include "io/config/dot_config_file.hpp"
#include "io/config/led_config_file.hpp"
#include "io/config/mount_watch_config_file.hpp"
#include "io/config/outside_in_config_file.hpp"
#include "io/config/setting_table.hpp"
#include "io/config/square_config_file.hpp"

namespace irloc::io {
namespace {

// Comments start in this column, so that a reader scans the values down one edge.
constexpr std::size_t kCommentColumn = 36;

// Text accumulates line by line, each at its indent, optionally commented out ("# key: value").
class ConfigText {
 public:
  void line(int indent, const std::string& content, const std::string& comment = "", bool commented_out = false) {
    std::string text(static_cast<std::size_t>(2 * indent), ' ');
    if (commented_out) text += "# ";
    text += content;
    if (!comment.empty()) {
      text.resize(std::max(text.size() + 1, kCommentColumn), ' ');
      text += "# " + comment;
    }
    text_ += text + "\n";
  }
  void comment(const std::string& text) { text_ += "# " + text + "\n"; }
  void blank() { text_ += "\n"; }
  const std::string& text() const { return text_; }

 private:
  std::string text_;
};

template <typename Section>
void settings(ConfigText& out, int indent, std::span<const Setting<Section>> table, const Section& values,
              bool commented_out = false) {
  for (const Setting<Section>& setting : table) {
    out.line(indent, std::string(setting.key) + ": " + setting_value_text(setting, values), setting_comment(setting),
             commented_out);
  }
}

void camera_and_robot(ConfigText& out, const dot::DotSourceConfig& dot) {
  out.line(0, "mode: on_robot", "on_robot: the camera rides on the robot; outside_in: a fixed camera watches it");
  out.line(0, "camera:");
  out.line(1, "calibration: calib.yaml", "required: ROS camera_info, relative to this file");
  out.line(1, "mount:", "on_robot, required: T_B_C, by exactly one of preset and rotation");
  out.line(2, "preset: up", "optical axis along base +z, image top toward the robot's front");
  out.line(2, "xyz: [0, 0, 0.3]", "required: the camera in the base frame; each in [-10, 10] m");
  out.line(2, "rpy: [0, 0, 0]", "roll, pitch, yaw on the base side of the preset; each in [-7, 7] rad");
  out.line(2, "rotation: [0, -1, 0, 1, 0, 0, 0, 0, 1]", "instead of preset and rpy: R_B_C row-major", true);
  out.line(1, "line_time_ns: 0", "rolling shutter: row r exposed r * line_time_ns after row 0; 0: global; [0, 1000000] ns");
  settings(out, 1, camera_pixel_settings(), dot);
  out.line(1, "floor_reference:", "outside_in, required: known floor points and their pixels", true);
  out.line(2, "world: [[2.5, 1], [4.5, 1], [4.5, -1], [2.5, -1]]", "floor points (z = 0), 4 to 64; each in [-1000, 1000] m",
           true);
  out.line(2, "pixels: [[174.5, 290.6], [220, 152], [419, 152], [464.5, 290.6]]", "the same points' pixels, same order",
           true);
  outside_in::FloorReference reference;
  out.line(2, "pixel_sigma: " + number_text(reference.pixel_sigma), "how precisely the pixels were measured; [0.01, 20] px",
           true);
  out.line(0, "robot:");
  out.line(1, "dof: 3", "required: 3 (x, y, yaw), 4 (and z) or 6 (the full pose); outside_in: 3");
  static const MotionLimits limits;
  settings(out, 1, robot_motion_settings(), limits);
  out.line(1, "max_side_speed: 0.05",
           "fastest sideways drive of the base origin (wheels that do not slide: their slip); absent: max_speed; "
           "[0.01, max_speed] m/s",
           true);
  out.line(1, "body:", "outside_in, required: the watched robot's box; B at the centre of its footprint", true);
  out.line(2, "length: 0.6", "along x; [0.05, 10] m", true);
  out.line(2, "width: 0.4", "along y; [0.05, 10] m", true);
  out.line(2, "height: 0.35", "[0.02, 5] m", true);
  out.line(0, "map: map.yaml", "required on_robot, optional outside_in: the marker map, relative to this file");
}

}  // namespace

std::string reference_config_yaml() {
  // The defaults, each the struct's own. Static: read through a member pointer it does not know,
  // GCC 12 takes a local's padding for an uninitialized member (-Wmaybe-uninitialized).
  static const dot::DotSourceConfig dot;
  static const square::SquareConfig square;
  static const led::LedSourceConfig led;
  static const calibration::MountWatchConfig mount_watch;
  static const outside_in::OutsideInConfig outside_in;
  ConfigText out;
  out.comment("irloc config, every key at its default (irlocd --print-config; docs/config.md).");
  out.comment("Keys marked required must be given; any other key may be left out for its default.");
  out.comment("Lines of a key commented out are alternatives, or keys of mode outside_in.");
  out.blank();
  camera_and_robot(out, dot);
  out.blank();
  out.line(0, "front_end:", "the strobe difference's blobs, every source's; these and camera.pixel_bits were keys of dot:");
  settings(out, 1, front_end_settings(), dot);
  out.blank();
  out.line(0, "dot:", "the dot-marker source (docs/dot_markers.md)");
  settings(out, 1, dot_settings(), dot);
  out.line(1, "grey_levels:", "the grey-level model of a dot's evidence (irloc-sim fit-confidence)");
  out.line(2, "dot:", "genuine dots");
  settings(out, 3, grey_level_settings(), dot.grey_levels.dot);
  out.line(2, "clutter:", "noise, glints, lamp edges");
  settings(out, 3, grey_level_settings(), dot.grey_levels.clutter);
  out.blank();
  out.line(0, "square:", "the square tape marker source (docs/square_markers.md)");
  settings(out, 1, square_settings(), square);
  out.blank();
  out.line(0, "led:", "the LED landmark source (docs/led_landmarks.md)");
  settings(out, 1, led_settings(), led);
  out.blank();
  out.line(0, "mount_watch:", "on_robot: the online watch of the mount's tilt (docs/calibration.md)");
  settings(out, 1, mount_watch_settings(), mount_watch);
  out.blank();
  out.line(0, "mavlink:", "optional: what the MAVLink stream sends besides the pose (docs/hardware.md)", true);
  out.line(1, "pose_message: vision_position_estimate", "or odometry: the pose with the track's velocity", true);
  out.line(1, "ekf_origin:", "the EKF origin of an autopilot without GPS; all three required", true);
  out.line(2, "latitude_deg: 47.3977419", "WGS84; [-90, 90] deg", true);
  out.line(2, "longitude_deg: 8.5455938", "WGS84; [-180, 180] deg", true);
  out.line(2, "altitude_m: 488", "above mean sea level; [-1000, 10000] m", true);
  out.blank();
  out.line(0, "outside_in:", "outside_in only: the source's thresholds (docs/outside_in.md)", true);
  settings(out, 1, outside_in_settings(), outside_in, true);
  return out.text();
}

}  // namespace irloc::io
