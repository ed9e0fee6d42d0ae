#pragma once
// irlocd's tests' rendered drive: a loop of 0.4 m radius at 0.5 m/s under three dot markers,
// 640 x 480 (rendered_robot_scenario.hpp): a pose at every LED-on frame.

#include "tests/firmware/rendered_robot_scenario.hpp"

namespace irloc::test {

inline ScenarioText loop_drive_scenario(int frames, int seed, int frame_rate = 30) {
  ScenarioText text = rendered_robot_scenario(380, "[-0.05, 0.01, 0, 0, 0]", frame_rate);
  text.seed = seed;
  text.frames = frames;
  text.trajectory = "  type: loop\n  centre: [0, 0]\n  radius: 0.4\n  speed: 0.5\n";
  text.room += "  bounds: [-3, -3, 3, 3]\n";
  text.map = "  dot_markers:\n"
             "    - {id: 1782, origin: [0.3, 0.4, 2.6], yaw: 0.0}\n"
             "    - {id: 421, origin: [-0.5, -0.3, 2.6], yaw: 1.2}\n"
             "    - {id: 3003, origin: [0.5, -0.45, 2.6], yaw: -2.0}\n";
  return text;
}

}  // namespace irloc::test
