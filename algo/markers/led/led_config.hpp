#pragma once
// Every tunable of the active IR LED landmark source in one place, with its default (the `led:`
// section of the config YAML, docs/led_landmarks.md). Units: pixels of the frame, fractions of
// the frame's full scale, metres, radians.

namespace irloc::led {

struct LedSourceConfig {
  // Detection. An LED is a small round spot brighter than `threshold` in the LED-on frame whose
  // LED-off partner is bright there too (retro-reflectors go dark when the robot's LEDs are off).
  double threshold = 0.25;            // fraction of full scale
  double off_threshold = 0.15;        // fraction of full scale the LED-off frame must reach nearby
  int off_search_px = 20;             // how far the spot may move between the two frames (turning)
  int max_area = 80;                  // pixels: larger spots are lamps or sunlit patches
  double max_elongation = 1.8;        // sqrt(major / minor variance), tested from 5 pixels up
  int centroid_margin = 2;            // pixels around a spot in its centroid window

  // Association.
  int search_detections = 10;         // brightest detections the hypothesis search uses
  int max_hypotheses = 60000;         // solver calls per search; beyond it the search gives up
  double search_gate_px = 6.0;        // a mapped LED reprojects onto a detection within this
  double accept_gate_px = 2.0;        // ... and after refinement within this
  double max_rms_px = 1.0;            // a fit with a larger reprojection RMS is refused
  // Mapped LEDs a pose predicts well inside the image that are not seen (dim at the edge of a
  // fisheye, occluded): at most max(max_missing, max_missing_fraction x predicted).
  int max_missing = 1;
  double max_missing_fraction = 0.3;
  double edge_margin_px = 12.0;       // "well inside": this far from the image border
  // ... and bright enough to be seen: the matched LED of least brightness x range^2, moved to the
  // unseen LED's range (inverse square), would be at least this many times the detection
  // threshold. Off its axis an LED is dimmer than its range alone says, so the rule never excuses
  // an LED that its range says must show; it excuses far LEDs beside near, faint ones.
  double missing_brightness = 2.0;
  // radians: how far an LED's real axis may be off the map's direction. Within this of its cone's
  // edge an LED may match a detection but is not missed when unseen.
  double cone_tolerance = 0.26;
  double max_range = 15.0;            // metres: farther LEDs are not expected to be seen
  // The most mapped LEDs in any 3 max_range x 3 max_range square (led_neighbourhood.hpp): each
  // pose considered costs this many projections at most; a denser map is refused at start-up.
  int max_leds_in_range = 512;
  double max_tilt = 0.2;              // radians: base tilt a hypothesis may have (dof 6)
  double min_height = -0.3;           // metres: base z a hypothesis may have
  double max_height = 0.3;
  double distinct_position = 0.05;    // metres: hypotheses further apart are different poses
  double distinct_angle = 0.02;       // radians
  // The search's winner explains this many more LEDs (matched less missing) than every other
  // verified pose, else `ambiguous` (docs/led_landmarks.md: the margins measured on the family).
  int min_margin_leds = 1;

  // Tracking from the last pose.
  double track_gate_px = 12.0;        // a prediction matches the one detection within this
  double track_timeout = 0.5;         // seconds since the last pose after which the track is lost
  double track_max_jump = 0.3;        // metres (and radians) a tracked pose may leave the prediction

  // Continuity: a searched pose within reach_window of the last pose may be at most the fastest
  // robot's (robot.max_speed, robot.max_yaw_rate: SourceInput::limits) travel in dt plus
  // track_max_jump metres (and its turn plus track_max_jump radians) from it. A layout that two
  // poses explain (a pair of LEDs and a spurious point) then cannot move the robot across the room.
  double reach_window = 2.0;          // seconds

  // Pose.
  // A fit whose horizontal (x, y) position or yaw is less certain than this gives no pose
  // (standard deviations from the covariance at pixel_sigma; height, roll and pitch are not judged).
  double max_position_sigma = 0.25;   // metres
  double max_yaw_sigma = 0.05;        // radians
  double pixel_sigma = 0.2;           // pixels: standard deviation of a centre, for the covariance
  double loss_scale_px = 1.0;         // Huber scale of the refinement
};

}  // namespace irloc::led
