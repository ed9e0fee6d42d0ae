#include "algo/markers/outside_in/outside_in_source.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "algo/markers/outside_in/dropped_foreground.hpp"
#include "algo/source/rolling_shutter.hpp"

namespace irloc::outside_in {
namespace {

OutsideInConfig sized(OutsideInConfig config, const CameraIntrinsics& camera) {
  config.background.width = camera.width;
  config.background.height = camera.height;
  return config;
}

FloorGeometry checked_floor(const CameraIntrinsics& camera, const FloorReference& reference) {
  FloorGeometry floor = solve_floor_geometry(camera, reference);
  if (!floor.ok) throw std::invalid_argument("camera." + floor.error);
  return floor;
}

// A robot lost for less than this, and found again within this distance, is the same robot.
constexpr std::int64_t kReacquireNs = 2'000'000'000;
constexpr double kReacquireM = 1.0;

// The box fit's heading error beyond its covariance: the mask's edges and the contact shadow
// bias it by a few degrees, at least; more where the heading depends on the silhouette's edges
// alone (BoxFit::heading_per_px times the mask's systematic error, about a pixel).
constexpr double kFitHeadingBias = 3 * std::numbers::pi / 180;
constexpr double kMaskBiasPx = 1.0;

// A heading less certain than this (5 degrees, 1 sigma) is not given: the goal's gross error is
// 10 degrees. The track keeps it and may become certain again.
constexpr double kMaxHeadingVariance = 5 * 5 * std::numbers::pi * std::numbers::pi / (180 * 180);

// The direction of travel as a heading: the line through the newest fitted positions back to the
// first at least kTravelBaseline (m) from the newest, within kTravelSpanS (s); each position off
// the line by at least kTravelPositionSigma (m, 1 sigma: the fits' frame-to-frame noise across
// the track, as measured in docs/outside_in.md, step 5).
constexpr double kTravelBaseline = 0.15;
constexpr double kTravelSpanS = 1.0;
constexpr double kTravelPositionSigma = 0.003;
// A fit is a new point of the travel once it lies this far from the newest (m): 3 sigma of two
// positions' difference. A robot at rest adds none: its last line, measured again each frame
// through the same points, would hold a turn in place back.
constexpr double kTravelStep = 3 * std::numbers::sqrt2 * kTravelPositionSigma;

double wrap(double angle) { return std::remainder(angle, 2 * std::numbers::pi); }

// Whether a robot unseen for `unseen_s` may have turned onto the box's mirror branch: as fast as
// the config allows (MotionLimits::yaw_rate), from a heading last known to `heading_sigma` (rad,
// 3 sigma of it counted).
bool may_have_turned_to_mirror(double unseen_s, double heading_sigma, double symmetry_turn, const MotionLimits& limits) {
  return limits.yaw_rate * unseen_s + 3 * heading_sigma >= 0.5 * symmetry_turn;
}

// The variance of a fit's systematic heading error, which stays while the view does (the heading
// filter's bias state): the mask's, at least kFitHeadingBias, heading_per_px times a pixel or
// the residuals' norm where larger (what the box leaves unexplained is an error of that size at
// least: fits at 0.3-0.7 px RMS lagging a turn in place by up to 12 degrees gave a pose 8 degrees
// off), widened by near-equal minima on both sides of the chosen one; and the floor reference's
// (camera_yaw_variance), which differs from view to view (a turn in place through a view where it
// moved the fits 8 degrees, followed at 4 degrees claimed, was posed 11 degrees off).
double heading_bias_variance(const BoxFit& fit, double camera_yaw_variance) {
  const double bias = std::max(kFitHeadingBias, std::max(kMaskBiasPx, fit.residual_norm_px) * fit.heading_per_px);
  return bias * bias + 0.25 * fit.heading_spread * fit.heading_spread + camera_yaw_variance;
}

// Whether the box explains the fit's blob to the mask's own error: a blob that holds more (a sun
// patch's ghost or a person merged with the robot) or less (a face the foreground missed) leaves
// residuals of several pixels, and its fit's heading and position are off by more than their
// covariance says (10-12 cm and 30-180 degrees beside a ghost; 8 degrees with a face missing).
bool explains_blob(const BoxFit& fit) { return fit.residual_rms_px <= kMaskBiasPx; }

// Whether the blob is the robot whole, to within what the fit allows for: a blob whose tip the
// cleaning cut off (dropped_foreground.hpp) is fitted to a fraction of a pixel as the whole box
// turned and moved (10 degrees and 40 mm off). Its fit shows where the robot is, to the extent
// lost (fill_result), and its heading, with that in its variance (it still tells the box's
// branch); its position is no point of the direction of travel.
bool blob_whole(int dropped_extent_px) { return dropped_extent_px <= kAllowedDroppedPx; }

// The one of yaw + k * period nearest the reference heading (period: the box's symmetry turn).
double nearer_branch(double yaw, double reference, double period) {
  return wrap(reference + std::remainder(yaw - reference, period));
}

}  // namespace

OutsideInSource::OutsideInSource(const SourceSetup& setup, const OutsideInConfig& config)
    : config_(sized(config, setup.camera)),
      width_(setup.camera.width),
      height_(setup.camera.height),
      camera_(setup.camera),
      floor_(checked_floor(setup.camera, config.floor_reference)),
      box_(camera_, floor_.camera_from_world, config.body),
      appearance_(box_, width_, height_),
      background_(config_.background),
      open_and_close_(setup.camera.width),
      labeller_(static_cast<std::size_t>(setup.camera.width) * setup.camera.height / 8),
      foreground_(static_cast<std::size_t>(width_) * height_),
      scratch_(foreground_.size()),
      mask_(foreground_.size()) {}

bool OutsideInSource::touches_border(int x_min, int y_min, int x_max, int y_max) const {
  const int margin = config_.border_margin_px;
  return x_min < margin || y_min < margin || x_max >= width_ - margin || y_max >= height_ - margin;
}

ProtectedRects OutsideInSource::protected_rects(std::int64_t t_ns) const {
  ProtectedRects rects;
  // A new track is protected for a while before it has moved: the robot itself may stand still.
  // One that never moves (what was behind a robot in view at start-up) loses it and is absorbed.
  const bool young = static_cast<double>(t_ns - track_.start_t_ns) < 3 * config_.absorb_s * 1e9;
  if (track_.active && (track_.moved || young)) {
    constexpr int kMargin = 3;
    const Silhouette& s = track_.silhouette;
    rects.add({s.x_min - kMargin, s.y_min - kMargin, s.x_max + kMargin, s.y_max + kMargin});
  }
  // A mover half in view (the robot entering a view, close and large) cannot be fitted, so it has
  // no track yet: the last frame's blobs at the image's edge keep their still insides.
  for (const Blob& blob : blobs_)
    if (touches_border(blob.x_min, blob.y_min, blob.x_max, blob.y_max)) rects.add({blob.x_min, blob.y_min, blob.x_max, blob.y_max});
  return rects;
}

void OutsideInSource::restart() {
  background_.restart();
  background_step_ = BackgroundStep{};
  frame_period_.restart();
  track_ = Track{};
  last_seen_ = LastSeen{};
  blobs_.clear();  // the last frame's, which protect the background at the image's edge
}

void OutsideInSource::process(const SourceInput& input, SourceResult& result) {
  result.clear(SourceKind::external);
  attempt_ = AttemptDetail{};
  clock_.start(result.times);
  const auto* frame = std::get_if<ImageView8>(&input.on.image);
  if (!frame) {
    result.set_outcome(OutsideInOutcome::unsupported_depth);
    return;
  }
  const MutableImageView8 foreground(foreground_.data(), width_, height_);
  const MutableImageView8 scratch(scratch_.data(), width_, height_);
  const MutableImageView8 mask(mask_.data(), width_, height_);
  const bool learning = !background_.started();
  frame_period_.add(input.on.t_ns);
  background_.set_absorb_frames(frame_period_.frames_in(config_.absorb_s, background_.absorb_frames(), 255));
  background_step_ = background_.apply(*frame, foreground, protected_rects(input.on.t_ns));
  frame_ = *frame;
  limits_ = input.limits;
  clock_.mark(result.times, "background");
  if (learning) {
    result.set_outcome(OutsideInOutcome::learning_background);
    return;
  }
  open_and_close_.apply(foreground, scratch, mask);
  labeller_.label(mask, BlobParams{static_cast<std::uint32_t>(config_.min_blob_area_px)}, blobs_);
  clock_.mark(result.times, "components");

  forget_if_clock_broke(input.on.t_ns);
  ChosenFit chosen;
  const bool found = choose_fit(input.on.t_ns, chosen);
  clock_.mark(result.times, "box_fit");
  if (!found) {
    if (track_.active) mark_merge();
    if (track_.active) {
      ++track_.missed;
      if (static_cast<double>(input.on.t_ns - track_.t_ns) > config_.max_coast_s * 1e9) track_.active = false;
    }
    result.set_outcome(track_.active ? OutsideInOutcome::occluded : OutsideInOutcome::no_robot);
    return;
  }
  const bool motion_known = fit_at_frame_time(input.on.t_ns, input.line_time_ns, chosen.continues_track, chosen.fit);
  const OutsideInOutcome outcome = update_track(input.on.t_ns, chosen, input.limits);
  result.set_outcome(outcome);
  if (outcome != OutsideInOutcome::found) return;
  fill_result(chosen, motion_known, input, result);
}

// The track's pose, with the fit's covariance, the floor reference's, the heading filter's yaw
// variance and, without the motion, what the rows' time can add.
void OutsideInSource::fill_result(const ChosenFit& chosen, bool motion_known, const SourceInput& input,
                                  SourceResult& result) const {
  const BoxFit& fit = chosen.fit;
  result.ok = true;
  result.world_from_base.rotation = Eigen::AngleAxisd(track_.pose.yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  result.world_from_base.translation = Eigen::Vector3d(track_.pose.x, track_.pose.y, 0);
  const int index[3] = {0, 1, 5};  // x, y, yaw among (x, y, z, roll, pitch, yaw)
  // The fit's own uncertainty and the floor reference's, which moves every pose alike.
  const Eigen::Matrix3d from_camera = fit.camera_sensitivity * floor_.covariance * fit.camera_sensitivity.transpose();
  Eigen::Matrix3d covariance = fit.covariance + from_camera;
  // A blob short of the robot: an error of that many pixels in an extent residual, at its weight.
  if (!blob_whole(chosen.dropped_extent)) {
    const double shortfall = kExtentResidualWeight * chosen.dropped_extent;
    covariance += shortfall * shortfall * fit.per_px_covariance;
  }
  // The heading is the filter's: its variance (and the camera's part), the cross terms scaled to
  // keep their correlation.
  const double yaw_variance = track_.heading.yaw_variance() + from_camera(2, 2);
  const double yaw_scale = std::sqrt(yaw_variance / covariance(2, 2));
  covariance.row(2).head<2>() *= yaw_scale;
  covariance.col(2).head<2>() *= yaw_scale;
  covariance(2, 2) = yaw_variance;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) result.covariance(index[i], index[j]) = covariance(i, j);
  if (!motion_known) {
    const double seen_after = row_time({fit.fitted.cx, fit.fitted.cy}, input.line_time_ns);
    add_unknown_motion(seen_after, input.limits, result.covariance);
    result.pose_delay_ns = std::llround(seen_after * 1e9);
  }
  result.rms_px = fit.residual_rms_px;
  result.confidence = 1.0 / (1.0 + fit.residual_rms_px);
}

// A frame clock that went back or leapt (a camera reopened, a clock jump) breaks the track's
// timing: start it over, heading unknown, rather than predict from it.
void OutsideInSource::forget_if_clock_broke(std::int64_t t_ns) {
  const std::int64_t since_track = t_ns - track_.t_ns;
  if (track_.t_ns != 0 && (since_track < 0 || since_track >= kReacquireNs)) track_ = Track{};
  const std::int64_t since_seen = t_ns - last_seen_.t_ns;
  if (since_seen < 0 || since_seen >= kReacquireNs) last_seen_.valid = false;
}

// The box fit holds for the time its silhouette's rows were seen, about its centre row's (the
// box spans few rows; the shear of its sides is second order). The arc from the track's last pose
// to the fit (rolling_shutter.hpp's constant motion, which a robot on a curve keeps and a
// smoothed velocity lags behind) moves it back to t_ns. A new track, or one that coasted longer
// than kMaxTrackGapNs, has no motion.
bool OutsideInSource::fit_at_frame_time(std::int64_t t_ns, std::int64_t line_time_ns, bool continues_track,
                                        BoxFit& fit) const {
  if (line_time_ns <= 0) return true;
  if (!continues_track) return false;
  const double seen_after = row_time({fit.fitted.cx, fit.fitted.cy}, line_time_ns);
  const auto pose_of = [](const FloorPose& floor) {
    return RigidTransform{Eigen::AngleAxisd(floor.yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix(),
                          Eigen::Vector3d(floor.x, floor.y, 0)};
  };
  const PosePrior last{pose_of(track_.pose), track_.t_ns};
  FloorPose seen = fit.pose;
  seen.yaw = nearer_branch(seen.yaw, track_.pose.yaw, box_.body().symmetry_turn());
  const std::optional<FrameMotion> motion =
      motion_since(&last, pose_of(seen), t_ns + std::llround(seen_after * 1e9), kMaxTrackGapNs);
  if (!motion) return false;
  const RigidTransform at_frame_time = pose_after(pose_of(seen), -seen_after, *motion);
  fit.pose.x = at_frame_time.translation.x();
  fit.pose.y = at_frame_time.translation.y();
  fit.pose.yaw = wrap(seen.yaw - motion->yaw_rate * seen_after);
  return true;
}

bool OutsideInSource::choose_fit(std::int64_t t_ns, ChosenFit& chosen) const {
  const bool tracking = track_.active;
  const double dt = tracking ? static_cast<double>(t_ns - track_.t_ns) * 1e-9 : 0;
  const Eigen::Vector2d predicted = Eigen::Vector2d(track_.pose.x, track_.pose.y) + track_.velocity * dt;
  const HeadingPrior heading{track_.heading.yaw() + track_.heading.rate() * dt, tracking ? config_.heading_prior_rad : 0};
  // Where the robot would be had it kept its velocity since it was last seen with its heading:
  // measured from where it was seen instead, a box-like ghost beside that place (a drifting sun
  // patch) can win over the robot that has driven on (docs/outside_in.md).
  const Eigen::Vector2d last_seen_expected = last_seen_.expected_at(t_ns);
  // Candidates rank by class, then score: 0, near where the robot is expected since it was last
  // seen with its heading (it keeps that heading; this beats a new track elsewhere, on a ghost or
  // a box-like mover);
  // 1, the live track's gated continuation; 2, without a track, the best-shaped box.
  int best_class = 3;
  double best_score = std::numeric_limits<double>::infinity();
  FitCount count;
  for (const Blob& blob : blobs_) {
    if (count.fits >= config_.max_fits_per_frame) break;
    if (touches_border(blob.x_min, blob.y_min, blob.x_max, blob.y_max)) continue;  // not whole in view
    BoxFit fit;
    bool by_appearance = false;
    EndView end;
    if (!fit_blob(blob, predicted, heading, t_ns, count, fit, by_appearance, end)) continue;
    const Eigen::Vector2d position(fit.pose.x, fit.pose.y);
    const double distance = (position - predicted).norm();
    const bool gated = tracking && distance <= config_.track_gate_m;
    // A blob the box does not explain, or not whole, may carry a live track along, never start
    // one: where it began and which way it went are the blob's, not the robot's.
    const bool explains = explains_blob(fit);
    // The appearance fit sees the faces the foreground dropped.
    const int dropped = by_appearance ? 0 : dropped_extent_px(blob, foreground_view(), foreground());
    if (!gated && !(explains && blob_whole(dropped))) continue;
    const double from_last_seen = (position - last_seen_expected).norm();
    int candidate_class = 3;
    double score = 0;
    if (tracking && track_.heading_known) {
      if (gated) candidate_class = 1, score = distance;
    } else if (last_seen_.valid && from_last_seen < kReacquireM) {
      candidate_class = 0, score = from_last_seen;
    } else if (gated) {
      candidate_class = 1, score = distance;
    } else if (!tracking) {
      candidate_class = 2, score = fit.residual_rms_px;
    }
    if (candidate_class < best_class || (candidate_class == best_class && score < best_score)) {
      best_class = candidate_class;
      best_score = score;
      chosen = {fit, gated, explains, dropped, by_appearance, end};
    }
  }
  if (best_class == 3 && tracking) return fit_at_prediction(t_ns, predicted, heading, chosen);
  return best_class < 3;
}

OutsideInOutcome OutsideInSource::update_track(std::int64_t t_ns, const ChosenFit& chosen, const MotionLimits& limits) {
  const BoxFit& fit = chosen.fit;
  const Eigen::Vector2d position(fit.pose.x, fit.pose.y);
  // The fit's heading error: its own noise (white), and the systematic errors.
  const double camera_yaw_variance =
      fit.camera_sensitivity.row(2) * floor_.covariance * fit.camera_sensitivity.row(2).transpose();
  const double bias_variance = heading_bias_variance(fit, camera_yaw_variance);
  const double white_variance = fit.covariance(2, 2);
  const bool whole = blob_whole(chosen.dropped_extent);
  const double shortfall = whole ? 0.0 : kExtentResidualWeight * chosen.dropped_extent;
  const double shortfall_variance = shortfall * shortfall * fit.per_px_covariance(2, 2);
  if (!chosen.continues_track) {
    start_track(t_ns, chosen, white_variance, bias_variance, limits);
  } else {
    const double dt = static_cast<double>(t_ns - track_.t_ns) * 1e-9;
    const Eigen::Vector2d step = position - Eigen::Vector2d(track_.pose.x, track_.pose.y);
    if (dt > 0) track_.velocity = 0.5 * (track_.velocity + step / dt);
    // The robot's travel, for the fits' bias (the view's change) and for rest: counted once it is
    // kTravelStep from where it was last counted, so that the fits' own frame-to-frame noise (a few
    // millimetres, whatever the frame rate) is neither a drive nor a change of view.
    const double moved = (position - track_.moved_from).norm();
    const double travel = moved >= kTravelStep ? moved : 0.0;
    if (travel > 0 && track_.branch_from_travel && track_.heading_known &&
        track_.branch.add(position - track_.moved_from, track_.heading.yaw()))
      track_.heading.turn_by(std::numbers::pi);
    if (travel > 0) track_.moved_from = position;
    track_.heading.predict(dt, travel, travel < HeadingFilter::kRestSpeed * dt, bias_variance);
    if (chosen.explained)
      measure_heading(t_ns, fit, white_variance + shortfall_variance, bias_variance, whole && !track_.beside_merge, limits);
    else
      mark_merge();
    track_.pose = {fit.pose.x, fit.pose.y, track_.heading.yaw()};
  }
  track_.beside_merge = !chosen.explained;
  track_.t_ns = t_ns;
  track_.missed = 0;
  ++track_.frames;
  track_.silhouette = fit.fitted;
  attempt_ = {chosen.dropped_extent, std::sqrt(track_.heading.yaw_variance()), std::sqrt(camera_yaw_variance), track_.frames,
              track_.pose.yaw};
  if (!chosen.explained) return OutsideInOutcome::not_explained;
  // The floor reference's error also moves the heading from travel (it turns the floor plane
  // as a whole, a bias the filter cannot average away): the pose's heading variance, filter and
  // camera, decides.
  const bool uncertain = track_.heading.yaw_variance() + camera_yaw_variance > kMaxHeadingVariance;
  use_end_view(chosen.end, fit.pose.yaw, !uncertain);
  if (!track_.heading_known || (track_.branch_from_travel && !track_.branch.confirmed()))
    return OutsideInOutcome::heading_unknown;
  last_seen_ = {true, track_.pose, std::sqrt(track_.heading.yaw_variance()), track_.velocity, t_ns};
  return uncertain ? OutsideInOutcome::heading_uncertain : OutsideInOutcome::found;
}

void OutsideInSource::start_track(std::int64_t t_ns, const ChosenFit& chosen, double white_variance, double bias_variance,
                                  const MotionLimits& limits) {
  const BoxFit& fit = chosen.fit;
  const Eigen::Vector2d position(fit.pose.x, fit.pose.y);
  // Seen again after an occlusion near where it was last seen: it keeps its heading's branch,
  // unless it may have turned onto the mirror one unseen (hidden by a person for 1.5 s while it
  // turned in place, a robot was taken back 180 degrees off). Its position tells nothing of a
  // turn in place.
  const bool reacquired = last_seen_.valid && (position - last_seen_.expected_at(t_ns)).norm() < kReacquireM &&
                          !may_have_turned_to_mirror(static_cast<double>(t_ns - last_seen_.t_ns) * 1e-9, last_seen_.heading_sigma,
                                                     box_.body().symmetry_turn(), limits);
  const double heading = last_seen_.pose.yaw;
  track_ = Track{};
  track_.active = true;
  track_.pose = fit.pose;
  track_.anchor = position;
  track_.moved_from = position;
  track_.start_t_ns = t_ns;
  track_.travel.add(position, t_ns);
  track_.heading_t_ns = t_ns;
  track_.heading_sigma = std::sqrt(white_variance + bias_variance);
  track_.branch_from_travel = chosen.by_appearance;
  if (reacquired) {
    track_.pose.yaw = nearer_branch(fit.pose.yaw, heading, box_.body().symmetry_turn());
    track_.heading_known = true;
    track_.moved = true;
    track_.branch.confirm();
  }
  track_.heading.reset(track_.pose.yaw, white_variance, bias_variance);
}

// The fits just before and after a blob the box does not explain (merged with a sun patch's ghost
// or a person; or no fit at all) may hold a little of it still, within the mask's error, and be
// pulled sideways by it smoothly, frame after frame, and a travel line through them turns with
// them. They still give a position and their outline's heading; the one before leaves the travel
// history (the lines it already entered stay measured), the one after does not enter it.
void OutsideInSource::mark_merge() {
  if (track_.travel.size() > 0 && track_.travel.back(0).t_ns == track_.t_ns) track_.travel.drop_newest();
  track_.beside_merge = true;
}

// A fit that explains its blob measures the heading: by its outline (the filter takes the branch
// nearest its prediction) and, while the robot drives, by its travel. After frames without such
// a fit the robot may have turned unseen as fast as the config allows (MotionLimits::yaw_rate):
// once that turn, with 3 sigma of the heading last measured, could reach the box's mirror branch,
// the branch is not known and is resolved as a new track's (merged with a sun patch's ghost for
// 1.8 s, a robot driving straight was taken on its mirror branch, 180 degrees off).
void OutsideInSource::measure_heading(std::int64_t t_ns, const BoxFit& fit, double white_variance, double bias_variance,
                                      bool adds_travel, const MotionLimits& limits) {
  const Eigen::Vector2d position(fit.pose.x, fit.pose.y);
  const double symmetry = box_.body().symmetry_turn();
  const bool after_gap = track_.missed > 0 || track_.heading_t_ns < track_.t_ns;
  const double unseen_s = static_cast<double>(t_ns - track_.heading_t_ns) * 1e-9;
  if (track_.heading_known && after_gap && may_have_turned_to_mirror(unseen_s, track_.heading_sigma, symmetry, limits)) {
    track_.heading_known = false;
    track_.anchor = position;
    track_.travel = TravelHistory{};
    track_.branch = TravelBranch{};
    track_.heading.reset(fit.pose.yaw, white_variance, bias_variance);
  } else {
    track_.heading.update_fit(fit.pose.yaw, white_variance, symmetry);
  }
  if (adds_travel &&
      (track_.travel.size() == 0 || (position - track_.travel.back(0).position).norm() >= kTravelStep)) {
    track_.travel.add(position, t_ns);
    update_heading_from_travel();
  }
  track_.heading_t_ns = t_ns;
  track_.heading_sigma = std::sqrt(track_.heading.yaw_variance());
  if (track_.heading_known) return;
  const Eigen::Vector2d travel_since_start = position - track_.anchor;
  if (travel_since_start.norm() < config_.heading_motion_m) return;
  // The robot drives forward when it first moves in view; after that the heading follows by
  // continuity, whichever way it drives.
  const double forward = nearer_branch(track_.heading.yaw(), std::atan2(travel_since_start.y(), travel_since_start.x()), symmetry);
  track_.heading.turn_by(wrap(forward - track_.heading.yaw()));
  track_.heading_known = true;
  track_.moved = true;
}

// A robot on wheels heads where it drives (or reverses): the line fitted through its positions
// over the shortest recent stretch of kTravelBaseline gives the heading modulo a half turn at
// their mean time (the filter relates that to now by its turn rate: the shortest stretch lags
// least). It is free of the fits' heading bias (the mask's error
// moves the position little), so it anchors the heading while the robot drives and keeps it
// through a stop, where the fits alone sat on their bias. The positions' scatter across the line
// is its noise, as measured: a curve, or fits that jump between the mirror-image minima of an
// end-on view (about 2 cm apart across the track), widen it. A robot that drives sideways fails
// the filter's 3-sigma gate and is not taken for heading where it goes.
void OutsideInSource::update_heading_from_travel() {
  const TravelHistory& travel = track_.travel;
  const std::int64_t newest = travel.back(0).t_ns;
  int count = 0;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  double mean_age = 0;  // s before the newest
  bool spans_baseline = false;
  while (count < travel.size() && !spans_baseline) {
    const double age = static_cast<double>(newest - travel.back(count).t_ns) * 1e-9;
    if (age > kTravelSpanS) break;
    spans_baseline = (travel.back(count).position - travel.back(0).position).norm() >= kTravelBaseline;
    mean += travel.back(count).position;
    mean_age += age;
    ++count;
  }
  if (!spans_baseline || count < 3) return;
  mean /= count;
  mean_age /= count;
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  for (int k = 0; k < count; ++k) {
    const Eigen::Vector2d offset = travel.back(k).position - mean;
    scatter += offset * offset.transpose();
  }
  // The principal direction of the scatter (the total least-squares line).
  const double angle = 0.5 * std::atan2(2 * scatter(0, 1), scatter(0, 0) - scatter(1, 1));
  const Eigen::Vector2d along(std::cos(angle), std::sin(angle));
  const Eigen::Vector2d across(-along.y(), along.x());
  double along_min = 0, along_max = 0, along_squares = 0, across_squares = 0;
  for (int k = 0; k < count; ++k) {
    const Eigen::Vector2d offset = travel.back(k).position - mean;
    const double a = along.dot(offset), c = across.dot(offset);
    along_min = std::min(along_min, a);
    along_max = std::max(along_max, a);
    along_squares += a * a;
    across_squares += c * c;
  }
  if (along_max - along_min < kTravelBaseline) return;
  const double noise = std::max(across_squares / (count - 2), kTravelPositionSigma * kTravelPositionSigma);
  // The line's direction variance is noise / along_squares; each position enters the lines of
  // about `count` consecutive frames, so each line counts for 1 / count of its information.
  const double variance = count * noise / along_squares;
  track_.heading.update_unbiased(angle, mean_age, variance, std::numbers::pi);
}

}  // namespace irloc::outside_in
