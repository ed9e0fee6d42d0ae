#pragma once
// A test scene for the LED source, imaged by the simulator (host_sim's LED spots and Sensor):
// a forward-looking 640 x 480 camera on a robot, always-on LEDs on a wall ahead imaged as
// point-spread spots, and the truth (the robot's pose, every LED's projection by the camera model).
// The robot may roll and pitch: the scene renders with the tilt folded into the mount, so that the
// source, given the level mount, sees a tilted base.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "algo/core/image.hpp"
#include "algo/frames/frame.hpp"
#include "algo/geometry/camera_model.hpp"
#include "algo/geometry/pose.hpp"
#include "algo/geometry/rigid_transform.hpp"
#include "algo/map/marker_map.hpp"
#include "host_sim/render/landmark_spots.hpp"
#include "host_sim/render/noise.hpp"
#include "host_sim/scenario/scenario.hpp"

namespace irloc::test {

// T_B_C of a camera looking along the base's +x, image top up (camera z = base x, camera x =
// -base y, camera y = -base z), at xyz.
inline RigidTransform forward_mount(const Eigen::Vector3d& xyz) {
  RigidTransform mount;
  mount.rotation << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  mount.translation = xyz;
  return mount;
}

inline LedLandmark led_at(double x, double y, double z) {
  LedLandmark led;
  led.name = "L";
  led.position = {x, y, z};
  return led;
}

// A rectangle of radiance added to both frames (a lamp), pixel bounds inclusive.
struct PaintedLamp {
  int x0, y0, x1, y1;
  float radiance;
};

struct LedScene {
  CameraIntrinsics camera;
  RigidTransform mount = forward_mount({0.1, 0, 0.5});
  std::vector<LedLandmark> scene_leds;   // what is rendered
  Eigen::Vector3d base_xyz = Eigen::Vector3d::Zero();
  double yaw = 0, roll = 0, pitch = 0;
  double intensity = 0.01;               // W/sr of each LED toward the camera
  double psf_sigma = 0.7;                // pixels
  int bit_depth = 8;
  bool noise = true;
  std::uint64_t seed = 1;
  std::vector<PaintedLamp> lamps;
  std::vector<PaintedLamp> on_only;      // bright only in the LED-on frame (retro-reflectors)

  LedScene() {
    camera.width = 640;
    camera.height = 480;
    camera.fx = camera.fy = 500;
    camera.cx = 319.5;
    camera.cy = 239.5;
  }

  RigidTransform world_from_base() const {
    RigidTransform pose;
    pose.rotation = rotation_from_rpy(roll, pitch, yaw);
    pose.translation = base_xyz;
    return pose;
  }

  // The pixel where the camera model puts a world point, seen from the true pose.
  std::optional<Eigen::Vector2d> project(const Eigen::Vector3d& world) const {
    const CameraModel model(camera);
    Eigen::Vector2d pixel;
    if (!model.project((world_from_base() * mount).inverse() * world, pixel) || !model.in_image(pixel)) {
      return std::nullopt;
    }
    return pixel;
  }

