#pragma once
// A simulation scenario: the camera, the robot's path, its IR LED ring, the room, the marker
// map, people, noise and timing (docs/simulator.md has the YAML reference). Plain data, read
// once at start-up by load_scenario / parse_scenario.

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "algo/geometry/camera_intrinsics.hpp"
#include "algo/geometry/pose.hpp"
#include "algo/map/marker_map.hpp"
#include "host_sim/render/outside_in_scene.hpp"

namespace irloc::sim {

// The sensor: calibration, timing and the radiometric response (docs/simulator.md).
struct CameraSpec {
  CameraIntrinsics intrinsics;
  std::filesystem::path calibration_file;  // calibration_file: the file it was read from; empty when inline
  Eigen::Isometry3d mount = Eigen::Isometry3d::Identity();  // T_B_C
  int bit_depth = 8;            // 8, 10 or 12
  double frame_rate = 30;       // frames per second
  double exposure = 0.002;      // seconds
  // Rolling shutter: row r exposed r * line_time_ns after row 0 (conventions.md); 0: global.
  std::int64_t line_time_ns = 0;
  double sensitivity = 6;       // full-scale fraction per (W sr^-1 m^-2 * s) of scene radiance
  double full_well = 10000;     // electrons at full scale (shot noise)
  double read_noise = 4;        // electrons rms
  double black_level = 0.02;    // fraction of full scale
  bool noise = true;            // shot and read noise on
};

// A kind of IR LED: on-axis radiant intensity and the half-intensity half-angle of its
// I(theta) = I0 cos^m(theta) beam.
struct LedType {
  std::string name;
  double intensity = 0.5;   // W/sr on the axis at the strobe current
  double half_angle = 0.35; // radians, where the intensity is I0 / 2
};

// One LED of the ring, in the camera frame C: its place and its beam axis.
struct RingLed {
  std::size_t type = 0;         // index into LedRing::types
  Eigen::Vector3d position;     // metres, camera frame
  Eigen::Vector3d axis;         // unit vector, camera frame
};

struct LedRing {
  std::vector<LedType> types;
  std::vector<RingLed> leds;
};

// The retro-reflective material of dots and tape: coefficient of retro-reflection as a
// function of the observation angle alpha and the entrance angle beta.
struct RetroReflector {
  double coefficient = 300;        // sr^-1 (radiance per irradiance) at alpha = beta = 0
  double observation_width = 0.03; // radians: R falls by e^-1 at this observation angle
  double entrance_limit = 1.3;     // radians: R falls to 0 at this entrance angle
};

struct Lamp {
  Eigen::Vector2d centre;   // on the ceiling, W x-y
  Eigen::Vector2d size;     // metres along W x and y (a rectangle); radius > 0 makes it a disc
  double radius = 0;
  double radiance = 50;     // W sr^-1 m^-2 in the camera's band
};

// A bright rectangle on a wall: its two opposite corners lie in the plane of one wall.
struct Window {
  Eigen::Vector3d corner_a, corner_b;
  double radiance = 5;
};

// A retro-reflective thing on the ceiling that is not a marker: a strip of safety tape on a duct
// or a piece of furniture (a rectangle), or a round sticker half in shadow, whose lit half is a
// half disc (a crescent). It shines in LED-on frames exactly as the tape does.
struct CeilingClutter {
  enum class Kind { strip, crescent } kind = Kind::strip;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  // on the ceiling, W x-y
  double yaw = 0;       // radians from W x toward y: the strip's length direction; the way the crescent's lit half faces
  double length = 0;    // strip, metres
  double width = 0;     // strip, metres
  double radius = 0;    // crescent, metres
};

struct Room {
  double ceiling_height = 2.6;               // z of the ceiling plane in W
  std::optional<Eigen::Vector4d> bounds;     // walls at x0, y0, x1, y1; none: open ceiling
  double ambient = 0.01;                     // irradiance of the room lights on ceiling and walls, W/m^2
  double ceiling_reflectance = 0.7;
  double wall_reflectance = 0.5;
  std::vector<Lamp> lamps;
  std::vector<Window> windows;
  std::vector<CeilingClutter> clutter;       // on the ceiling plane
};

// Physical side of the map's active LED landmarks.
struct LandmarkEmitters {
  double intensity = 0.05;  // W/sr on the axis
  double radius = 0.004;    // metres, size of the glowing emitter
  double psf_sigma = 0;     // pixels: > 0 images them as points blurred by this Gaussian (landmark_spots.hpp)
};

// A person or post: a vertical cylinder walking back and forth along a path.
struct Occluder {
  std::vector<Eigen::Vector2d> path;  // W x-y; one point: standing still
  double speed = 0.8;                 // m/s
  double radius = 0.25;
  double height = 1.8;
  double reflectance = 0.3;
};

enum class TrajectoryKind { static_pose, waypoints, loop, lawn_mower, spin };

struct TrajectorySpec {
  TrajectoryKind kind = TrajectoryKind::static_pose;
  // static_pose: [x, y, yaw]; spin: centre [x, y] with start yaw and rate.
  Eigen::Vector3d pose = Eigen::Vector3d::Zero();
  // waypoints: [x, y] each with the speed (m/s) to reach it from the one before.
  std::vector<Eigen::Vector2d> points;
  std::vector<double> speeds;
  bool closed = false;                       // waypoints: return to the first point and repeat
  double turn_rate = 1.5;                    // rad/s, turning in place at corners
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  // loop
  double radius = 1;                                 // loop
  double speed = 0.5;                                // loop, lawn_mower: m/s
  bool clockwise = false;                            // loop
  Eigen::Vector4d area = Eigen::Vector4d::Zero();    // lawn_mower: x0, y0, x1, y1
  double spacing = 0.5;                              // lawn_mower: lane spacing
  double rate = 0.5;                                 // spin: rad/s
  // Optional rocking on top of any path (a robot on an uneven floor, for dof 6): roll, pitch and
  // base height oscillate with these amplitudes (radians, metres) and period (seconds).
  double sway_roll = 0, sway_pitch = 0, sway_heave = 0, sway_period = 1;
};

struct MetricsSpec {
  double gross_position = 0.25;  // metres: an ok pose further off is a gross error
  double gross_yaw = 0.2;        // radians
  int warm_up_frames = 0;        // outside-in: frames the background learns before poses count
};

// A lamp switched at a frame: the scene's illumination factor from then on.
struct LightStep {
  int frame = 0;
  double lamp = 1;
};

// One wall camera of an outside-in scene: a pinhole `wall_height` above the floor at
// `wall_position`, looking along `yaw_deg` (from world +x toward +y), pitched down; its floor
// reference (four tile corners) and the MAVLink component ID its irlocd sends under.
struct WallCameraSpec {
  CameraIntrinsics intrinsics;
  std::filesystem::path calibration_file;                   // calibration_file: the file; empty when inline
  Eigen::Vector2d wall_position = Eigen::Vector2d::Zero();  // m, the camera's foot on the floor
  double wall_height = 2.4;                                 // m
  double pitch_deg = 38;                                    // down from horizontal
  double yaw_deg = 0;                                       // from world +x toward +y
  bool auto_exposure = true;
  double noise_sigma = 1.5;                                 // grey levels
  std::int64_t line_time_ns = 0;                            // rolling shutter: row r at t + r * line_time_ns
  std::array<Eigen::Vector2d, 4> floor_reference;           // tile corners, W x-y, in order round
  int component_id = 197;                                   // irlocd --component-id (197: its default)
};

// An outside-in scene (`kind: outside_in`, docs/outside_in.md): one camera (`camera:`) or several
// (`cameras:`) on the walls watching the box robot on a floor of 0.5 m tiles, people, light steps,
// a drifting sun patch. Every camera sees the same scene at the same instants
// (Scenario::camera.frame_rate; Scenario::camera.intrinsics are the first camera's).
struct OutsideInSpec {
  std::vector<WallCameraSpec> cameras;                      // at least one
  double body_length = 0.6, body_width = 0.4, body_height = 0.35;  // m
  RobotLook look;                                           // robot.look: the dark robot by default
  std::vector<LightStep> light_steps;                       // by frame
  Eigen::Vector2d sun_from{3.0, 1.2}, sun_to{3.0, 1.2};     // the sun patch drifts over the run
  double sun_strength = 0.5;                                // relative irradiance at its centre
};

struct Scenario {
  std::string name;             // the file name, for messages
  std::uint64_t seed = 1;
  int frames = 200;
  CameraSpec camera;
  Dof dof = Dof::planar3;
  // robot.max_side_speed, written to the replay config (docs/config.md): the trajectories never
  // drive the base origin sideways; empty: not written (a robot that may).
  std::optional<double> max_side_speed;
  TrajectorySpec trajectory;
  LedRing ring;
  RetroReflector retro;
  Room room;
  MarkerMap map;
  LandmarkEmitters landmark_emitters;
  std::vector<Occluder> people;
  std::vector<std::uint64_t> dropped_frames;  // sequence numbers left out
  double drop_probability = 0;                // each further frame dropped with this chance
  int pair_stride = 1;  // one LED-on/off pair (seq 2k, 2k + 1) in pair_stride kept: a drive sampled sparsely
  int motion_blur_samples = 1;                // time samples over the exposure; 1 = no blur
  int supersampling = 3;                      // rays per pixel along each axis
  MetricsSpec metrics;
  std::optional<OutsideInSpec> outside_in;    // kind: outside_in (then no ring, room or map)
};

// The files a scenario names (its cameras' calibration_file), which no output may replace.
std::vector<std::filesystem::path> referenced_files(const Scenario& scenario);

// Reads a scenario file. Relative file names inside it are relative to the file. Throws
// io::InputError "FILE:LINE: FIELD: problem" for the first problem, unknown keys included.
Scenario load_scenario(const std::filesystem::path& path);

// The same from YAML text; `name` stands for the file in messages, `base_dir` resolves
// relative file names.
Scenario parse_scenario(const std::string& yaml_text, const std::string& name,
                        const std::filesystem::path& base_dir = {});

}  // namespace irloc::sim
