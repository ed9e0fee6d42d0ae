#pragma once
// The survey's tuning (docs/survey.md). Defaults suit the corridor of docs/survey.md: a level
// robot at frame rate under markers 1.8 m apart.

#include <cstddef>

namespace irloc::survey {

struct SurveyConfig {
  // Capacity, sized at start-up: the markers a run refines (seen together with another, mapped or
  // learned: the dense solve's nodes, so a frame's solve is O(max_markers^3) and its memory
  // O(max_markers^2) whatever the map's size; the map's other markers are written as they were) and
  // the candidate IDs.
  std::size_t max_markers = 64;
  std::size_t max_candidates = 16;

  // One marker's dots -> the robot's pose in the marker's level frame.
  std::size_t min_dots = 5;           // fewer dots say too little about depth and yaw
  double refine_loss_scale_px = 1.5;  // Huber scale of the per-marker fit, pixels
  // Floor of the measured pixel noise, pixels: the centroid error that an ideal pixel grid (each
  // pixel integrating the light over its area) leaves on a sharp dot 3.5 px in radius, RMS per
  // axis over its sub-pixel places (docs/survey.md, "The error a line repeats"). Rendered drives
  // measure 0.009-0.015 px.
  double min_pixel_sigma = 0.0026;
  // Dots closer than this across an image axis share the error the pixel grid fixes along it
  // (px; their correlation falls linearly to none at this distance; pixel_error_response in
  // marker_sighting.cpp): the error is a function of the dot's place on the grid, so the dots of
  // one column of a marker aligned with the image repeat one u error. It changes sign within a
  // quarter of its period (1 px or less). The rendered drives' sigmas are the same at 0.5 px
  // (docs/survey.md, "The fixed marker's dots: one error per image column").
  double grid_error_correlation_px = 0.1;
  double pixel_noise_smoothing = 0.01;  // weight of one sighting in the running pixel-noise estimate
  // A sighting whose squared residuals exceed chi-square(2 dots - 4) at this probability times the
  // pooled pixel noise is not used (a clipped or merged dot).
  double poor_fit_false_alarm = 1e-4;

  // The graph: Huber on each edge's per-sighting Mahalanobis distance; a weak prior keeps every
  // node determined (an unseen marker stays at its map pose with this uncertainty).
  double edge_huber = 3.0;
  double prior_sigma_m = 1.0;
  double prior_sigma_yaw = 1.0;
  // A marker the map gives a `sigma` (surveyed before) holds to its map pose with that sigma times
  // this scale (the written sigmas are somewhat optimistic), at least the floors; Huber at
  // prior_huber sigmas lets its sightings outvote it when it has moved since.
  double surveyed_sigma_scale = 3.0;
  double min_surveyed_sigma_m = 0.002;
  double min_surveyed_sigma_yaw = 0.002;
  double prior_huber = 3.0;
  int iterations_per_frame = 1;
  // The error a line's sightings of a pair share beyond the repeated share of their own
  // (MarkerGraph::shared_variance()) is measured once the pairs hold this many lines beyond each
  // one's first (until then: none).
  int shared_error_min_lines = 5;

  // A node is established (localization may use it, it anchors new markers, its sightings are
  // gated and tested for moves) once its edges and the candidate sightings that placed it hold
  // this many sightings and its marginal sigma is within these: evidence, not a count alone.
  int min_established_sightings = 2;
  double established_sigma_m = 0.015;   // x and y each
  double established_sigma_yaw = 0.005;  // rad
  // One sighting of a pair against the solved graph: chi-square(4) gate (p = 1e-4): beyond it the
  // sighting is not added (it would drag both markers).
  double sighting_gate = 23.5;
  // The move test: the sum of a marker's last `move_window` sighting statistics against
  // chi-square(4 * move_window) at this false-alarm probability.
  int move_window = 10;
  double move_false_alarm = 1e-6;
  // ...and it must have moved at least this far: the test alone also fires on a marker whose
  // sightings are a little more biased than their covariance says (rendered dots: a few mm).
  double min_move_m = 0.05;
  double min_move_yaw = 0.05;

  // Candidates: an unmapped ID becomes a marker once its sightings at one place (placed through an
  // established marker seen in the same frame) are at least min_candidate_sightings from robot
  // positions at least min_candidate_baseline_m apart (not one view repeated), agree with each
  // other (chi-square at candidate_false_alarm), and place it within the established sigmas. A
  // sighting farther than candidate_radius from its place starts or joins a second place: an ID at
  // two places once each has conflict_sightings. A place within candidate_radius_m of another
  // marker is that marker's dots misread, never a marker.
  int min_candidate_sightings = 2;
  double min_candidate_baseline_m = 0.2;
  double candidate_false_alarm = 1e-4;
  double candidate_radius_m = 0.10;
  double candidate_radius_yaw = 0.2;
  int conflict_sightings = 6;
  double default_pitch = 0.04;  // grid pitch of markers not in the map, metres
};

}  // namespace irloc::survey
