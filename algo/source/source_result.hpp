#pragma once
// What one pose source reports for one pose attempt (pose_source.hpp). The Localizer fuses the
// results of every source that found a pose into the one PoseEstimate of the attempt.

#include <cstddef>
#include <cstdint>
#include <optional>

#include <Eigen/Core>

#include "algo/core/static_vector.hpp"
#include "algo/frames/stage_times.hpp"
#include "algo/geometry/rigid_transform.hpp"
#include "algo/source/frame_motion.hpp"
#include "algo/source/source_kind.hpp"

namespace irloc {

// One landmark point the source's pose used: a dot of a dot marker, a corner of a square, an LED.
// Map building and calibration group them by landmark.
struct PointObservation {
  int landmark = -1;   // dot marker ID; index in the map's square_markers or led_landmarks
  int point = 0;       // which point of the landmark: a dot's cell (0..15), a corner (0..3), 0 for an LED
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();  // where it was measured, px
  Eigen::Vector3d world = Eigen::Vector3d::Zero();  // where the map puts it, W, metres
};

inline constexpr std::size_t kMaxPointObservations = 128;
using PointObservationList = StaticVector<PointObservation, kMaxPointObservations>;

// The pose parameters' covariance: (x, y, z, roll, pitch, yaw) of T_W_B, m^2, rad^2 and m rad.
using PoseCovariance = Eigen::Matrix<double, 6, 6>;

struct SourceResult {
  SourceKind kind = SourceKind::dot;
  bool ok = false;                 // a trustworthy pose; the fields below the line mean nothing otherwise
  // "found", or why there is no pose: the text of the source's outcome enum (DotOutcome,
  // SquareOutcome, LedOutcome, OutsideInOutcome), set by set_outcome; counted per source by
  // OutcomeCounts (irlocd --stats).
  const char* outcome = "";
  // ---
  RigidTransform world_from_base;  // T_W_B
  // From the source's own solver at its solution (its Jacobian): anisotropic, with the cross
  // terms. Rows and columns of parameters the robot's dof fixes are zero.
  PoseCovariance covariance = PoseCovariance::Zero();
  int marker_id = -1;              // the dot marker the pose is named after, or -1
  double confidence = 0;           // in [0, 1]
  double rms_px = 0;               // reprojection RMS of the fit
  PointObservationList observations;  // the points the pose used (also for ok == false, when measured)
  StageClock::Times times;            // wall-clock time of each of the source's stages
  // 0 for the pose and the observations at the frame's t_ns; under a rolling shutter with the
  // motion within the frame unknown, or told only loosely by the frame itself, the observations'
  // mean row time after t_ns: their pixels are their rows', and the plain fit to them holds about
  // this long after t_ns. The pose is that plain fit, or where plain_fit is set, the pose at t_ns
  // as well as the frame tells it (the covariance says how well).
  std::int64_t pose_delay_ns = 0;
  // Where the pose is at t_ns by a motion that the frame alone told (no track), loosely (with
  // pose_delay_ns) or well: the plain fit, which a track takes as its last pose (PosePrior::plain:
  // with the next frame's plain fit, each at its own mean row time, the motion between the frames).
  std::optional<RigidTransform> plain_fit;
  // How long after t_ns the plain fit the track takes holds (plain(): plain_fit, else the pose),
  // the mean row time of the points fitted; 0 for a pose at t_ns.
  std::int64_t plain_delay_ns() const { return plain_fit ? plain_fit_delay_ns : pose_delay_ns; }
  std::int64_t plain_fit_delay_ns = 0;  // with plain_fit: how long after t_ns it holds
  // Under a rolling shutter, the motion within the frame that the pose at t_ns was solved with,
  // where the poses before this frame told it (the track's, or the arc from the last plain fit to
  // this frame's): the Localizer takes the pose back along it to revise the first pose before it
  // (Localizer::revised_previous). Empty where the frame alone told the motion, or nothing did.
  std::optional<FrameMotion> motion_from_track;

  // The outcome's text: the to_string of the source's outcome enum, found beside the enum in the
  // source's namespace, returns string literals (null-terminated, never freed).
  template <typename SourceOutcome>
  void set_outcome(SourceOutcome why) {
    outcome = to_string(why).data();
  }

  // Whether a track takes this pose as a plain fit: the plain fit itself, or a pose at t_ns by the
  // frame's own motion (plain_fit).
  bool plain() const { return pose_delay_ns > 0 || plain_fit.has_value(); }

  // Whether the pose and the observations' pixels are those at the frame's t_ns, what map building,
  // calibration and the mount watch take: not a plain fit of a rolling shutter's rows.
  bool at_frame_time() const { return pose_delay_ns == 0; }

  // Back to "nothing found" for the next attempt; allocates nothing.
  void clear(SourceKind source) {
    kind = source;
    ok = false;
    outcome = "";
    covariance.setZero();
    marker_id = -1;
    confidence = 0;
    rms_px = 0;
    observations.clear();
    times.clear();
    pose_delay_ns = 0;
    plain_fit.reset();
    plain_fit_delay_ns = 0;
    motion_from_track.reset();
  }
};

}  // namespace irloc
