// OutsideInSource's fits of the box: to each blob's silhouette (box_silhouette.hpp), and to the
// pixels (appearance_fit.hpp) where a blob is only part of the robot or no blob carries the live
// track (docs/outside_in.md, steps 3-4 and "The appearance fit").
#include <array>
#include <cmath>
#include <numbers>

#include "algo/markers/outside_in/outside_in_source.hpp"

namespace irloc::outside_in {
namespace {

// A blob the box fits to within this residual RMS is the whole robot: no appearance fit.
constexpr double kWholeBlobResidualPx = 1.0;
// A blob larger than the box it is fitted to holds more than the robot (a person, a sun patch's
// ghost, a robot merged with them): no part of a robot, no appearance fit.
constexpr double kMaxPartAreaRatio = 1.0;
// Appearance fits of blobs per frame (the largest blobs first), each up to 160 costs: bounded work.
constexpr int kMaxAppearanceFits = 2;
// Beyond the filter's 3 sigma and the config's yaw rate: the fits' own heading noise.
constexpr double kTurnSlackRad = 5 * std::numbers::pi / 180;
// How far an appearance fit moves the silhouette fit's pose at most: its steps (2, 1, 0.5, 0.25 cm)
// times its evaluations would allow more, but a fit that ends farther off is a different minimum.
constexpr double kAppearanceReachM = 0.15;
// Starts closer than this end in the same minimum: one descent.
constexpr double kSameStartM = 0.01;

}  // namespace

bool OutsideInSource::fit_blob(const Blob& blob, const Eigen::Vector2d& predicted, const HeadingPrior& heading,
                               std::int64_t t_ns, FitCount& count, BoxFit& fit, bool& by_appearance, EndView& end) const {
  const Silhouette observed = silhouette_of(blob);
  // Cheap plausibility before the fit: the box upright at the blob's place has a similar area.
  Eigen::Vector2d floor;
  Silhouette upright;
  if (!box_.floor_point_below({observed.cx, observed.cy}, floor) || !box_.project({floor.x(), floor.y(), 0}, upright))
    return false;
  if (observed.area < 0.4 * upright.area || observed.area > 2.5 * upright.area) return false;
  ++count.fits;
  fit = fit_box(box_, observed, heading);
  by_appearance = false;
  const bool passes = fit.ok && fit.area_ratio >= config_.min_area_ratio && fit.area_ratio <= config_.max_area_ratio &&
                      fit.residual_rms_px <= config_.max_shape_residual * std::sqrt(fit.fitted.area);
  // A blob the box leaves a pixel or more unexplained, and no larger than it, may be part of a robot
  // whose other faces match the floor: its pixels decide, from the silhouette fit's pose.
  if (!fit.ok || (passes && fit.residual_rms_px <= kWholeBlobResidualPx) || fit.area_ratio > kMaxPartAreaRatio ||
      count.appearance_fits >= kMaxAppearanceFits || !may_carry_track(fit.pose, predicted))
    return passes;
  ++count.appearance_fits;
  // From the live track's prediction too, where that is another start: a blob that is part of the
  // robot can hold the fit in a minimum beside the robot's (measured: 44 mm off after a stop).
  const std::array<FloorPose, 2> starts{fit.pose, {predicted.x(), predicted.y(), heading.yaw}};
  const bool two = track_.active && std::hypot(starts[1].x - starts[0].x, starts[1].y - starts[0].y) > kSameStartM;
  by_appearance = fit_by_appearance(std::span<const FloorPose>(starts.data(), two ? 2 : 1), heading, t_ns, fit, end);
  return passes || by_appearance;
}

bool OutsideInSource::may_carry_track(const FloorPose& pose, const Eigen::Vector2d& predicted) const {
  if (!track_.active || !track_.heading_known) return true;
  return (Eigen::Vector2d(pose.x, pose.y) - predicted).norm() <= config_.track_gate_m + kAppearanceReachM;
}

bool OutsideInSource::reachable_heading(double yaw, std::int64_t t_ns) const {
  if (!track_.active) return true;
  const double dt = static_cast<double>(t_ns - track_.t_ns) * 1e-9;
  const double predicted = track_.heading.yaw() + track_.heading.rate() * dt;
  const double off = std::abs(std::remainder(yaw - predicted, box_.body().symmetry_turn()));
  return off <= limits_.yaw_rate * dt + 3 * std::sqrt(track_.heading.yaw_variance()) + kTurnSlackRad;
}

// The covariance is the silhouette fit's of the outline at the appearance fit's pose: what a whole
// blob of the robot there would give, not the appearance fit's own (one fit measured 60 mm off at a
// claimed 2 mm: docs/outside_in.md, "The appearance fit").
bool OutsideInSource::fit_by_appearance(std::span<const FloorPose> starts, const HeadingPrior& heading, std::int64_t t_ns,
                                        BoxFit& fit, EndView& end) const {
  const AppearanceFit refined = appearance_.refine(frame_, background_, starts);
  Silhouette outline;
  if (!refined.explains_robot() || !reachable_heading(refined.pose.yaw, t_ns) || !box_.project(refined.pose, outline))
    return false;
  const BoxFit redone = fit_box(box_, outline, heading);
  if (!redone.ok) return false;
  fit = redone;
  fit.pose = {refined.pose.x, refined.pose.y, box_.body().folded(refined.pose.yaw)};
  end = refined.end;
  if (std::cos(fit.pose.yaw - refined.pose.yaw) < 0) end.side = -end.side;  // the same end, seen from the folded yaw
  fit.heading_spread = 0;  // the pixels chose among the outline's minima
  return true;
}

bool OutsideInSource::fit_at_prediction(std::int64_t t_ns, const Eigen::Vector2d& predicted, const HeadingPrior& heading,
                                        ChosenFit& chosen) const {
  BoxFit fit;
  const FloorPose start{predicted.x(), predicted.y(), heading.yaw};
  EndView end;
  if (!fit_by_appearance(std::span<const FloorPose>(&start, 1), heading, t_ns, fit, end)) return false;
  const Silhouette& s = fit.fitted;
  if ((Eigen::Vector2d(fit.pose.x, fit.pose.y) - predicted).norm() > config_.track_gate_m ||
      touches_border(s.x_min, s.y_min, s.x_max, s.y_max))
    return false;
  chosen = {fit, true, true, 0, true, end};
  return true;
}

}  // namespace irloc::outside_in
