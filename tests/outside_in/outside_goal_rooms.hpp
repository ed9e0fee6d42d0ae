#pragma once
// The family of rooms of the outside-in goal (bench_outside_goal, docs/outside_in.md "Goal
// benchmark"), drawn from a seed: a 640 x 480 wall camera 2-3.5 m up, pitched 20-60 degrees down,
// f 420-560 px; one 0.5 m floor tile in the middle of the view as the floor reference, its corners
// clicked to 0.3 px; a box robot 0.4-0.7 m long, dark, light grey with a dark front strip, mid grey
// or white (draw_look), that appears in view and drives at 0.47 m/s between random floor points,
// turning in place toward each; per class a stop, half turn and reverse, a person, or lamp steps
// and a bright sun patch. A second generator (variation_generator) draws what varies beyond that,
// each room's first draws staying as they were: the lens (pinhole, barrel distortion or a
// fisheye), 10, 15 or 30 fps, a drive that leaves the view and comes back on another side, and a
// floor reference of up to 4 x 4 tiles. Tests replay single rooms of it.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
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

constexpr double kSpeed = 0.47;                               // m/s
constexpr double kTurnRate = 60 * std::numbers::pi / 180;    // rad/s, turning toward the next point
constexpr double kMaxRange = 6.0;          // m from the camera's foot: the goal's robots
constexpr double kEmptySeconds = 1;        // the background starts on the empty floor
constexpr double kMaxSeconds = 22;          // of a drive that stays in view
constexpr double kLongestExit = 6;          // m: the way out of the view and back in, at most

enum class RoomClass { drive, stop_turn_reverse, person, light };

// What the second generator draws; its defaults are the rooms without it.
struct RoomVariation {
  LensModel lens = LensModel::plumb_bob;
  std::array<double, 5> distortion{};
  double focal_scale = 1;   // of the room's drawn f: a fisheye's is shorter
  double fps = 10;
  bool exits = false;       // the drive leaves the view and comes back on another side
  int reference_columns = 1, reference_rows = 1;  // tiles of the floor reference's rectangle
  bool every_tile_corner = false;                 // the rectangle's tile corners clicked, not only its 4
  int frames_out_of_view = 0;                     // of the drawn drive: the robot wholly outside the image
  std::string describe() const;
};

struct Room {
  RoomVariation variation;
  double fps = 10;
  WallCamera camera;
  BoxBody body;
  FloorReference reference;
  std::vector<SceneState> frames;
  sim::RobotLook look;
  std::string look_name = "dark";  // its kind, for the benchmark's lines
};

// Appends the frames of a drive from `from` to `to`: a turn in place toward it, then straight on.
inline void drive(std::vector<SceneState>& frames, double fps, FloorPose& pose, const Eigen::Vector2d& to, bool backwards = false) {
  const Eigen::Vector2d from(pose.x, pose.y);
  const Eigen::Vector2d step = to - from;
  double heading = std::atan2(step.y(), step.x());
  if (backwards) heading = std::remainder(heading + std::numbers::pi, 2 * std::numbers::pi);
  const double turn = std::remainder(heading - pose.yaw, 2 * std::numbers::pi);
  const int turn_frames = static_cast<int>(std::ceil(std::abs(turn) / (kTurnRate / fps)));
  const double start_yaw = pose.yaw;
  for (int i = 1; i <= turn_frames; ++i) {
    pose.yaw = start_yaw + turn * i / turn_frames;
    frames.emplace_back().robot = pose;
  }
  const int drive_frames = static_cast<int>(std::ceil(step.norm() / (kSpeed / fps)));
  for (int i = 1; i <= drive_frames; ++i) {
    const Eigen::Vector2d at = from + step * i / drive_frames;
    pose.x = at.x();
    pose.y = at.y();
    frames.emplace_back().robot = pose;
  }
}

