#include "algo/markers/square/square_marker_source.hpp"

#include <array>
#include <cmath>

#include "algo/source/rolling_shutter.hpp"

namespace irloc::square {

namespace {

// The frame's own motion is used when its 1-sigma uncertainty is at most the fastest robot's speed
// and yaw rate (what the covariance allows for with the motion unknown) over this.
constexpr double kOwnMotionGain = 4;

// The mean row time after t_ns of the found squares' corners, ns: when a plain fit to them holds.
std::int64_t corners_mean_row_time_ns(const SquareDetection& detection, std::int64_t line_time_ns) {
  double sum = 0;
  for (std::size_t seen = 0; seen < detection.square_count; ++seen) {
    for (const Eigen::Vector2d& corner : detection.corner_pixels[seen]) sum += row_time(corner, line_time_ns);
  }
  const double corners = 4.0 * static_cast<double>(detection.square_count);
  return corners > 0 ? std::llround(sum / corners * 1e9) : 0;
}

}  // namespace

SquareMarkerSource::SquareMarkerSource(const SourceSetup& setup, const SquareConfig& config)
    : detector_(setup.camera, setup.pixel_bits, setup.base_from_camera, setup.dof, setup.map.square_markers, config),
      max_prior_age_ns_(static_cast<std::int64_t>(config.max_prior_age * 1e9)) {}

void SquareMarkerSource::process(const SourceInput& input, SourceResult& result) {
  result.clear(SourceKind::square);
  detection_ = SquareDetection{};
  own_motion_covariance_.setZero();
  motion_from_track_.reset();
  plain_fit_.reset();
  if (input.off == nullptr) {
    result.set_outcome(SquareOutcome::no_off_frame);
    return;
  }
  StageClock clock;
  clock.start(result.times);
  // A prior from the frame clock's future (the clock went back) is of unknown age: not used.
  const bool recent = input.prior != nullptr && input.on.t_ns >= input.prior->t_ns &&
                      input.on.t_ns - input.prior->t_ns <= max_prior_age_ns_;
  const RigidTransform* prior = recent ? &input.prior->world_from_base : nullptr;
  const bool at_frame_time = detect(input, prior);
  clock.mark(result.times, "square");
  result.set_outcome(detection_.outcome);
  if (!detection_.found()) return;
  result.ok = true;
  result.world_from_base = detection_.world_from_base;
  result.covariance = detection_.covariance;
  result.confidence = detection_.confidence;
  for (std::size_t seen = 0; seen < detection_.square_count; ++seen) {
    const int square = detection_.squares[seen];
    const SquareMarker& marker = detector_.markers()[static_cast<std::size_t>(square)];
    for (int corner = 0; corner < 4; ++corner) {
      const auto k = static_cast<std::size_t>(corner);
      result.observations.push_back({square, corner, detection_.corner_pixels[seen][k], marker.corners[k]});
    }
  }
  const std::int64_t mean_row_time_ns = corners_mean_row_time_ns(detection_, input.line_time_ns);
  // The frame's own motion's uncertainty, on x, y and yaw of the pose.
  constexpr std::array<int, 3> kPlanar{0, 1, 5};
  for (std::size_t i = 0; i < 3; ++i) {
    for (std::size_t j = 0; j < 3; ++j) result.covariance(kPlanar[i], kPlanar[j]) += own_motion_covariance_(i, j);
  }
  if (at_frame_time) result.motion_from_track = motion_from_track_;
  result.plain_fit = plain_fit_;
  if (plain_fit_) result.plain_fit_delay_ns = plain_fit_delay_ns_;
  if (input.line_time_ns > 0 && !at_frame_time) {
    add_unknown_motion(static_cast<double>(mean_row_time_ns) * 1e-9, input.limits, result.covariance);
    result.pose_delay_ns = mean_row_time_ns;
  }
}

// Under a rolling shutter the detector moves the tape points to t_ns by the motion within the
// frame before it fits the sides. That motion is the track's. Without one, after a pose at its
// frame's t_ns, the motion from that pose to this frame's own fit, found again with it: twice,
// for the first fit is the pose at about the tape's mean row time (taken as the pose then: its
// corners' mean row time) and the second, at t_ns, settles the motion; after a plain last pose (a
// first frame's), once: the arc between the two plain fits, each at its own mean row time. With no recent
// pose (a drive's first frame, after a gap) the frame's own motion: fitted with the pose to the
// tape of the square found as seen (SquareDetector::fit_motion), its prior the motion before a
// gap the track did not bridge, else the fastest robot's (frame_motion_prior: a robot that does
// not drive sideways bounds the speed the tape decides least well), used where it tells the
// motion at least kOwnMotionGain times better than the fastest robot's bounds (its uncertainty
// goes into the covariance; the square as seen is the plain fit the track takes, so the next
// frame revises this pose: Localizer::revised_previous). Where it does not (dof 6, a square seen
// over few rows), the plain fit.
// A fit that fails with the motion leaves the one as seen.
bool SquareMarkerSource::detect(const SourceInput& input, const RigidTransform* prior) {
  const double line_time = static_cast<double>(input.line_time_ns) * 1e-9;
  if (input.line_time_ns > 0 && input.motion) {
    const RowMotion rows{*input.motion, line_time};
    detection_ = detector_.detect(input.on.image, input.off->image, *input.pair, prior, &rows);
    motion_from_track_ = input.motion;
    return true;
  }
  detection_ = detector_.detect(input.on.image, input.off->image, *input.pair, prior);
  if (input.line_time_ns == 0) return true;
  if (!detection_.found()) return false;
  const bool motion_from_last_pose =
      input.prior != nullptr && frame_motion(input, detection_.world_from_base).has_value();
  const TapeMotionFit own =
      motion_from_last_pose ? TapeMotionFit{} : detector_.fit_motion(detection_, line_time, frame_motion_prior(input));
  if (own.ok && own.velocity_sigma * kOwnMotionGain <= input.limits.speed &&
      own.yaw_rate_sigma * kOwnMotionGain <= input.limits.yaw_rate) {
    const RowMotion rows{own.motion, line_time};
    SquareDetection moved = detector_.detect(input.on.image, input.off->image, *input.pair, prior, &rows);
    if (moved.found()) {
      plain_fit_ = detection_.world_from_base;
      plain_fit_delay_ns_ = corners_mean_row_time_ns(detection_, input.line_time_ns);
      detection_ = moved;
      own_motion_covariance_ = own.pose_covariance;
      return true;
    }
  }
  const int passes = input.prior != nullptr && input.prior->plain ? 1 : 2;
  bool at_frame_time = false;
  for (int pass = 0; pass < passes; ++pass) {
    // The square as seen holds at its corners' mean row time; found again with a motion, at t_ns.
    const std::int64_t fit_delay_ns = at_frame_time ? 0 : corners_mean_row_time_ns(detection_, input.line_time_ns);
    const std::optional<FrameMotion> motion = frame_motion(input, detection_.world_from_base, fit_delay_ns);
    if (!motion) break;
    const RowMotion rows{*motion, line_time};
    SquareDetection moved = detector_.detect(input.on.image, input.off->image, *input.pair, prior, &rows);
    if (!moved.found()) break;
    detection_ = moved;
    motion_from_track_ = motion;
    at_frame_time = true;
  }
  return at_frame_time;
}

}  // namespace irloc::square
