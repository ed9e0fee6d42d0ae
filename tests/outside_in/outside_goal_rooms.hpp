#pragma once
// The family of rooms of the outside-in goal (bench_outside_goal, docs/outside_in.md "Goal
// benchmark"), drawn from a seed: a 640 x 480 wall camera 2-3.5 m up, pitched 20-60 degrees down,
// f 420-560 px; one 0.5 m floor tile in the middle of the view as the floor reference, its corners
// clicked to 0.3 px; a box robot 0.4-0.7 m long, dark, light grey with a dark front strip, mid grey
// or white (draw_look), that appears in view and drives at 0.47 m/s between random floor points,
// turning in place toward each; per class a stop, half turn and reverse, a person, or lamp steps
// and a bright sun patch. Tests replay single rooms of it.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "tests/outside_in/outside_in_drive.hpp"

namespace irloc::test::outside_goal {

using outside_in::BoxBody;
using outside_in::FloorPose;
using outside_in::FloorReference;

constexpr double kFps = 10;
constexpr double kSpeed = 0.47;                               // m/s
constexpr double kTurnRate = 60 * std::numbers::pi / 180;    // rad/s, turning toward the next point
constexpr double kMaxRange = 6.0;          // m from the camera's foot: the goal's robots
constexpr int kEmptyFrames = 10;           // the background starts on the empty floor
constexpr int kMaxFrames = 220;

enum class RoomClass { drive, stop_turn_reverse, person, light };

struct Room {
  WallCamera camera;
  BoxBody body;
  FloorReference reference;
  std::vector<SceneState> frames;
  sim::RobotLook look;
  std::string look_name;  // its kind, for the benchmark's lines
};

// The floor point seen at a pixel of a pinhole wall camera, if the ray meets the floor.
inline std::optional<Eigen::Vector2d> floor_at(const WallCamera& camera, double u, double v) {
  const RigidTransform world_from_camera = camera.world_from_camera();
  const auto& k = camera.intrinsics;
  const Eigen::Vector3d ray = world_from_camera.rotation * Eigen::Vector3d((u - k.cx) / k.fx, (v - k.cy) / k.fy, 1);
  if (ray.z() >= -1e-6) return std::nullopt;
  return (world_from_camera.translation - world_from_camera.translation.z() / ray.z() * ray).head<2>();
}

// Appends the frames of a drive from `from` to `to`: a turn in place toward it, then straight on.
inline void drive(std::vector<SceneState>& frames, FloorPose& pose, const Eigen::Vector2d& to, bool backwards = false) {
  const Eigen::Vector2d from(pose.x, pose.y);
  const Eigen::Vector2d step = to - from;
  double heading = std::atan2(step.y(), step.x());
  if (backwards) heading = std::remainder(heading + std::numbers::pi, 2 * std::numbers::pi);
  const double turn = std::remainder(heading - pose.yaw, 2 * std::numbers::pi);
  const int turn_frames = static_cast<int>(std::ceil(std::abs(turn) / (kTurnRate / kFps)));
  const double start_yaw = pose.yaw;
  for (int i = 1; i <= turn_frames; ++i) {
    pose.yaw = start_yaw + turn * i / turn_frames;
    frames.emplace_back().robot = pose;
  }
  const int drive_frames = static_cast<int>(std::ceil(step.norm() / (kSpeed / kFps)));
  for (int i = 1; i <= drive_frames; ++i) {
    const Eigen::Vector2d at = from + step * i / drive_frames;
    pose.x = at.x();
    pose.y = at.y();
    frames.emplace_back().robot = pose;
  }
}

inline void hold(std::vector<SceneState>& frames, FloorPose& pose, double seconds, double turn = 0) {
  const int count = static_cast<int>(seconds * kFps);
  const double start_yaw = pose.yaw;
  for (int i = 1; i <= count; ++i) {
    pose.yaw = start_yaw + turn * i / count;
    frames.emplace_back().robot = pose;
  }
}

// The robot's look, one of four kinds: the dark robot; a light grey one brighter than the floor
// with a dark strip along the lower part of its front; a mid grey one between the tiles' shades;
// a white one. The side faces get less of the lamp than the top. From its own generator, seeded
// from the room's (taken by value: the room's own is not advanced, so its geometry and drive are
// drawn as they would be without looks).
inline void draw_look(std::mt19937 room_rng, Room& room) {
  std::seed_seq seeds{static_cast<unsigned>(room_rng()), 0x6c6f6f6bu};  // "look": a stream apart
  std::mt19937 rng(seeds);
  std::uniform_real_distribution<double> unit(0, 1);
  const int kind = std::uniform_int_distribution<int>(0, 3)(rng);
  if (kind == 0) {
    room.look = {};
    room.look_name = "dark";
    return;
  }
  const double top = kind == 1 ? 195 + 20 * unit(rng) : kind == 2 ? 150 + 25 * unit(rng) : 235 + 20 * unit(rng);
  const double side_light = 0.6 + 0.35 * unit(rng);
  room.look = {top, side_light * top, (side_light - 0.1) * top, (side_light - 0.05) * top};
  room.look_name = kind == 2 ? "mid grey" : "white";
  if (kind == 1) {
    room.look.strip_shade = 35 + 25 * unit(rng);
    room.look.strip_to = 0.25 + 0.2 * unit(rng);
    room.look_name = "light grey, dark front strip";
  }
}

inline Room draw_room(RoomClass room_class, std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0, 1);
  Room room;
  draw_look(rng, room);
  const double f = 420 + 140 * unit(rng);
  room.camera.intrinsics = CameraIntrinsics{640, 480, f, f, 319.5, 239.5, LensModel::plumb_bob, {}};
  room.camera.height = 2 + 1.5 * unit(rng);
  room.camera.pitch_deg = 20 + 40 * unit(rng);
  room.body.length = 0.4 + 0.3 * unit(rng);
  room.body.width = room.body.length * (0.55 + 0.3 * unit(rng));
  room.body.height = 0.2 + 0.2 * unit(rng);

