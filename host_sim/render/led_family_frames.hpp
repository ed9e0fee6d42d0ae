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
#include "algo/markers/led/led_association.hpp"
#include "host_sim/scenario/led_scene_family.hpp"

namespace irloc::sim {

// A mapped LED at an attempt and where the camera model projects it. In LedFamilyPair::visible:
// one the camera sees (lit, toward the camera inside its true cone, in the image clear of its
// border, above the detection threshold and clear of clutter and other LEDs).
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
  // Every lit LED toward which the camera lies inside the LED's true cone, where the camera model
  // projects it (in the image or not), visible or not: `visible` leaves out spots it cannot vouch
  // for (near clutter, near another LED), which the detector may still measure.
  std::vector<VisibleLed> lit;
  // The spurious always-on points (LedClutter::Kind::spurious) the camera sees by the same test as
  // `visible`, where the camera model projects them: to any source, by position, LEDs as well.
  std::vector<Eigen::Vector2d> stray;
};

// threshold: the detector's, a fraction of full scale (an LED counts as visible when its
// noise-free peak reaches 1.3 x it).
void render_led_family_pair(const LedFamilyScene& scene, int attempt, double threshold, LedFamilyPair& pair);
// The same pair (its time, the sensor's noise) seen by the robot standing still at
// `world_from_base`: what another pose would show in this room.
void render_led_family_pair_at(const LedFamilyScene& scene, int attempt, const RigidTransform& world_from_base,
                               double threshold, LedFamilyPair& pair);

// The true association of a pair's detections: each lit LED takes the detection nearest its
// projection within `within_px`, unless another lit LED projects within 2 within_px of it (the two
// spots are one detection, which is neither's). What a least-squares fit told the truth uses.
led::LedMatchList true_association(const LedFamilyPair& pair, const led::LedDetectionList& detections,
                                   double within_px);

}  // namespace irloc::sim
