#include "host_sim/render/led_family_frames.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>

#include "algo/geometry/camera_model.hpp"
#include "host_sim/render/landmark_spots.hpp"
#include "host_sim/render/noise.hpp"
#include "host_sim/render/radiometry.hpp"

namespace irloc::sim {
namespace {

constexpr std::int64_t kStartNs = 1'000'000'000;
constexpr double kVisibleOverThreshold = 1.3;  // a visible LED's noise-free peak over the threshold
constexpr double kClearOfClutterPx = 6;        // and this far from clutter and other spots

// Radiance of the clutter, W sr^-1 m^-2 (full scale at the sensor's defaults is about 83).
double clutter_radiance(LedClutter::Kind kind) {
  switch (kind) {
    case LedClutter::Kind::lamp: return 300;
    case LedClutter::Kind::window: return 150;
    case LedClutter::Kind::retro: return 120;
    case LedClutter::Kind::spurious: return 0;  // imaged as a spot
  }
  return 0;
}

struct Disc {
  Eigen::Vector2d centre;
  double radius;
  bool spurious = false;  // a spurious point's (a spot, not a disc, in the image)
};

// The clutter's disc in the image seen from camera_from_world, if in front of the camera.
bool clutter_disc(const CameraModel& camera, const RigidTransform& camera_from_world, const LedClutter& clutter,
                  Disc& disc) {
  const Eigen::Vector3d point = camera_from_world * clutter.position;
  if (point.norm() < 0.3 || !camera.project(point, disc.centre)) return false;
  disc.radius = std::max(1.0, 0.5 * clutter.size * camera.intrinsics().fx / point.norm());
  return true;
}

void paint_disc(const Disc& disc, double radiance, int width, int height, std::vector<float>& image) {
  const int x0 = std::max(0, static_cast<int>(std::floor(disc.centre.x() - disc.radius)));
  const int x1 = std::min(width - 1, static_cast<int>(std::ceil(disc.centre.x() + disc.radius)));
  const int y0 = std::max(0, static_cast<int>(std::floor(disc.centre.y() - disc.radius)));
  const int y1 = std::min(height - 1, static_cast<int>(std::ceil(disc.centre.y() + disc.radius)));
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      if ((Eigen::Vector2d(x, y) - disc.centre).norm() <= disc.radius) {
        image[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)] +=
            static_cast<float>(radiance);
      }
    }
  }
}

// The spots' scenario: the lit installed LEDs and the spurious points.
Scenario spot_scenario(const LedFamilyScene& scene) {
  Scenario scenario;
  scenario.landmark_emitters.intensity = scene.led_intensity;
  scenario.landmark_emitters.psf_sigma = scene.psf_sigma;
  for (std::size_t k = 0; k < scene.leds.size(); ++k) {
    if (!scene.dead[k]) scenario.map.led_landmarks.push_back(scene.leds[k]);
  }
  for (const LedClutter& clutter : scene.clutter) {
    if (clutter.kind != LedClutter::Kind::spurious) continue;
    LedLandmark point;
    point.position = clutter.position;
    scenario.map.led_landmarks.push_back(point);
  }
  return scenario;
}

void size_images(const LedFamilyScene& scene, LedFamilyPair& pair) {
  const int width = scene.camera.width, height = scene.camera.height;
  if (scene.bit_depth > 8 && pair.on16.width() != width) {
    pair.on16 = Image16(width, height);
    pair.off16 = Image16(width, height);
  }
  if (scene.bit_depth <= 8 && pair.on8.width() != width) {
    pair.on8 = Image8(width, height);
    pair.off8 = Image8(width, height);
  }
}

// What renders one frame of a pair.
struct FrameRenderer {
  const LedFamilyScene& scene;
  const CameraModel& camera;
  const Sensor& sensor;
  const Scenario& spots;
  std::optional<RigidTransform> standing;  // the robot standing still there; else the scene's drive

  RigidTransform world_from_base(double t) const { return standing ? *standing : scene.world_from_base(t); }
};

