#pragma once
// The robot of irlocd's tests on rendered drives, as a scenario (tests/support/scenario_text.hpp):
// a 640 x 480 camera with sensor noise, looking up from 0.3 m above a level robot's base, its
// 12-LED ring, under a 2.6 m ceiling, one ray per pixel. The tests give the lens's focal length
// and distortion coefficients and the frame rate, then the seed, frames, drive and markers.

#include <string>

#include "tests/support/scenario_text.hpp"

namespace irloc::test {

inline ScenarioText rendered_robot_scenario(int focal_px, const std::string& distortion_coefficients, int frame_rate) {
  const std::string focal = std::to_string(focal_px);
  ScenarioText text;
  text.calibration = "    image_width: 640\n    image_height: 480\n"
                     "    camera_matrix: {rows: 3, cols: 3, data: [" + focal + ", 0, 319.5, 0, " + focal +
                     ", 239.5, 0, 0, 1]}\n"
                     "    distortion_model: plumb_bob\n"
                     "    distortion_coefficients: {rows: 1, cols: 5, data: " + distortion_coefficients + "}\n";
  text.mount = "{preset: up, xyz: [0.05, 0, 0.3]}";
  text.camera_timing = "  frame_rate: " + std::to_string(frame_rate) + "\n  exposure: 0.002\n";
  text.noise = true;
  text.ring = "  types:\n    - {name: ir850_wide, intensity: 0.2, half_angle: 0.6}\n"
              "  rings:\n    - {type: ir850_wide, count: 12, radius: 0.025, tilt: 0.35}\n";
  text.room = "  ceiling_height: 2.6\n";
  text.extra = "robot:\n  dof: 3\nrender:\n  supersampling: 1\n";
  return text;
}

}  // namespace irloc::test
