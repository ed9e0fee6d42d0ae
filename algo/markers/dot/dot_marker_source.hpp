#pragma once
// The dot-matrix ID marker source, one checked strobe pair in, one SourceResult out:
//   blobs of the pair's shared pass (algo/kernels/pair_pass.hpp) -> dot candidates -> groups ->
//   direction dots -> cell decoding + per-cell contrast test -> map lookup -> P3P + refinement
//   -> confidence.
// Everything is allocated in the constructor; process() allocates nothing, and its work is
// bounded by the fixed capacities of each stage (overflow shows in the frame report). The pose's
// covariance is the refinement's (pose_refinement.hpp); the observations are the dots of every
// marker the final fit used.

#include <array>
#include <optional>
#include <utility>

#include <Eigen/Geometry>

#include "algo/core/static_vector.hpp"
#include "algo/geometry/camera_model.hpp"
#include "algo/kernels/pair_pass.hpp"
#include "algo/markers/dot/cell_decoder.hpp"
#include "algo/markers/dot/dot_candidates.hpp"
#include "algo/markers/dot/dot_grouping.hpp"
#include "algo/markers/dot/dot_pose.hpp"
#include "algo/markers/dot/dot_source_config.hpp"
#include "algo/markers/dot/nominal_plane.hpp"
#include "algo/markers/dot/track_identification.hpp"
#include "algo/source/pose_motion_fit.hpp"
#include "algo/source/pose_source.hpp"
#include "algo/source/source_result.hpp"

namespace irloc::dot {

// What the last frame saw, stage by stage; every `dropped` is an overflow report.
struct DotFrameReport {
  std::uint32_t threshold = 0;          // of the strobe difference, grey levels (the last one used)
  std::uint32_t threshold_doublings = 0;  // relabellings at twice the threshold after an overflow
  BlobCounters blobs;
  CandidateCounters candidates;
  GroupingCounters groups;
  std::uint32_t no_direction_dots = 0;  // groups without a right isosceles O, X, Y, none identified by the track
  std::uint32_t identified_by_track = 0;  // groups without direction dots that the track identified
  std::uint32_t impossible_layout = 0;  // a dot in cell (3, 3), or O, X, Y lost on refinement
  std::uint32_t low_cell_margin = 0;    // the per-cell intensity test disagreed with the decoding
  std::uint32_t unknown_ids = 0;        // decoded IDs not in the map: never used for a pose
  std::uint32_t markers_dropped = 0;    // markers beyond kMaxMarkersInView (unmapped ones kept only for the survey)
  std::uint32_t markers_decoded = 0;    // mapped markers handed to the pose stage
  std::uint32_t markers_used = 0;       // kept in the final fit
  double rms_px = 0;                    // reprojection RMS of the final fit
  double confidence = 0;                // before the floor
};


class DotMarkerSource final : public PoseSource {
 public:
  // The map's dot markers are copied. Throws std::invalid_argument (at start-up) for a
  // configuration the front end cannot run.
  DotMarkerSource(const SourceSetup& setup, const DotSourceConfig& config);

  SourceKind kind() const override { return SourceKind::dot; }
  // Uses input.pair's blobs: relabels them when its threshold differs from the shared one (its own
  // threshold settings) or after an overflow. Not ok when the pair has no LED-off frame, no
  // mapped marker is decoded, or the confidence is below the floor.
  void process(const SourceInput& input, SourceResult& result) override;
  // Forgets the dots kept of the last plain frame.
  void restart() override { last_plain_t_ns_.reset(); }

  // What the last process() saw, stage by stage.
  const DotFrameReport& last_diagnostics() const { return report_; }
  // The markers decoded in the last frame (with their evidence and whether the fit used them).
  const MarkerObservationList& last_markers() const { return markers_; }
  const DotCandidateList& last_candidates() const { return candidates_; }
  const NominalPlane& nominal_plane() const { return plane_; }
  const DotSourceConfig& config() const { return config_; }

