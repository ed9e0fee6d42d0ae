#pragma once
// The dot-matrix marker path, one strobe pair in, one pose attempt out:
//   front end (strobe difference -> blobs, algo/kernels) -> dot candidates -> groups ->
//   direction dots -> cell decoding + per-cell contrast test -> map lookup -> P3P + refinement
//   -> confidence.
// Everything is allocated in the constructor; process() allocates nothing, and its work is
// bounded by the fixed capacities of each stage (overflow shows in the frame report).

#include <vector>

#include <Eigen/Geometry>

#include "algo/geometry/camera_intrinsics.hpp"
#include "algo/geometry/camera_model.hpp"
#include "algo/geometry/pose.hpp"
#include "algo/kernels/fused_front_end.hpp"
#include "algo/markers/dot/cell_decoder.hpp"
#include "algo/markers/dot/dot_candidates.hpp"
#include "algo/markers/dot/dot_grouping.hpp"
#include "algo/markers/dot/dot_path_config.hpp"
#include "algo/markers/dot/dot_pose.hpp"
#include "algo/markers/dot/noise_threshold.hpp"
#include "algo/markers/dot/nominal_plane.hpp"
#include "algo/map/marker_map.hpp"
#include "algo/pipeline/pose_estimate.hpp"
#include "algo/frames/stage_times.hpp"
#include "algo/frames/strobe_pairer.hpp"

namespace irloc::dot {

// What the last frame saw, stage by stage; every `dropped` is an overflow report.
struct DotFrameReport {
  std::uint32_t threshold = 0;          // of the strobe difference, grey levels (the last one used)
  std::uint32_t threshold_doublings = 0;  // relabellings at twice the threshold after an overflow
  BlobCounters blobs;
  CandidateCounters candidates;
  GroupingCounters groups;
  std::uint32_t no_direction_dots = 0;  // groups without a right isosceles O, X, Y
  std::uint32_t impossible_layout = 0;  // a dot in cell (3, 3), or O, X, Y lost on refinement
  std::uint32_t low_cell_margin = 0;    // the per-cell intensity test disagreed with the decoding
  std::uint32_t unknown_ids = 0;        // decoded IDs not in the map: never used for a pose
  std::uint32_t markers_dropped = 0;    // mapped markers beyond kMaxMarkersInView
  std::uint32_t markers_decoded = 0;    // mapped markers handed to the pose stage
  std::uint32_t markers_used = 0;       // kept in the final fit
  double rms_px = 0;                    // reprojection RMS of the final fit
  double confidence = 0;                // before the floor
};

class DotPath {
 public:
  // camera: the calibration; base_from_camera: the mount T_B_C; map: its dot markers are copied.
  // Throws std::invalid_argument (at start-up) for a configuration the front end cannot run.
  DotPath(const CameraIntrinsics& camera, const Eigen::Isometry3d& base_from_camera, Dof dof, const MarkerMap& map,
          const DotPathConfig& config);
  // Its stages keep references to its members: it stays where it was made.
  DotPath(const DotPath&) = delete;
  DotPath& operator=(const DotPath&) = delete;

  // The pose attempt for the pair's LED-on frame; source `dot`. Not ok when the pair has no
  // LED-off frame, no mapped marker is decoded, or the confidence is below the floor.
  PoseEstimate process(const StrobePair& pair, StageClock::Times& times);

  const DotFrameReport& last_report() const { return report_; }
  // The markers decoded in the last frame (with their evidence and whether the fit used them).
  const MarkerObservationList& last_markers() const { return markers_; }
  const DotCandidateList& last_candidates() const { return candidates_; }
  const NominalPlane& nominal_plane() const { return plane_; }
  const DotPathConfig& config() const { return config_; }

 private:
  void label_blobs(const GrayImageView& on, const GrayImageView& off);
  void decode_groups(const GrayImageView& on, const GrayImageView& off);
  bool observe(const DecodedCells& decoded, MarkerObservation& observation) const;

  DotPathConfig config_;
  CameraModel camera_;
  RigidTransform base_from_camera_;
  Dof dof_;
  std::vector<DotMarker> markers_in_map_;
  NominalPlane plane_;
  double expected_diagonal_ = 0;  // |XY| on the nominal plane, metres
  double link_distance_ = 0;
  int window_radius_ = 1;         // cell contrast window, px
  NoiseThreshold noise_threshold_;
  FusedFrontEnd front_end_;
  DotCandidateSelector selector_;

  // Per-frame state, sized here.
  BlobList blobs_;
  DotCandidateList candidates_;
  DotGroupList groups_;
  MarkerObservationList markers_;
  DotFrameReport report_;
};

}  // namespace irloc::dot
