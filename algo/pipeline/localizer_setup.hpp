#pragma once
// Everything the per-frame pipeline is set up with (the config file, docs/formats.md); fixed for
// the lifetime of a Localizer. One config struct per pose source.

#include <optional>

#include "algo/geometry/camera_intrinsics.hpp"
#include "algo/geometry/pose.hpp"
#include "algo/geometry/rigid_transform.hpp"
#include "algo/kernels/strobe_check.hpp"
#include "algo/map/marker_map.hpp"
#include "algo/markers/dot/dot_source_config.hpp"
#include "algo/markers/led/led_config.hpp"
#include "algo/markers/outside_in/outside_in_config.hpp"
#include "algo/markers/square/square_config.hpp"
#include "algo/pipeline/pose_fusion.hpp"
#include "algo/source/source_input.hpp"

namespace irloc {

struct LocalizerSetup {
  CameraIntrinsics camera;
  RigidTransform mount;  // T_B_C
  // The config's camera.line_time_ns: row r of a frame is exposed r * line_time_ns after its top
  // row (conventions.md); 0: a global shutter. A frame's own report (Frame::line_time_ns) wins.
  std::int64_t line_time_ns = 0;
  Dof dof = Dof::planar3;
  MotionLimits robot_limits;  // robot.max_speed, robot.max_yaw_rate
  MarkerMap map;
  dot::DotSourceConfig dot;  // the dot marker source, made when the map has dot markers
  // The square tape marker source, made when the map has square markers.
  square::SquareConfig square;
  led::LedSourceConfig led;  // the LED landmark source, made when the map has LED landmarks
  // Outside-in mode (a fixed camera watching the robot): when set, the outside-in source is the
  // only source.
  std::optional<outside_in::OutsideInConfig> outside_in;
  FusionGate fusion;
  // The brightness check of every strobe pair (algo/kernels/strobe_check.hpp), counted in the
  // shared pass; irlocd sets it from the board's strobe settings.
  StrobeCheckSettings strobe_check;
};

}  // namespace irloc