inline void hold(std::vector<SceneState>& frames, double fps, FloorPose& pose, double seconds, double turn = 0) {
  const int count = static_cast<int>(seconds * fps);
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

inline RoomVariation draw_variation(std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0, 1);
  RoomVariation variation;
  const double lens = unit(rng);
  if (lens < 0.5) {  // barrel distortion as a webcam's; k2 = k1^2 keeps the radial map increasing
    const double k1 = -0.05 - 0.25 * unit(rng);
    variation.distortion = {k1, k1 * k1, 0, 0, 0};
  } else if (lens < 0.75) {  // a fisheye: 54-73 degrees from the axis to the image's side
    variation.lens = LensModel::equidistant;
    variation.focal_scale = 0.6;
    variation.distortion = {-0.03 + 0.06 * unit(rng), 0, 0, 0, 0};
  }
  const std::array<double, 3> rates{10, 15, 30};
  variation.fps = rates[std::min<std::size_t>(2, static_cast<std::size_t>(3 * unit(rng)))];
  variation.exits = unit(rng) < 0.5;
  variation.reference_columns = 1 + std::min(3, static_cast<int>(4 * unit(rng)));
  variation.reference_rows = 1 + std::min(3, static_cast<int>(4 * unit(rng)));
  variation.every_tile_corner = unit(rng) < 0.5;
  return variation;
}

inline std::string RoomVariation::describe() const {
  char text[200];
  std::snprintf(text, sizeof text, "%s k1 %.3f, %.0f fps, %s (%d frames out of view), reference %dx%d tiles (%s)",
                lens == LensModel::equidistant ? "fisheye" : distortion[0] != 0 ? "barrel" : "pinhole", distortion[0], fps,
                exits ? "exits" : "stays in view", frames_out_of_view, reference_columns, reference_rows,
                every_tile_corner ? "every corner" : "4 corners");
  return text;
}

// No corner of the box, standing anywhere around `at`, in the image (with a 10 px margin).
inline bool out_of_view(const WallProjection& camera, const BoxBody& body, const Eigen::Vector2d& at) {
  const double reach = 0.5 * std::hypot(body.length, body.width);
  for (int k = 0; k < 16; ++k)
    for (double z : {0.0, body.height}) {
      const double angle = k * std::numbers::pi / 8;
      const Eigen::Vector2d px = camera.project({at.x() + reach * std::cos(angle), at.y() + reach * std::sin(angle), z});
      if (px.allFinite() && px.x() > -10 && px.y() > -10 && px.x() < camera.intrinsics().width + 10 &&
          px.y() < camera.intrinsics().height + 10)
        return false;
    }
  return true;
}

// The first floor point out of view on the way from `from` (in view) toward one side of the image
// (0 left, 1 right, 2 near: the floor seen on that edge in from's row or column) and on beyond it.
inline std::optional<Eigen::Vector2d> way_out(const WallProjection& camera, const BoxBody& body, const Eigen::Vector2d& from, int side) {
  const Eigen::Vector2d pixel = camera.project({from.x(), from.y(), 0});
  const double w = camera.intrinsics().width, h = camera.intrinsics().height;
  const std::optional<Eigen::Vector2d> toward =
      side == 2 ? camera.floor_at(pixel.x(), h - 1) : camera.floor_at(side == 0 ? 0 : w - 1, pixel.y());
  if (!toward || (*toward - from).norm() < 1e-6) return std::nullopt;
  const Eigen::Vector2d step = 0.05 * (*toward - from).normalized();
  Eigen::Vector2d point = from;
  for (int k = 0; k < 200; ++k, point += step)
    if (out_of_view(camera, body, point)) return point;
  return std::nullopt;
}

// Where the robot leaves the view after `leave` and where it comes back to `back`: the nearest
// point out of view toward a side of the image (left, right, near) and toward another side, or
// none when the lens sees no floor there or the way out and back in is longer than kLongestExit.
inline std::vector<Eigen::Vector2d> exit_and_return(const WallProjection& camera, const BoxBody& body, const Eigen::Vector2d& leave,
                                                    const Eigen::Vector2d& back) {
  std::optional<Eigen::Vector2d> out, in;
  int exit = -1;
  for (int side = 0; side < 3; ++side) {
    const auto point = way_out(camera, body, leave, side);
    if (point && (!out || (*point - leave).norm() < (*out - leave).norm())) {
      out = point;
      exit = side;
    }
  }
  for (int side = 0; side < 3; ++side) {
    const auto point = way_out(camera, body, back, side);
    if (side != exit && point && (!in || (*point - back).norm() < (*in - back).norm())) in = point;
  }
  if (!out || !in || (*out - leave).norm() + (back - *in).norm() > kLongestExit) return {};
  return {*out, *in};
}

