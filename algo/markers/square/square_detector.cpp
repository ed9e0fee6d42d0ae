#include "algo/markers/square/square_detector.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <variant>

#include "algo/markers/square/corner_order.hpp"
#include "algo/markers/square/solid_side.hpp"
#include "algo/markers/square/square_search.hpp"

namespace irloc::square {
namespace {

// At most (SquareRefiner::refine): the wide passes end when the corners settle, usually after
// two; a coarse side a few degrees off (under dof 6, a skewed square's column pair) takes more.
constexpr int kRefinementPasses = 6;
// A passed hypothesis fits closely when its corner RMS is at most this fraction of
// max_corner_residual (5 mm of 2 cm): its variants are merged into it, and its sides are not
// straightened (straighten_if_loose).
constexpr double kCloseFitCornerRms = 0.25;
// The pose on straightened sides replaces a hypothesis's when its corner RMS is at most this
// fraction of the hypothesis's: a side pulled by a strip fits the map's square many times worse
// than the straightened one, while on a far square with few points a segment a straightened side
// is a choice within the noise that would move a fused pose by millimetres (the measurements are
// in docs/square_markers.md, step 6).
constexpr double kStraightCornerRms = 0.5;
// Capacity of the tape point buffers; the Hough vote takes fewer than 2^16 points.
constexpr std::size_t kMaxTapePoints = 65535;
static_assert(kMaxSquaresInView <= TapeMotionFitter::kMaxSquares);

// Tape threshold from the pair's shared noise estimate: median + kTapeSigmas sigma, as the dot
// source's blobs. The thin-line extractor keeps any isolated pixel above it as a tape point, so
// the noise must stay below it nearly everywhere.
constexpr double kTapeSigmas = 5.0;
constexpr std::uint32_t kMinTapeThreshold = 6;

std::uint16_t tape_threshold(const DifferenceNoise& noise) {
  return static_cast<std::uint16_t>(std::min<std::uint32_t>(noise.threshold(kTapeSigmas, kMinTapeThreshold), 65535));
}

int element_radius_for(const CeilingPlaneMap& plane, double tape_width) {
  // The opening must erase the widest tape: more than half of it in pixels, and one more.
  const double widest = tape_width / plane.min_metres_per_pixel();
  return static_cast<int>(std::ceil(widest / 2)) + 1;
}

HoughConfig hough_config(const CeilingPlaneMap& plane, const SquareMarker& marker, double side) {
  HoughConfig config;
  config.theta_bins = 180;
  // Bins one tape width wide: a tape's points fall in one or two of them.
  config.rho_resolution = static_cast<std::int32_t>(std::lround(marker.tape_width * kPlaneRawPerMetre));
  config.rho_max = static_cast<std::int32_t>(std::ceil(plane.max_radius() * std::sqrt(2.0) * kPlaneRawPerMetre));
  config.max_points = kMaxTapePoints;
  // A dashed side half hidden still gives about d / 4 of tape, two grid cells wide.
  const double cell = marker.tape_width / 2;
  config.min_votes = static_cast<std::uint32_t>(std::max(6.0, 0.1 * side / cell));
  config.nms_rho = 2;
  config.nms_theta = 3;
  config.refine_peaks = false;  // the sides are refined on all the tape points (side_refinement.hpp)
  return config;
}

// Two hypotheses that put the robot at the same pose (within 5 cm and 2 degrees) are one.
bool same_pose(const RigidTransform& p, const RigidTransform& q) {
  const double turn = std::abs(wrap_angle(rpy_from_rotation(p.rotation).yaw - rpy_from_rotation(q.rotation).yaw));
  return (p.translation - q.translation).norm() < 0.05 && turn < 0.035;
}
bool same_pose(const SquareDetection& a, const SquareDetection& b) { return same_pose(a.world_from_base, b.world_from_base); }

// The mapped region, or std::invalid_argument when no pixel sees the ceiling.
const CeilingPlaneMap::Region& mapped(const CeilingPlaneMap& plane) {
  if (plane.mapped_region().width == 0) throw std::invalid_argument("square path: no pixel sees the ceiling");
  return plane.mapped_region();
}


}  // namespace

SquareDetector::SquareDetector(const CameraIntrinsics& camera, int pixel_bits, const RigidTransform& base_from_camera,
                               Dof dof, std::span<const SquareMarker> markers, const SquareConfig& config)
    : config_(config),
      dof_(dof),
      markers_(checked_square_markers(markers)),
      base_from_camera_(base_from_camera),
      side_(mean_side(markers_.front())),
      ceiling_z_(ceiling_z_of(markers_.front())),
      camera_(camera),
      plane_(camera_, base_from_camera, ceiling_above_camera(markers_.front(), base_from_camera), config.max_ray_angle),
      poser_(camera_, plane_, base_from_camera, dof, markers_, config_),
      tape_mask_(mapped(plane_).x, mapped(plane_).y, mapped(plane_).width, mapped(plane_).height,
                 element_radius_for(plane_, markers_.front().tape_width), pixel_bits),
      tape_points_(plane_, markers_.front().tape_width / 2, kMaxTapePoints, TapePoints::kTapePatchCells,
                  base_from_camera.translation.head<2>()),
      refiner_(kMaxTapePoints),
      hough_(hough_config(plane_, markers_.front(), side_)),
      levelled_(plane_.ceiling_above_camera(), dof == Dof::full6 ? kMaxTapePoints : 0) {
  element_radius_ = element_radius_for(plane_, markers_.front().tape_width);
  // A side needs at least as many tape pixels as a Hough peak needs grid cells.
  min_side_points_ = hough_config(plane_, markers_.front(), side_).min_votes;
  options_.resize(markers_.size());
  for (std::size_t m = 0; m < markers_.size(); ++m) {
    const SquareMarker& marker = markers_[m];
    ceiling_above_camera(marker, base_from_camera);
    map_turns_.push_back(turn(marker.corners[0].head<2>(), marker.corners[1].head<2>(), marker.corners[2].head<2>()));
    const DashGeometry geometry{marker.tape_width, marker.dash, marker.gap};
    const auto group = std::find_if(groups_.begin(), groups_.end(), [&](const PatternGroup& g) {
      return g.geometry.dash == geometry.dash && g.geometry.gap == geometry.gap;
    });
    if (group == groups_.end()) {
      groups_.push_back({geometry, {m}});
    } else {
      group->members.push_back(m);
    }
  }
}

SquareDetection SquareDetector::detect(const GrayImageView& on, const GrayImageView& off, const DifferenceNoise& noise,
                                       const RigidTransform* prior, const RowMotion* rows) {
  return detect_pair(on, off, noise, nullptr, prior, rows);
}

SquareDetection SquareDetector::detect(const GrayImageView& on, const GrayImageView& off, const PairPass& pair,
                                       const RigidTransform* prior, const RowMotion* rows) {
  return detect_pair(on, off, pair.analysis().noise, &pair, prior, rows);
}

SquareDetection SquareDetector::detect_pair(const GrayImageView& on, const GrayImageView& off,
                                            const DifferenceNoise& noise, const PairPass* pair,
                                            const RigidTransform* prior, const RowMotion* rows) {
  const int width = camera_.intrinsics().width;
  const int height = camera_.intrinsics().height;
  if (on.index() != off.index() || std::holds_alternative<ImageView16>(on) != tape_mask_.wide() ||
      width_of(on) != width || height_of(on) != height || width_of(off) != width || height_of(off) != height) {
    SquareDetection refused;
    refused.outcome = SquareOutcome::bad_frames;
    return refused;
  }
  const std::uint16_t threshold = config_.threshold > 0 ? config_.threshold : tape_threshold(noise);
  const bool shared = pair != nullptr && pair->analysis().threshold == threshold &&
                      pair->analysis().blob_counters.runs_dropped == 0;
  if (shared) {
    tape_mask_.extract(pair->foreground_runs());
  } else {
    tape_mask_.extract(on, off, threshold);
  }
  SquareDetection detection = detect_in_mask(tape_mask_.mask(), tape_mask_.x(), tape_mask_.y(), prior, rows);
  detection.threshold = threshold;
  detection.mask_from_shared_pass = shared;
  return detection;
}

SquareDetection SquareDetector::detect_in_mask(const BitImage& mask, int x0, int y0, const RigidTransform* prior,
                                               const RowMotion* rows) {
  const TapePointCounters points = tape_points_.collect(mask, x0, y0, rows);
  levelled_.forget();
  frame_.clear();
  const HoughCounters hough = hough_.detect(tape_points_.vote_points(), peaks_);
  find_hypotheses(prior);
  SquareDetection detection;
  if (frame_.passed.empty()) {
    detection.outcome = frame_.outcome;
  } else {
    detection = choose();
  }
  detection.points = points;
  detection.hough = hough;
  detection.hypotheses_found = static_cast<std::uint32_t>(frame_.passed.size());
  detection.hypotheses_merged = frame_.merged;
  return detection;
}

void SquareDetector::find_hypotheses(const RigidTransform* prior) {
  // With the height known (dof 3) a side on the table is d long to within the consistency check
  // and the Hough bins (a tape width): no wider search, so that a weak line a few bins off does not
  // make a hypothesis with the true ones.
  const bool exact = dof_ == Dof::planar3;
  const double side_tolerance =
      exact ? std::min(config_.side_tolerance, config_.max_side_error + markers_.front().tape_width / side_)
            : config_.side_tolerance;
  // The level search, also under dof 6: the small tilt of a robot on a rough floor leaves the
  // sides in one column pair (or two), where a side beside a strip of tape is still found. dof 6
  // also tries the pairs of peaks within the wider tilted tolerances: a larger tilt skews the
  // square out of the column pairs, and a far square's peaks can be truer to its skewed sides than
  // a column's strongest lines. Both searches' hypotheses compete.
  find_level_square_candidates(hough_, peaks_, {side_, side_tolerance, config_.angle_tolerance, exact}, candidates_);
  score_candidates(prior);
  if (dof_ == Dof::full6) {
    find_square_candidates(
        peaks_, {side_, config_.tilted_side_tolerance, config_.tilted_angle_tolerance, false}, candidates_);
    const SquareOutcome level_outcome = frame_.outcome;
    score_candidates(prior);
    if (frame_.passed.empty() && level_outcome != SquareOutcome::no_square) frame_.outcome = level_outcome;
  }
  // None passed: the refined hypotheses, strongest first, are refitted on the other ridges beside
  // their sides (a frame with a pose pays nothing for it).
  for (std::size_t f = 0; f < frame_.failed.size() && frame_.passed.empty(); ++f) {
    refit_on_other_ridges(frame_.failed[f], prior);
  }
}

// The best passed hypothesis, and the other squares that put the robot at the same pose: they are
// fused (one fit over all their corners). The best wins only when it is clearly better than the
// best hypothesis at another pose.
SquareDetection SquareDetector::choose() const {
  const auto& passed = frame_.passed;
  std::size_t best = 0;
  for (std::size_t k = 1; k < passed.size(); ++k) {
    if (passed[k].detection.confidence > passed[best].detection.confidence) best = k;
  }
  const SquareDetection& winner = passed[best].detection;
  std::array<IdentifiedSquare, kMaxSquaresInView> seen;
  std::size_t seen_count = 0;
  double rival = 0;
  for (std::size_t k = 0; k < passed.size(); ++k) {
    const SquareHypothesis& candidate = passed[k == 0 ? best : (k == best ? 0 : k)];  // the best first
    if (!same_pose(candidate.detection, winner)) {
      rival = std::max(rival, candidate.detection.confidence);
      continue;
    }
    const std::size_t square = candidate.square.square;
    const bool known = std::any_of(seen.begin(), seen.begin() + static_cast<std::ptrdiff_t>(seen_count),
                                   [&](const IdentifiedSquare& other) { return other.square == square; });
    if (!known && seen_count < seen.size()) seen[seen_count++] = candidate.square;
  }
  if (rival > 0 && winner.confidence < config_.clear_win_ratio * rival) {
    SquareDetection ambiguous;
    ambiguous.outcome = SquareOutcome::ambiguous;
    return ambiguous;
  }
  if (seen_count > 1) {
    SquareDetection fused = poser_.solve({seen.data(), seen_count}, winner);
    if (fused.found()) {
      fused.confidence = winner.confidence;
      return fused;
    }
  }
  return winner;
}

void SquareDetector::score_candidates(const RigidTransform* prior) {
  // Every hypothesis with at least half the votes of the strongest is scored against the whole
  // tape model (refined sides, dash patterns, the map's corners: the confidence), except a variant
  // of one that passed with a close fit (corner RMS within kCloseFitCornerRms of the check's limit):
  // two neighbouring lines within two tape widths of its refined sides (traces_corner). The
  // variants are its square with weaker or stray lines for a side (the wide tolerances of the
  // dof 6 peak search give several per frame), the same square through other lines (under dof 6
  // the skew can put its sides in two column pairs, each 2-4 degrees off a side), or a strip
  // beside a side, which would move the pose by less than same_pose tells apart. A loosely fitted
  // hypothesis may be the worse variant of a square, so the others are scored against it.
  const double tape_width = markers_.front().tape_width;
  const bool none_before = frame_.passed.empty();
  if (none_before) frame_.outcome = SquareOutcome::no_square;
  for (std::size_t c = 0; c < candidates_.size(); ++c) {
    if (2 * candidates_[c].votes < candidates_[0].votes) break;
    const bool variant = std::any_of(frame_.passed.begin(), frame_.passed.end(), [&](const SquareHypothesis& passed) {
      return passed.detection.corner_rms <= kCloseFitCornerRms * config_.max_corner_residual &&
             traces_corner(candidates_[c], passed.fit, 2 * tape_width);
    });
    if (variant) {
      ++frame_.merged;
      continue;
    }
    SquareFit fit;
    SquareOutcome outcome = SquareOutcome::sides_too_thin;
    const bool refined =
        refiner_.refine(tape_points_.all(), candidates_[c], tape_width, kRefinementPasses, min_side_points_, fit);
    if (refined) outcome = add_if_passed(fit, prior);
    if (c == 0 && none_before) frame_.outcome = outcome;
    if (refined && outcome != SquareOutcome::found) frame_.failed.push_back(fit);
  }
}

void SquareDetector::refit_on_other_ridges(const SquareFit& fit, const RigidTransform* prior) {
  // A strip of tape a few widths beside a side is a ridge of points of its own: the coarse line
  // may have been the strip's, or the refinement pulled by both may have settled between them.
  // Which ridge is the side is for the whole model to say (the other sides, the dash patterns,
  // the map's square at a pose): each choice is refined and evaluated as a hypothesis.
  const double tape_width = markers_.front().tape_width;
  const SquareRefiner::SideRidges ridges =
      SquareRefiner::side_ridges(tape_points_.all(), fit, tape_width, min_side_points_);
  std::array<std::size_t, kMaxRidgeSides> sides{};
  std::size_t ambiguous = 0;
  for (std::size_t k = 0; k < 4 && ambiguous < kMaxRidgeSides; ++k) {
    if (ridges.count[k] == 2) sides[ambiguous++] = k;
  }
  for (std::size_t choice = 0; choice < (std::size_t{1} << ambiguous) && frame_.ridge_refits_left > 0; ++choice) {
    SquareSides coarse;
    coarse.votes = 0;
    bool moved = false;
    for (std::size_t k = 0; k < 4; ++k) coarse.sides[k] = fit.sides[k].line;
    for (std::size_t a = 0; a < ambiguous; ++a) {
      const double offset = ridges.offsets[sides[a]][(choice >> a) & 1];
      coarse.sides[sides[a]].rho += offset;
      moved |= std::abs(offset) > tape_width / 2;
    }
    if (!moved) continue;  // the fit already tried
    --frame_.ridge_refits_left;
    SquareFit refit;
    if (!refiner_.refine(tape_points_.all(), coarse, tape_width, kRefinementPasses, min_side_points_, refit)) continue;
    add_if_passed(refit, prior);
  }
}

SquareOutcome SquareDetector::add_if_passed(const SquareFit& fit, const RigidTransform* prior) {
  SquareHypothesis hypothesis;
  hypothesis.fit = fit;
  const SquareOutcome outcome = evaluate(hypothesis, prior);
  if (outcome != SquareOutcome::found) return outcome;
  straighten_if_loose(hypothesis);
  frame_.passed.push_back(hypothesis);
  return outcome;
}

SquareOutcome SquareDetector::evaluate(SquareHypothesis& hypothesis, const RigidTransform* prior) {
  if (dof_ == Dof::full6) return evaluate_tilted(hypothesis, prior);
  // The points each side's dash pattern counts are among those the refinement gathered for it.
  const SidePoints sides{refiner_.near(0), refiner_.near(1), refiner_.near(2), refiner_.near(3)};
  return classify(hypothesis.fit.corners, sides, prior, hypothesis);
}

SquareOutcome SquareDetector::evaluate_tilted(SquareHypothesis& hypothesis, const RigidTransform* prior) {
  // The patterns are measured on the tape as a level camera would have seen it, levelled at the
  // hypothesis' own tilt (the 6-dof fit of its corners to the map's square). A hypothesis that
  // takes a strip for a side can fit a square at another tilt; read at that tilt, the true
  // square's dashes lose their phase. The tape is levelled again only when the tilt differs; a
  // hypothesis posed at another tilt than its probe's is measured again at that one.
  RollPitchYaw probed;
  if (!probe_tilt(hypothesis.fit.corners, probed)) return SquareOutcome::inconsistent;
  if (!levelled_.levelled_near(probed)) levelled_.level(probed, tape_points_.all());
  const SidePoints level{levelled_.points(), levelled_.points(), levelled_.points(), levelled_.points()};
  SquareOutcome outcome = classify(levelled_.levelled(hypothesis.fit.corners), level, prior, hypothesis);
  if (outcome == SquareOutcome::found) {
    const RollPitchYaw tilt = rpy_from_rotation(hypothesis.detection.world_from_base.rotation);
    if (!levelled_.levelled_near(tilt)) {
      levelled_.level(tilt, tape_points_.all());
      outcome = classify(levelled_.levelled(hypothesis.fit.corners), level, prior, hypothesis);
    }
  }
  return outcome;
}

void SquareDetector::straighten_if_loose(SquareHypothesis& hypothesis) {
  const SquareDetection& attempt = hypothesis.detection;
  if (attempt.corner_rms <= kCloseFitCornerRms * config_.max_corner_residual) return;  // a close fit already
  SquareFit straight = hypothesis.fit;
  if (!refiner_.straighten(markers_.front().tape_width, min_side_points_, straight)) return;
  const std::size_t member = hypothesis.square.square;
  const IdentifiedSquare square{member, order_corners(straight.corners, attempt.solid_side, map_turns_[member])};
  SquareDetection unposed = attempt;
  unposed.confidence = seen_fraction(attempt.patterns);  // as pose_options() left it for solve()
  const SquareDetection posed = poser_.solve({&square, 1}, unposed);
  if (!posed.found() || posed.corner_rms > kStraightCornerRms * attempt.corner_rms) return;
  hypothesis.fit = straight;
  hypothesis.square = square;
  hypothesis.detection = posed;
}

SquareOutcome SquareDetector::classify(const std::array<Eigen::Vector2d, 4>& measured, const SidePoints& points,
                                       const RigidTransform* prior, SquareHypothesis& hypothesis) {
  SquareOutcome why_not = SquareOutcome::solid_ambiguous;
  bool several_groups = false;
  const std::size_t options = pose_options(hypothesis.fit, measured, points, why_not, several_groups);
  if (options == 0) return why_not;
  if (several_groups) return SquareOutcome::unidentified;
  // Which square: with several in the map and a recent pose, the one (and only one) that puts the
  // robot near it; without a recent pose, the only square of its pattern.
  std::size_t chosen = options;
  if (markers_.size() > 1 && prior != nullptr) {
    for (std::size_t k = 0; k < options; ++k) {
      const Eigen::Vector3d offset = options_[k].detection.world_from_base.translation - prior->translation;
      if (offset.head<2>().norm() > config_.max_prior_distance) continue;
      if (chosen != options) return SquareOutcome::unidentified;  // two squares near the last pose
      chosen = k;
    }
  } else if (options == 1) {
    chosen = 0;
  }
  if (chosen == options) return SquareOutcome::unidentified;
  hypothesis.square = options_[chosen].square;
  hypothesis.detection = options_[chosen].detection;
  return SquareOutcome::found;
}

std::size_t SquareDetector::pose_options(const SquareFit& fit, const std::array<Eigen::Vector2d, 4>& measured,
                                         const SidePoints& points, SquareOutcome& why_not, bool& several_groups) {
  // The dash pattern under each of the map's patterns: exactly one side solid, the other three
  // dashed and in the pattern's phase from the map's start corners (solid_side_of); with several
  // patterns in the map only one pattern may match.
  std::size_t options = 0;
  const PatternGroup* matched_group = nullptr;
  // The dashes at the scale of the square on the table: under dof 4 the height is not known yet,
  // and the table's scale with it (a dash phase drifts by half a period along a side 5 % off).
  double scale = 1;
  if (dof_ == Dof::height4) {
    double perimeter = 0;
    for (std::size_t k = 0; k < 4; ++k) perimeter += (measured[k] - measured[(k + 3) % 4]).norm();
    scale = perimeter / (4 * side_);
  }
  for (const PatternGroup& group : groups_) {
    const DashGeometry geometry{group.geometry.tape_width * scale, group.geometry.dash * scale,
                                group.geometry.gap * scale};
    SquareDetection attempt;
    for (std::size_t k = 0; k < 4; ++k) {
      attempt.patterns[k] = measure_dash_pattern(points[k], measured[(k + 3) % 4], measured[k], geometry);
    }
    const double min_visible = seen_fraction(attempt.patterns);
    if (min_visible < config_.min_visible_fraction) {
      if (why_not == SquareOutcome::solid_ambiguous) why_not = SquareOutcome::side_hidden;
      continue;
    }
    attempt.confidence = min_visible;  // until solve()
    for (std::size_t member : group.members) {
      // Each side's phase read from its start corner: the measured order when it turns as the
      // map's corners do, else the other way round.
      const bool forward = (turn(measured[3], measured[0], measured[1]) > 0) == (map_turns_[member] > 0);
      bool out_of_phase = false;
      const int solid = solid_side_of(attempt.patterns, forward, config_, out_of_phase);
      if (solid < 0) {
        // Gaps as the pattern's but not its phase: another pattern, when the map has several.
        why_not = out_of_phase && groups_.size() > 1 ? SquareOutcome::unidentified : SquareOutcome::solid_ambiguous;
        continue;
      }
      attempt.solid_side = solid;
      const IdentifiedSquare square{member, order_corners(fit.corners, solid, map_turns_[member])};
      const SquareDetection posed = poser_.solve({&square, 1}, attempt);
      if (!posed.found()) {
        why_not = posed.outcome;
        continue;
      }
      several_groups |= matched_group != nullptr && matched_group != &group;
      matched_group = &group;
      options_[options++] = {square, posed};
    }
  }
  return options;
}

TapeMotionFit SquareDetector::fit_motion(const SquareDetection& detection, double line_time,
                                         const std::optional<MotionPrior>& prior) {
  if (!detection.found() || dof_ == Dof::full6) return {};
  std::array<std::array<Eigen::Vector2d, 4>, kMaxSquaresInView> squares;
  for (std::size_t seen = 0; seen < detection.square_count; ++seen) {
    const SquareMarker& marker = markers_[static_cast<std::size_t>(detection.squares[seen])];
    for (std::size_t k = 0; k < 4; ++k) squares[seen][k] = marker.corners[k].head<2>();
  }
  // The plane's metres at the fitted height, as solve() scales the corners.
  const double scale = (ceiling_z_ - detection.world_from_base.translation.z() - base_from_camera_.translation.z()) /
                       plane_.ceiling_above_camera();
  const SeenTape tape{tape_points_.all(), tape_points_.rows(), base_from_camera_.translation.head<2>(), scale};
  return motion_fitter_.fit(tape, {squares.data(), detection.square_count}, markers_.front().tape_width / 2,
                            line_time, detection.world_from_base, prior);
}

// The tilt, from the 6-dof fit of the quadrilateral to the first map square in any of its four
// turns (they differ by a quarter turn about the square's vertical axis: the same tilt). False
// when no fit.
bool SquareDetector::probe_tilt(const std::array<Eigen::Vector2d, 4>& corners, RollPitchYaw& tilt) const {
  const IdentifiedSquare probe{0, order_corners(corners, 0, map_turns_[0])};
  SquareDetection attempt;
  attempt.confidence = 1;
  const SquareDetection posed = poser_.solve({&probe, 1}, attempt);
  if (!posed.found()) return false;
  tilt = rpy_from_rotation(posed.world_from_base.rotation);
  return true;
}

}  // namespace irloc::square
