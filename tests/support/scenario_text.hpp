#pragma once
// A small, clean test scenario as YAML text, with the parts tests vary given as arguments.

#include <string>

namespace irloc::test {

struct ScenarioText {
  std::string calibration =
      "    image_width: 48\n    image_height: 36\n"
      "    camera_matrix: {rows: 3, cols: 3, data: [40, 0, 23.5, 0, 40, 17.5, 0, 0, 1]}\n"
      "    distortion_model: plumb_bob\n"
      "    distortion_coefficients: {rows: 1, cols: 5, data: [0, 0, 0, 0, 0]}\n";
  std::string mount = "{preset: up, xyz: [0, 0, 0.3]}";
  std::string camera_timing;  // camera: lines such as frame_rate and exposure; empty: the defaults
  std::string trajectory = "  type: static\n  pose: [0, 0, 0.3]\n";
  std::string ring = "  types:\n    - {name: wide, intensity: 0.2, half_angle: 0.6}\n"
                     "  rings:\n    - {type: wide, count: 8, radius: 0.02, tilt: 0.2}\n";
  std::string room = "  ceiling_height: 1.3\n  ambient: 0\n  ceiling_reflectance: 0\n";
  std::string map = "  dot_markers:\n    - {id: 1782, origin: [-0.05, -0.06, 1.3], yaw: 0.4, radius: 0.012}\n";
  std::string extra = "render:\n  supersampling: 4\n";
  bool noise = false;
  int frames = 2;
  int seed = 3;

  std::string yaml() const {
    return "seed: " + std::to_string(seed) + "\nframes: " + std::to_string(frames) +
           "\ncamera:\n  calibration:\n" + calibration + "  mount: " + mount + "\n" + camera_timing +
           "  noise: " + (noise ? "true" : "false") +
           "\ntrajectory:\n" + trajectory + "led_ring:\n" + ring + "room:\n" + room + "map:\n" + map + extra;
  }
};

}  // namespace irloc::test