// The floor reference: the rectangle of tiles under the view's middle (shrunk until it is in the
// image), its corners or every tile corner on it, clicked to 0.3 px. The first four clicks come from
// `rng` as for one tile, any more from `variation_rng`. The rectangle's tiles, once shrunk, are
// left in variation.
inline FloorReference draw_reference(const WallProjection& camera, const Eigen::Vector2d& middle, RoomVariation& variation,
                                     std::mt19937& rng, std::mt19937& variation_rng) {
  std::normal_distribution<double> click(0, 0.3);
  std::array<Eigen::Vector2d, 4> first_clicks;
  for (Eigen::Vector2d& noise : first_clicks) noise = Eigen::Vector2d(click(rng), click(rng));
  const double t = sim::kFloorTile;
  const double x0 = std::floor(middle.x() / t) * t, y0 = std::floor(middle.y() / t) * t;
  int columns = variation.reference_columns, rows = variation.reference_rows;
  const auto in_image = [&](double x, double y) {
    const Eigen::Vector2d px = camera.project({x, y, 0});
    return px.allFinite() && px.x() >= 5 && px.y() >= 5 && px.x() <= camera.intrinsics().width - 6 &&
           px.y() <= camera.intrinsics().height - 6;
  };
  const auto fits = [&] {
    return in_image(x0, y0) && in_image(x0 + columns * t, y0) && in_image(x0 + columns * t, y0 + rows * t) &&
           in_image(x0, y0 + rows * t);
  };
  while ((columns > 1 || rows > 1) && !fits()) {
    columns = std::max(1, columns - 1);
    rows = std::max(1, rows - 1);
  }
  variation.reference_columns = columns;
  variation.reference_rows = rows;
  std::vector<Eigen::Vector2d> corners{{x0, y0}, {x0 + columns * t, y0}, {x0 + columns * t, y0 + rows * t}, {x0, y0 + rows * t}};
  if (variation.every_tile_corner)
    for (int i = 0; i <= columns; ++i)
      for (int j = 0; j <= rows; ++j)
        if (i % columns != 0 || j % rows != 0) corners.emplace_back(x0 + i * t, y0 + j * t);
  FloorReference reference;
  std::normal_distribution<double> more_clicks(0, 0.3);
  for (std::size_t k = 0; k < corners.size(); ++k) {
    const Eigen::Vector2d noise =
        k < 4 ? first_clicks[k] : Eigen::Vector2d(more_clicks(variation_rng), more_clicks(variation_rng));
    reference.world.push_back(corners[k]);
    reference.pixels.push_back(camera.project({corners[k].x(), corners[k].y(), 0}) + noise);
  }
  reference.pixel_sigma = 0.3;
  return reference;
}