// The frame `seq` (LED-on or off) into pair.on or pair.off; returns its radiance. In the LED-on
// frame, the clutter's discs (a spurious point as a 1 px disc) are added to clutter_seen.
std::vector<float> render_frame(const FrameRenderer& renderer, bool led_on, std::uint64_t seq, LedFamilyPair& pair,
                                std::vector<Disc>& clutter_seen) {
  const LedFamilyScene& scene = renderer.scene;
  const int width = scene.camera.width, height = scene.camera.height;
  const bool deep = scene.bit_depth > 8;
  const double t = static_cast<double>(seq) / scene.frame_rate;
  const RigidTransform world_from_camera = renderer.world_from_base(t) * scene.mount;
  const RigidTransform camera_from_world = world_from_camera.inverse();
  std::vector<float> radiance(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 0.0f);
  add_landmark_spots(renderer.spots, renderer.camera, to_isometry(world_from_camera), 1.0, radiance);
  for (const LedClutter& clutter : scene.clutter) {
    Disc disc{};
    if (clutter.kind == LedClutter::Kind::spurious || (clutter.kind == LedClutter::Kind::retro && !led_on) ||
        !clutter_disc(renderer.camera, camera_from_world, clutter, disc)) {
      continue;
    }
    paint_disc(disc, clutter_radiance(clutter.kind), width, height, radiance);
    if (led_on) clutter_seen.push_back(disc);
  }
  if (led_on) {
    for (const LedClutter& clutter : scene.clutter) {
      Disc disc{};
      if (clutter.kind == LedClutter::Kind::spurious && clutter_disc(renderer.camera, camera_from_world, clutter, disc)) {
        clutter_seen.push_back({disc.centre, 1.0, true});
      }
    }
  }
  for (int y = 0; y < height; ++y) {
    const std::span<const float> row(radiance.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(width),
                                     static_cast<std::size_t>(width));
    if (deep) {
      renderer.sensor.expose_row(row, seq, y, (led_on ? pair.on16 : pair.off16).view().row(y));
    } else {
      renderer.sensor.expose_row(row, seq, y, (led_on ? pair.on8 : pair.off8).view().row(y));
    }
  }
  Frame& frame = led_on ? pair.on : pair.off;
  frame = Frame{seq, kStartNs + static_cast<std::int64_t>(std::llround(t * 1e9)), led_on, {}};
  if (deep) {
    frame.image = ImageView16((led_on ? pair.on16 : pair.off16).view());
  } else {
    frame.image = ImageView8((led_on ? pair.on8 : pair.off8).view());
  }
  return radiance;
}

// Whether a spot at `pixel` shows clearly in the LED-on frame (its radiance given): clear of the
// image's border, its noise-free peak at least kVisibleOverThreshold x the threshold, and clear of
// the clutter's discs (but `own`, the spot's own disc, when it is clutter itself).
struct SpotTest {
  const FrameRenderer& renderer;
  const CameraSpec& spec;
  const std::vector<float>& on_radiance;
  const std::vector<Disc>& clutter_seen;
  double threshold;

  bool shows(const Eigen::Vector2d& pixel, const Disc* own = nullptr) const {
    const LedFamilyScene& scene = renderer.scene;
    const int width = scene.camera.width, height = scene.camera.height;
    const double margin = 3 * scene.psf_sigma + 4;
    if (pixel.x() < margin || pixel.y() < margin || pixel.x() > width - 1 - margin || pixel.y() > height - 1 - margin) {
      return false;
    }
    const auto x = static_cast<std::size_t>(std::lround(pixel.x())), y = static_cast<std::size_t>(std::lround(pixel.y()));
    double peak = 0;
    for (std::size_t dy = y - 1; dy <= y + 1; ++dy) {
      for (std::size_t dx = x - 1; dx <= x + 1; ++dx) {
        peak = std::max(peak, static_cast<double>(on_radiance[dy * static_cast<std::size_t>(width) + dx]));
      }
    }
    if (renderer.sensor.electrons(peak) / spec.full_well + spec.black_level < kVisibleOverThreshold * threshold) {
      return false;
    }
    return std::none_of(clutter_seen.begin(), clutter_seen.end(), [&](const Disc& disc) {
      return &disc != own && (disc.centre - pixel).norm() < disc.radius + kClearOfClutterPx + 3 * scene.psf_sigma;
    });
  }
  // Lit LEDs whose spots lie close enough to `pixel` to merge with a spot there.
  int lit_near(const LedFamilyPair& pair, const Eigen::Vector2d& pixel) const {
    return static_cast<int>(std::count_if(pair.lit.begin(), pair.lit.end(), [&](const VisibleLed& lit) {
      return (lit.pixel - pixel).norm() < kClearOfClutterPx + 3 * renderer.scene.psf_sigma;
    }));
  }
};