 private:
  // The pair's blobs at this source's threshold, and the candidate dots among them (report_).
  void find_candidates(PairPass& pair, const GrayImageView& off, StageClock& clock, StageClock::Times& times);
  void decode_groups(const SourceInput& input, const GrayImageView& on, const GrayImageView& off);
  // A group without direction dots: the mapped marker the track identifies it as (with the per-cell
  // intensity test at the predicted cells) into markers_; else counted.
  void identify_by_track(const DotGroup& group, const GrayImageView& on, const GrayImageView& off);
  DotPoseOptions pose_options() const;
  // The fit's figures and confidence into report_.
  void rate_pose(const DotPoseResult& pose);
  // The decoded marker's dots; world points from the map (zero when the map lacks the ID).
  void observe(const DecodedCells& decoded, const DotMarker* mapped, MarkerObservation& observation) const;
  // config.observe_every_marker: every decoded marker's dots into the result.
  void report_every_marker(SourceResult& result) const;
  void add_map_uncertainty(const Eigen::Vector3d& base_position, PoseCovariance& covariance) const;
  void fill_result(const DotPoseResult& pose, const RefinementOptions& refinement, SourceResult& result) const;
  // The pose at the frame's t_ns under a rolling shutter (algo/source/rolling_shutter.hpp): the
  // markers' points moved for the track's motion, or for the motion since the last pose as this
  // frame's fits find it, or for the motion the frame's own dots give (with the fastest robot as
  // its prior: its uncertainty then in the covariance); the plain fit when that fit fails (its
  // covariance then allows for the motion).
  DotPoseResult solve_at_frame_time(const SourceInput& input, const DotPoseOptions& options);
  // Dots' mapped points, pixels and times (s) after the frame's t_ns, as fit_pose_and_motion
  // takes them: this frame's and the last plain frame's.
  struct DotSightings {
    static constexpr std::size_t kCapacity = 2 * kMaxPointObservations;
    StaticVector<Eigen::Vector3d, kCapacity> world;
    StaticVector<Eigen::Vector2d, kCapacity> pixels;
    StaticVector<double, kCapacity> times;
  };
  // The used dots of this frame: their mapped points, pixels and row times.
  void add_used_dots(DotSightings& sightings) const;
  // The pose at t_ns and the motion fitted together to the sightings from `plain` (a plain fit),
  // with motion_prior_ as the motion's prior (pose_motion_fit.hpp).
  PoseMotionFit fit_sightings(const DotSightings& sightings, const RigidTransform& plain) const;
  // With no motion known: the pose at t_ns and the motion fitted together to the used dots with
  // the fastest robot as the motion's prior (pose_motion_fit.hpp); empty when the fit fails.
  std::optional<PoseMotionFit> fit_motion_from_frame(const RigidTransform& plain);
  // After a plain last pose (input.prior, not null): the motion fitted to both frames' dots at
  // their times, from this frame's plain fit (`plain`, plain_delay_ns after t_ns), where this
  // source kept the last frame's dots (last_plain_t_ns_ the prior's t_ns); else, or where that fit
  // fails, the arc between the two plain fits (frame_motion). Two frames tell the motion that one
  // marker's rows do not; the arc is biased where the marker lies on other rows of the two frames.
  std::optional<FrameMotion> motion_after_plain_prior(const SourceInput& input, const RigidTransform& plain,
                                                      std::int64_t plain_delay_ns) const;
  // Keeps this frame's used dots for the next frame's motion where its pose is plain (the track
  // takes it as a plain fit); else forgets them.
  void keep_dots_if_plain(std::int64_t t_ns, const DotPoseResult& pose);
  // From the plain fit with no motion known: the pose fitted to the dots moved by the frame's own
  // motion (motion_; own_motion_covariance_ then holds what its uncertainty adds, plain_fit_ the
  // plain fit, which the next frame revises), or the plain fit.
  DotPoseResult solve_with_own_motion(const DotPoseOptions& options, const DotPoseResult& plain);
  void move_to_frame_time(const RigidTransform& world_from_base);
  std::pair<double, double> used_dots_time_and_height() const;
  void observations_to_frame_time(const RigidTransform& world_from_base, double ceiling_height, SourceResult& result) const;

  DotSourceConfig config_;
  CameraModel camera_;
  RigidTransform base_from_camera_;
  Dof dof_;
  const MarkerMap& map_;
  NominalPlane plane_;
  double expected_diagonal_ = 0;  // |XY| on the nominal plane, metres
  double link_distance_ = 0;
  int window_radius_ = 1;         // cell contrast window, px
  DotCandidateSelector selector_;
  TrackIdentifier track_identifier_;

  // Per-frame state, sized here.
  DotCandidateList candidates_;
  DotGroupList groups_;
  MarkerObservationList markers_;
  MarkerObservationList unmapped_markers_;  // only with config.observe_every_marker
  DotFrameReport report_;
  // Rolling shutter, per frame: the line time, the fastest robot's motion, the prior on the motion
  // where the track gives none (the motion before a gap, else the fastest robot's), the motion
  // within the frame (empty: unknown), what its uncertainty adds to the pose's covariance and the
  // plain fit where it was fitted to the frame's own dots (the pose is then at t_ns only as well
  // as its covariance says, and the observations stay at their rows' times), and the markers'
  // mapped points while their world points are moved to t_ns.
  std::int64_t line_time_ns_ = 0;
  MotionLimits limits_;
  MotionPrior motion_prior_;
  std::optional<FrameMotion> motion_;
  PoseCovariance own_motion_covariance_ = PoseCovariance::Zero();
  std::optional<RigidTransform> plain_fit_;
  std::array<std::array<Eigen::Vector3d, kCellCount>, kMaxMarkersInView> map_points_{};
  // Across frames: the used dots of the last frame whose pose was plain, and its t_ns.
  DotSightings last_plain_dots_;
  std::optional<std::int64_t> last_plain_t_ns_;
};

}  // namespace irloc::dot