// A room of the class. Without variation_rng, the robot is dark, the lens a distortion-free
// pinhole, 10 fps, the drive stays in view and the reference is one tile.
inline Room draw_room(RoomClass room_class, std::mt19937& rng, std::mt19937* variation_rng = nullptr) {
  std::uniform_real_distribution<double> unit(0, 1);
  Room room;
  if (variation_rng) draw_look(rng, room);
  if (variation_rng) room.variation = draw_variation(*variation_rng);
  const RoomVariation& variation = room.variation;
  const double fps = room.fps = variation.fps;
  const double f = (420 + 140 * unit(rng)) * variation.focal_scale;
  room.camera.intrinsics = CameraIntrinsics{640, 480, f, f, 319.5, 239.5, variation.lens, variation.distortion};
  room.camera.height = 2 + 1.5 * unit(rng);
  room.camera.pitch_deg = 20 + 40 * unit(rng);
  room.body.length = 0.4 + 0.3 * unit(rng);
  room.body.width = room.body.length * (0.55 + 0.3 * unit(rng));
  room.body.height = 0.2 + 0.2 * unit(rng);
  const WallProjection view(room.camera);

  const Eigen::Vector2d middle = *view.floor_at(320, 300);
  std::mt19937 no_variation;  // the one-tile reference draws nothing from it
  room.reference = draw_reference(view, middle, room.variation, rng, variation_rng ? *variation_rng : no_variation);

  // Waypoints: floor points in the inner image, within the goal's range, 1 m apart at least.
  std::vector<Eigen::Vector2d> points;
  for (int tries = 0; points.size() < 4 && tries < 1000; ++tries) {
    const auto point = view.floor_at(130 + 380 * unit(rng), 170 + 240 * unit(rng));
    if (!point || point->norm() > kMaxRange - 0.5) continue;
    bool apart = true;
    for (const Eigen::Vector2d& other : points) apart = apart && (other - *point).norm() >= 1.0;
    if (apart) points.push_back(*point);
  }
  const int empty_frames = static_cast<int>(std::lround(kEmptySeconds * fps));
  room.frames.resize(static_cast<std::size_t>(empty_frames));
  const Eigen::Vector2d first_leg = points[1] - points[0];
  FloorPose pose{points[0].x(), points[0].y(), std::atan2(first_leg.y(), first_leg.x())};
  room.frames.emplace_back().robot = pose;
  drive(room.frames, fps, pose, points[1]);
  // A drive that exits leaves the view after the first leg, is away 2 s and comes back on another
  // side to the second point (the stop and turn then follow there); beyond kMaxSeconds by the
  // time that takes.
  std::size_t next = 2;
  double seconds = kMaxSeconds;
  const std::vector<Eigen::Vector2d> exit = variation.exits && variation_rng
                                                ? exit_and_return(view, room.body, points[1], points[next])
                                                : std::vector<Eigen::Vector2d>{};
  room.variation.exits = !exit.empty();
  if (!exit.empty()) {
    const std::size_t before = room.frames.size();
    drive(room.frames, fps, pose, exit[0]);
    hold(room.frames, fps, pose, 1);
    const Eigen::Vector2d in = points[next] - exit[1];
    pose = FloorPose{exit[1].x(), exit[1].y(), std::atan2(in.y(), in.x())};
    hold(room.frames, fps, pose, 1);
    drive(room.frames, fps, pose, points[next++]);
    seconds += static_cast<double>(room.frames.size() - before) / fps;
  }
  if (room_class == RoomClass::stop_turn_reverse) {
    hold(room.frames, fps, pose, 3);
    hold(room.frames, fps, pose, 6, std::numbers::pi);  // a half turn in place in 6 s
    hold(room.frames, fps, pose, 3);
    drive(room.frames, fps, pose, Eigen::Vector2d(pose.x, pose.y) -
                                 0.6 * Eigen::Vector2d(std::cos(pose.yaw), std::sin(pose.yaw)), true);
  }
  for (std::size_t k = next; k < points.size(); ++k) drive(room.frames, fps, pose, points[k]);
  const auto max_frames = static_cast<std::size_t>(std::lround(seconds * fps));
  if (room.frames.size() > max_frames) room.frames.resize(max_frames);

  for (const SceneState& scene : room.frames)
    room.variation.frames_out_of_view += scene.robot && out_of_view(view, room.body, {scene.robot->x, scene.robot->y});
  const int count = static_cast<int>(room.frames.size());
  if (room_class == RoomClass::person) {
    // Walks across the middle of the robot's path at 1.2 m/s, from 4 s on.
    const SceneState& crossing = room.frames[std::min(count - 1, empty_frames + count / 3)];
    const Eigen::Vector2d centre = crossing.robot ? Eigen::Vector2d(crossing.robot->x, crossing.robot->y) : middle;
    const double angle = 2 * std::numbers::pi * unit(rng);
    const Eigen::Vector2d direction(std::cos(angle), std::sin(angle));
    const int first = static_cast<int>(std::lround(4 * fps));
    for (int i = first; i < count; ++i) {
      const Eigen::Vector2d at = centre + 0.5 * direction.unitOrthogonal() + (-3.0 + 0.12 * ((i - first) * (10 / fps))) * direction;
      room.frames[static_cast<std::size_t>(i)].person = Person{at};
    }
  }
  const double sun_angle = 2 * std::numbers::pi * unit(rng);
  for (int i = 0; i < count; ++i) {
    SceneState& scene = room.frames[static_cast<std::size_t>(i)];
    scene.sun = middle + Eigen::Vector2d(std::cos(sun_angle), std::sin(sun_angle)) * (1.5 - 0.01 * (i * (10 / fps)));  // 0.1 m/s
    scene.sun_strength = room_class == RoomClass::light ? 0.5 : 0.2;
    if (room_class == RoomClass::light) scene.lamp = i >= 2 * count / 3 ? 1.15 : i >= count / 3 ? 0.75 : 1.0;
  }
  return room;
}

// The generator of a class's rooms for a seed: its first draw_room is the class's scene 0.
inline std::mt19937 room_generator(int seed, RoomClass room_class) {
  return std::mt19937(static_cast<unsigned>(seed) * 16 + static_cast<unsigned>(room_class));
}

// The second generator of a class's rooms for the same seed (draw_room's variation_rng).
inline std::mt19937 variation_generator(int seed, RoomClass room_class) {
  std::seed_seq seeds{static_cast<unsigned>(seed), static_cast<unsigned>(room_class), 27u};
  return std::mt19937(seeds);
}

}  // namespace irloc::test::outside_goal
