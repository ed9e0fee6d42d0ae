#pragma once
// The strobe pairs of an LED family scene (led_scene_family.hpp) and their truth: the installed
// LEDs (true axes; dead ones dark) and spurious points as point-spread spots (landmark_spots.hpp),
// lamps and windows as bright discs in both frames, retro-reflectors only in the LED-on frame; the
// sensor's noise (noise.hpp). The LED-off frame is exposed one frame period after the LED-on one,
// from the pose of that instant. Rendering skips ray-tracing the room: what the LED source sees is
// the spots and the clutter.

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "algo/core/image.hpp"
#include "algo/frames/frame.hpp"
#include "host_sim/scenario/led_scene_family.hpp"

namespace irloc::sim {

// A mapped LED the camera sees at an attempt: lit, toward the camera inside its true cone, in the
// image clear of its border, above the detection threshold and clear of clutter and other LEDs.
struct VisibleLed {
  int landmark = -1;                                 // index in the map's led_landmarks
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();   // where the camera model projects it
};

struct LedFamilyPair {
  Image8 on8, off8;
  Image16 on16, off16;
  Frame on, off;
  RigidTransform world_from_base;    // the truth at the LED-on frame
  std::vector<VisibleLed> visible;
};

// threshold: the detector's, a fraction of full scale (an LED counts as visible when its
// noise-free peak reaches 1.3 x it).
void render_led_family_pair(const LedFamilyScene& scene, int attempt, double threshold, LedFamilyPair& pair);

}  // namespace irloc::sim
