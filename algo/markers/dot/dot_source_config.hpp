#pragma once
// Every tunable of the dot-marker path in one place, with its default (the `dot:` section of
// the config YAML, docs/dot_markers.md). Units: pixels of the frame, grey levels of the
// frame's depth, metres, radians.

#include <cstdint>

namespace irloc::dot {

// One component of the grey-level model: a Gaussian over a blob's mean strobe difference.
struct GreyLevelComponent {
  double weight = 0.5;  // mixing weight
  double mean = 0;      // grey levels
  double sigma = 1;     // grey levels, > 0
};

// The paper's grey-level model: dot intensities are a mixture of genuine retro-reflective dots
// and clutter (noise, glints, lamp edges). The posterior of `dot` is a dot's grey-level evidence.
// `irloc-sim fit-confidence` fits both components to a recorded dataset.
struct GreyLevelModel {
  GreyLevelComponent dot{0.5, 80.0, 50.0};
  GreyLevelComponent clutter{0.5, 8.0, 4.0};
};

struct DotSourceConfig {
  int pixel_bits = 8;               // significant bits of the camera's pixels (8, 10, 12 or 16)
  // Foreground: on - off > threshold, grey levels. 0: estimated per frame from the difference's
  // noise (noise_threshold.hpp) as median + threshold_sigmas * sigma, at least min_threshold.
  std::uint32_t threshold = 0;
  double threshold_sigmas = 5.0;
  std::uint32_t min_threshold = 6;
  int threshold_rows = 48;          // rows sampled (evenly spaced) for the noise estimate
  // Distance from the camera to the ceiling plane along the plane's normal, metres; 0 derives it
  // from the map (mean dot-marker height) and the mount height.
  double ceiling_distance = 0;

  // Candidates (per blob).
  std::uint32_t min_area = 2;          // pixels
  double max_area_factor = 6.0;        // largest area, in units of the expected dot area (+ 9 px)
  double max_elongation = 2.5;         // sqrt(major / minor variance), tested from 6 px up
  double min_contrast = 0.35;          // (on - off) / on at the dot: lamps are bright when LEDs are off

  // Grouping and direction dots.
  double link_factor = 1.3;            // dots closer than link_factor * 3 pitch join one group
  double scale_tolerance = 1.4;        // marker size in the nominal plane within [1/t, t] of expected
  double max_side_ratio_error = 0.2;   // | |OX| / |OY| - 1 |
  double max_right_angle_error = 0.25; // | angle XOY - 90 deg |, radians

  // Decoding.
  double snap_tolerance = 0.3;         // a dot belongs to a cell within this many pitches
  double min_cell_margin = 0.2;        // per-cell intensity test margin below which a marker is rejected

  // Pose.
  double refine_loss_scale_px = 1.5;   // Huber scale of the refinement, pixels
  double marker_gate_px = 3.0;         // a marker whose dots reproject worse (RMS) is dropped
  // The reported covariance uses the pixel noise of each fit's own residuals, at least this, px.
  double min_pixel_sigma = 0.02;

  // Confidence.
  GreyLevelModel grey_levels;
  double rms_scale_px = 1.0;           // geometric evidence exp(-rms^2 / (2 scale^2))
  double full_margin = 0.6;            // a cell margin at or above this counts as full evidence
  double confidence_floor = 0.5;       // below: the pose is reported as `none`
};

}  // namespace irloc::dot
