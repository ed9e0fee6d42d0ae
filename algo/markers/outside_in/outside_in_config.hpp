#pragma once
// The outside-in source's settings (config `mode: outside_in`, docs/outside_in.md).
#include "algo/markers/outside_in/adaptive_background.hpp"
#include "algo/markers/outside_in/box_silhouette.hpp"
#include "algo/markers/outside_in/floor_geometry.hpp"

namespace irloc::outside_in {

struct OutsideInConfig {
  FloorReference floor_reference;   // camera.floor_reference
  BoxBody body;                     // robot.body
  AdaptiveBackgroundConfig background;  // width and height are the camera's; absorb_frames from absorb_s
  // Still foreground is absorbed into the background after this long (s), counted in frames of
  // the measured frame period (frame_period.hpp); a new track is protected from it for 3 times as long.
  double absorb_s = 1.0;
  int min_blob_area_px = 150;       // smaller foreground is noise
  int max_fits_per_frame = 8;       // bounded work: the largest plausible blobs are fitted
  // The fitted box must explain the blob: moment residual RMS up to this fraction of the
  // silhouette's size (sqrt of its area), and observed / fitted area within these bounds.
  double max_shape_residual = 0.06;
  double min_area_ratio = 0.8;
  double max_area_ratio = 1.25;
  int border_margin_px = 2;         // a blob this close to the image edge is not whole in view
  double max_coast_s = 0.35;        // the track survives this long without a fit
  double track_gate_m = 0.35;       // a fit this far from the track's prediction starts a new track
  double heading_motion_m = 0.05;   // travel that tells forward from backward on a new track
  double heading_prior_rad = 0.17;  // 10 deg: the track's predicted heading picks among the box fit's minima
};

}  // namespace irloc::outside_in
