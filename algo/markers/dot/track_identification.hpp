#pragma once
// Stage 4c, with a track only: a group without its direction dots (a marker cut by the image's
// edge, its O, X or Y beyond it) identified from where the track predicts the mapped markers' dots
// (docs/dot_markers.md, "Markers identified by the track"). The decoder reads an ID from a
// marker's own dots; here the track names the marker, so the match must leave no doubt:
//  - every dot of the group not cut by the image's edge (its centre within its radius and
//    kEdgeTolerancePx of it: its centroid biased, it is left out) lies within the gate of exactly
//    one predicted dot of the mapped markers near the prediction, all of one marker, each a
//    different dot; the gate is kGateSigmas standard deviations (Mahalanobis) of the predicted
//    dot's pixel (the predicted pose's covariance through the projection, and the centroid's noise);
//  - at least kMinMatchedDots such dots, so that the pose is fitted to them with redundancy;
//  - every dot of that marker the group lacks is, where the matched dots put it (the prediction
//    moved by their mean offset), off the image or cut by its edge;
//  - the marker's dots shifted by one grid step (eight ways) or turned by a quarter, a half or
//    three quarters about its centre fit the group nowhere (each group dot within the gate of one of
//    them): a track off by one of those would name the wrong cells.
// Otherwise nothing is identified. The pose then comes from the normal fit to the dots.
// Bounded: the map's markers are tested once per frame for lying near the prediction (at most
// kMaxMarkersNear kept: more, and nothing is identified), each group's dots against theirs.
// Allocates nothing.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>

#include <Eigen/Core>

#include "algo/core/static_vector.hpp"
#include "algo/geometry/camera_model.hpp"
#include "algo/geometry/rigid_transform.hpp"
#include "algo/map/marker_map.hpp"
#include "algo/markers/dot/cell_decoder.hpp"
#include "algo/markers/dot/dot_candidates.hpp"
#include "algo/markers/dot/dot_grouping.hpp"
#include "algo/markers/dot/dot_marker_layout.hpp"
#include "algo/source/source_input.hpp"
#include "algo/source/source_result.hpp"

namespace irloc::dot {

// The pose the track predicts for a frame's t_ns, and the motion within the frame.
struct TrackPrediction {
  RigidTransform world_from_base;
  PoseCovariance covariance = PoseCovariance::Zero();  // (x, y, z, roll, pitch, yaw)
  FrameMotion motion;
  std::int64_t line_time_ns = 0;
};

// The input's track at its frame's t_ns: the last pose moved by the track's motion; its covariance
// the last pose's, grown by the motion's uncertainty and by what the robot may change of its motion
// (the fastest robot's steady turn, as for motion_prior_after_gap) over the time since and the
// frame's readout (readout_s). Empty without a track (no motion known, or a prior after t_ns).
std::optional<TrackPrediction> predict_from_track(const SourceInput& input, double readout_s);

struct TrackMatch {
  const DotMarker* marker = nullptr;
  DecodedCells decoded;  // cells, id, candidate_of_cell (grid_to_plane unused)
  // Every cell's predicted pixel, moved by the matched dots' mean offset from theirs (where the
  // per-cell intensity test reads), and which cells have one.
  std::array<Eigen::Vector2d, kCellCount> cell_pixels{};
  CellMask predicted = 0;
};

class TrackIdentifier {
 public:
  static constexpr double kGateSigmas = 4.0;
  static constexpr double kCentroidSigmaPx = 0.5;
  static constexpr int kMinMatchedDots = 5;
  static constexpr std::size_t kMaxMarkersNear = 8;
  // A dot whose centre lies within its radius and this of the image's edge may be cut by it.
  static constexpr double kEdgeTolerancePx = 1.0;

  TrackIdentifier(const CameraModel& camera, const RigidTransform& base_from_camera, const MarkerMap& map);

  // Per frame, before identify(): the mapped markers near the prediction and their predicted dots;
  // none without a prediction.
  void predict(const std::optional<TrackPrediction>& prediction);
  // The mapped marker the group's dots are, by the rules above; false when they do not decide one.
  bool identify(const DotCandidateList& candidates, const DotGroup& group, TrackMatch& match) const;

 private:
  struct PredictedMarker {
    const DotMarker* marker = nullptr;
    CellMask populated = 0;
    CellMask predicted = 0;  // cells whose pixel is predicted (in the camera model)
    std::array<Eigen::Vector2d, kCellCount> pixels{};
    // Populated cells: the inverse of the predicted pixel's covariance, px^-2.
    std::array<Eigen::Matrix2d, kCellCount> information{};
    double dot_radius_px = 0;
  };

  // Where the camera, moving from the prediction, sees `world` at its row's time; false outside the
  // camera model.
  bool predicted_pixel(const Eigen::Vector3d& world, Eigen::Vector2d& pixel) const;
  // The inverse covariance of the pixel of `world`: the predicted pose's spread through the
  // projection at t_ns, and the centroid's noise.
  Eigen::Matrix2d pixel_information(const Eigen::Vector3d& world) const;
  void predict_marker(const DotMarker& marker, double depth);
  // Whether the marker's dots, shifted by a grid step or turned by quarters, also fit the group.
  bool fits_elsewhere(const DotCandidateList& candidates, const DotGroup& group, const PredictedMarker& near) const;
  bool inside_by(const Eigen::Vector2d& pixel, double margin) const;

  const CameraModel& camera_;
  RigidTransform base_from_camera_;
  const MarkerMap& map_;
  TrackPrediction prediction_;
  bool too_many_ = false;
  double widest_dot_radius_px_ = 0;  // of the markers near the prediction
  StaticVector<PredictedMarker, kMaxMarkersNear> near_;
};

}  // namespace irloc::dot