  sim::Scenario scenario() const {
    sim::Scenario s;
    s.name = "led_scene";
    s.seed = seed;
    s.frames = 2;
    s.camera.intrinsics = camera;
    // Level trajectory at (x, y, yaw); roll, pitch and height go into the mount: T_W_C is the same.
    RigidTransform tilt;
    tilt.rotation = rotation_from_rpy(0, 0, yaw).transpose() * rotation_from_rpy(roll, pitch, yaw);
    tilt.translation = {0, 0, base_xyz.z()};
    const RigidTransform mount_tilted = tilt * mount;
    Eigen::Isometry3d m = Eigen::Isometry3d::Identity();
    m.linear() = mount_tilted.rotation;
    m.translation() = mount_tilted.translation;
    s.camera.mount = m;
    s.camera.bit_depth = bit_depth;
    s.camera.noise = noise;
    s.trajectory.kind = sim::TrajectoryKind::static_pose;
    s.trajectory.pose = {base_xyz.x(), base_xyz.y(), yaw};
    s.ring.types.push_back({"wide", 0.2, 0.6});
    s.room.ceiling_height = 3.0;
    s.room.ambient = 0;
    s.map.led_landmarks = scene_leds;
    s.landmark_emitters.intensity = intensity;
    s.landmark_emitters.psf_sigma = psf_sigma;
    s.supersampling = 1;
    return s;
  }
};

// A rendered strobe pair and the frames that view it.
struct RenderedPair {
  Image<std::uint8_t> on8, off8;
  Image<std::uint16_t> on16, off16;
  Frame on, off;
};

// The scene radiance of the LED-on and LED-off exposures (lamps and on-only spots included).
struct SceneRadiance {
  std::vector<float> on, off;
};

// The LEDs are imaged by the simulator's point-spread spots (host_sim/landmark_spots.hpp, what
// the Renderer adds for them) on a dark scene; ray-tracing the empty room around them would only
// cost time (led_simulation_test checks that the Renderer images LEDs the same way).
inline SceneRadiance render_radiance(const LedScene& scene) {
  const sim::Scenario scenario = scene.scenario();
  const CameraModel camera(scene.camera);
  const RigidTransform world_from_camera = scene.world_from_base() * scene.mount;
  Eigen::Isometry3d t_w_c = Eigen::Isometry3d::Identity();
  t_w_c.linear() = world_from_camera.rotation;
  t_w_c.translation() = world_from_camera.translation;
  const int w = scene.camera.width, h = scene.camera.height;
  SceneRadiance radiance{std::vector<float>(static_cast<std::size_t>(w * h)), {}};
  radiance.off = radiance.on;
  for (const bool led_on : {true, false}) {
    std::vector<float>& image = led_on ? radiance.on : radiance.off;
    sim::add_landmark_spots(scenario, camera, t_w_c, 1.0, image);
    auto paint = [&](const PaintedLamp& lamp) {
      for (int y = lamp.y0; y <= lamp.y1; ++y) {
        for (int x = lamp.x0; x <= lamp.x1; ++x) image[static_cast<std::size_t>(y * w + x)] += lamp.radiance;
      }
    };
    for (const PaintedLamp& lamp : scene.lamps) paint(lamp);
    if (led_on) {
      for (const PaintedLamp& spot : scene.on_only) paint(spot);
    }
  }
  return radiance;
}

// The sensor's frames of a rendered scene (noise drawn from scene.seed and seq).
inline void expose_pair(const LedScene& scene, const SceneRadiance& radiance, RenderedPair& pair, std::uint64_t seq = 0) {
  const sim::Scenario scenario = scene.scenario();
  const sim::Sensor sensor(scenario.camera, scenario.seed);
  const int w = scene.camera.width, h = scene.camera.height;
  const bool deep = scene.bit_depth > 8;
  if (deep) {
    pair.on16 = Image<std::uint16_t>(w, h);
    pair.off16 = Image<std::uint16_t>(w, h);
  } else {
    pair.on8 = Image<std::uint8_t>(w, h);
    pair.off8 = Image<std::uint8_t>(w, h);
  }
  for (const bool led_on : {true, false}) {
    const std::vector<float>& image = led_on ? radiance.on : radiance.off;
    const std::uint64_t frame_seq = seq * 2 + (led_on ? 0 : 1);
    for (int y = 0; y < h; ++y) {
      const std::span<const float> row(image.data() + static_cast<std::size_t>(y * w), static_cast<std::size_t>(w));
      if (deep) {
        sensor.expose_row(row, frame_seq, y, (led_on ? pair.on16 : pair.off16).view().row(y));
      } else {
        sensor.expose_row(row, frame_seq, y, (led_on ? pair.on8 : pair.off8).view().row(y));
      }
    }
  }
  const std::int64_t t_ns = 1'000'000'000 + static_cast<std::int64_t>(seq) * 66'666'667;
  pair.on = Frame{seq * 2, t_ns, true, {}};
  pair.off = Frame{seq * 2 + 1, t_ns + 33'333'333, false, {}};
  if (deep) {
    pair.on.image = ImageView16(pair.on16.view());
    pair.off.image = ImageView16(pair.off16.view());
  } else {
    pair.on.image = ImageView8(pair.on8.view());
    pair.off.image = ImageView8(pair.off8.view());
  }
}

inline void render_pair(const LedScene& scene, RenderedPair& pair, std::uint64_t seq = 0) {
  expose_pair(scene, render_radiance(scene), pair, seq);
}

}  // namespace irloc::test