  // The reference: the tile under the view's middle, clicked to 0.3 px.
  std::normal_distribution<double> click(0, 0.3);
  const Eigen::Vector2d middle = *floor_at(room.camera, 320, 300);
  const double x0 = std::floor(middle.x() / sim::kFloorTile) * sim::kFloorTile;
  const double y0 = std::floor(middle.y() / sim::kFloorTile) * sim::kFloorTile;
  const double t = sim::kFloorTile;
  for (const Eigen::Vector2d& corner : {Eigen::Vector2d(x0, y0), Eigen::Vector2d(x0 + t, y0), Eigen::Vector2d(x0 + t, y0 + t),
                                       Eigen::Vector2d(x0, y0 + t)}) {
    room.reference.world.push_back(corner);
    room.reference.pixels.push_back(room.camera.project({corner.x(), corner.y(), 0}) + Eigen::Vector2d(click(rng), click(rng)));
  }
  room.reference.pixel_sigma = 0.3;

  // Waypoints: floor points in the inner image, within the goal's range, 1 m apart at least.
  std::vector<Eigen::Vector2d> points;
  for (int tries = 0; points.size() < 4 && tries < 1000; ++tries) {
    const auto point = floor_at(room.camera, 130 + 380 * unit(rng), 170 + 240 * unit(rng));
    if (!point || point->norm() > kMaxRange - 0.5) continue;
    bool apart = true;
    for (const Eigen::Vector2d& other : points) apart = apart && (other - *point).norm() >= 1.0;
    if (apart) points.push_back(*point);
  }
  room.frames.resize(kEmptyFrames);
  const Eigen::Vector2d first_leg = points[1] - points[0];
  FloorPose pose{points[0].x(), points[0].y(), std::atan2(first_leg.y(), first_leg.x())};
  room.frames.emplace_back().robot = pose;
  drive(room.frames, pose, points[1]);
  if (room_class == RoomClass::stop_turn_reverse) {
    hold(room.frames, pose, 3);
    hold(room.frames, pose, 6, std::numbers::pi);  // a half turn in place in 6 s
    hold(room.frames, pose, 3);
    drive(room.frames, pose, Eigen::Vector2d(pose.x, pose.y) -
                                 0.6 * Eigen::Vector2d(std::cos(pose.yaw), std::sin(pose.yaw)), true);
  }
  for (std::size_t k = 2; k < points.size(); ++k) drive(room.frames, pose, points[k]);
  if (room.frames.size() > kMaxFrames) room.frames.resize(kMaxFrames);

  const int count = static_cast<int>(room.frames.size());
  if (room_class == RoomClass::person) {
    // Walks across the middle of the robot's path at 1.2 m/s, from frame 40 on.
    const SceneState& crossing = room.frames[std::min(count - 1, kEmptyFrames + count / 3)];
    const Eigen::Vector2d centre = crossing.robot ? Eigen::Vector2d(crossing.robot->x, crossing.robot->y) : middle;
    const double angle = 2 * std::numbers::pi * unit(rng);
    const Eigen::Vector2d direction(std::cos(angle), std::sin(angle));
    for (int i = 40; i < count; ++i) {
      const Eigen::Vector2d at = centre + 0.5 * direction.unitOrthogonal() + (-3.0 + 0.12 * (i - 40)) * direction;
      room.frames[static_cast<std::size_t>(i)].person = Person{at};
    }
  }
  const double sun_angle = 2 * std::numbers::pi * unit(rng);
  for (int i = 0; i < count; ++i) {
    SceneState& scene = room.frames[static_cast<std::size_t>(i)];
    scene.sun = middle + Eigen::Vector2d(std::cos(sun_angle), std::sin(sun_angle)) * (1.5 - 0.01 * i);
    scene.sun_strength = room_class == RoomClass::light ? 0.5 : 0.2;
    if (room_class == RoomClass::light) scene.lamp = i >= 2 * count / 3 ? 1.15 : i >= count / 3 ? 0.75 : 1.0;
  }
  return room;
}

// The generator of a class's rooms for a seed: its first draw_room is the class's scene 0.
inline std::mt19937 room_generator(int seed, RoomClass room_class) {
  return std::mt19937(static_cast<unsigned>(seed) * 16 + static_cast<unsigned>(room_class));
}

}  // namespace irloc::test::outside_goal