// pair.lit, pair.visible and pair.stray: the truth of what the LED-on frame shows.
void find_visible_spots(const SpotTest& test, LedFamilyPair& pair) {
  const LedFamilyScene& scene = test.renderer.scene;
  const RigidTransform world_from_camera = pair.world_from_base * scene.mount;
  const RigidTransform camera_from_world = world_from_camera.inverse();
  pair.visible.clear();
  pair.lit.clear();
  pair.stray.clear();
  for (std::size_t k = 0; k < scene.leds.size(); ++k) {
    Eigen::Vector2d pixel;
    if (scene.dead[k] || landmark_intensity(scene.leds[k], 1.0, world_from_camera.translation) <= 0 ||
        !test.renderer.camera.project(camera_from_world * scene.leds[k].position, pixel)) {
      continue;
    }
    pair.lit.push_back({static_cast<int>(k), pixel});
    if (test.shows(pixel)) pair.visible.push_back({static_cast<int>(k), pixel});
  }
  // Two LEDs whose spots merge are not visible as two.
  std::erase_if(pair.visible, [&](const VisibleLed& led) { return test.lit_near(pair, led.pixel) != 1; });
  for (const Disc& disc : test.clutter_seen) {
    if (disc.spurious && test.shows(disc.centre, &disc) && test.lit_near(pair, disc.centre) == 0) {
      pair.stray.push_back(disc.centre);
    }
  }
}

void render_pair(const LedFamilyScene& scene, int attempt, const std::optional<RigidTransform>& standing,
                 double threshold, LedFamilyPair& pair) {
  const CameraModel camera(scene.camera);
  CameraSpec spec;
  spec.intrinsics = scene.camera;
  spec.bit_depth = scene.bit_depth;
  const Sensor sensor(spec, scene.seed);
  const Scenario spots = spot_scenario(scene);
  const FrameRenderer renderer{scene, camera, sensor, spots, standing};

  const double t_on = scene.attempt_times[static_cast<std::size_t>(attempt)];
  const auto pair_index = static_cast<std::uint64_t>(std::llround(t_on * scene.frame_rate / 2));
  const std::uint64_t seq_on = 2 * pair_index;
  pair.world_from_base = renderer.world_from_base(t_on);
  size_images(scene, pair);
  std::vector<Disc> clutter_seen;  // in the LED-on frame
  const std::vector<float> on_radiance = render_frame(renderer, true, seq_on, pair, clutter_seen);
  render_frame(renderer, false, seq_on + 1, pair, clutter_seen);
  find_visible_spots(SpotTest{renderer, spec, on_radiance, clutter_seen, threshold}, pair);
}

}  // namespace

void render_led_family_pair(const LedFamilyScene& scene, int attempt, double threshold, LedFamilyPair& pair) {
  render_pair(scene, attempt, std::nullopt, threshold, pair);
}

void render_led_family_pair_at(const LedFamilyScene& scene, int attempt, const RigidTransform& world_from_base,
                               double threshold, LedFamilyPair& pair) {
  render_pair(scene, attempt, world_from_base, threshold, pair);
}

led::LedMatchList true_association(const LedFamilyPair& pair, const led::LedDetectionList& detections,
                                   double within_px) {
  led::LedMatchList matches;
  for (const VisibleLed& led : pair.lit) {
    const bool merged = std::any_of(pair.lit.begin(), pair.lit.end(), [&](const VisibleLed& other) {
      return other.landmark != led.landmark && (other.pixel - led.pixel).norm() < 2 * within_px;
    });
    if (merged) continue;
    int nearest = -1;
    double nearest_px = within_px;
    for (std::size_t d = 0; d < detections.size(); ++d) {
      const double distance = (detections[d].pixel - led.pixel).norm();
      if (distance < nearest_px) {
        nearest_px = distance;
        nearest = static_cast<int>(d);
      }
    }
    if (nearest >= 0) matches.push_back({led.landmark, nearest});
  }
  return matches;
}

}  // namespace irloc::sim
