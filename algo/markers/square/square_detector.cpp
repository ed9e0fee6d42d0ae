#include "algo/markers/square/square_detector.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <variant>
#include <string>

#include "algo/geometry/planar_fit.hpp"
#include "algo/geometry/pose_solver.hpp"
#include "algo/markers/square/corner_order.hpp"
#include "algo/markers/square/square_search.hpp"

namespace irloc {
namespace {

// At most (SquareRefiner::refine): the wide passes end when the corners settle, usually after
// two; a coarse side a few degrees off (under dof 6, a skewed square's column pair) takes more.
constexpr int kRefinementPasses = 6;
// dof 6: a hypothesis whose fitted roll or pitch differs from the levelled view's by more than
// this is measured again at its own tilt (0.1 degrees: 0.2 degrees already decided between two
// hypotheses of one frame of the rendered tilting drive).
constexpr double kTiltAgreement = 0.00175;
constexpr std::size_t kMaxCorners = 4 * kMaxSquaresInView;
// A passed hypothesis fits closely when its corner RMS is at most this fraction of
// max_corner_residual (5 mm of 2 cm): its variants are merged into it, and its sides are not
// straightened (pose_on_straight_sides).
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

// How much of the square was seen: the smallest visible fraction of its four sides (the
// confidence before the fit's quality scales it).
double seen_fraction(const std::array<DashPattern, 4>& patterns) {
  double smallest = 1;
  for (const DashPattern& pattern : patterns) smallest = std::min(smallest, pattern.visible_fraction);
  return smallest;
}

double mean_side(const SquareMarker& marker) {
  double sum = 0;
  for (std::size_t k = 0; k < 4; ++k) sum += (marker.corners[(k + 1) % 4] - marker.corners[k]).norm();
  return sum / 4;
}

double ceiling_z_of(const SquareMarker& marker) {
  double sum = 0;
  for (const Eigen::Vector3d& corner : marker.corners) sum += corner.z() / 4;
  return sum;
}

// A level square, or std::invalid_argument naming the marker.
void check_square(const SquareMarker& marker) {
  const std::string name = "square marker '" + marker.name + "': ";
  const double side = mean_side(marker);
  const double z = ceiling_z_of(marker);
  for (std::size_t k = 0; k < 4; ++k) {
    const Eigen::Vector3d& a = marker.corners[k];
    const Eigen::Vector3d& b = marker.corners[(k + 1) % 4];
    const Eigen::Vector3d& c = marker.corners[(k + 2) % 4];
    if (std::abs(a.z() - z) > 0.01) throw std::invalid_argument(name + "corners are not level (z within 0.01 m)");
    if (std::abs((b - a).norm() - side) > 0.01 * side || std::abs((b - a).normalized().dot((c - b).normalized())) > 0.01) {
      throw std::invalid_argument(name + "corners are not a square (sides within 1 %, right angles)");
    }
  }
  if (side < 0.2) throw std::invalid_argument(name + "sides shorter than 0.2 m");
}

// The map's squares, each level and all alike in what the shared stages assume (side, tape
// width, ceiling height), their patterns equal or far enough apart; else std::invalid_argument.
std::vector<SquareMarker> checked(std::span<const SquareMarker> markers) {
  if (markers.empty()) throw std::invalid_argument("square path: the map has no square marker");
  const SquareMarker& first = markers.front();
  for (const SquareMarker& marker : markers) {
    check_square(marker);
    const std::string names = "square markers '" + first.name + "' and '" + marker.name + "': ";
    if (std::abs(mean_side(marker) - mean_side(first)) > 0.01 * mean_side(first)) {
      throw std::invalid_argument(names + "sides differ (the squares of one map share their side within 1 %)");
    }
    if (marker.tape_width != first.tape_width) throw std::invalid_argument(names + "tape widths differ");
    if (std::abs(ceiling_z_of(marker) - ceiling_z_of(first)) > 0.01) {
      throw std::invalid_argument(names + "ceiling heights differ (within 0.01 m)");
    }
    for (const SquareMarker& other : markers) {
      const bool same_pattern = marker.dash == other.dash && marker.gap == other.gap;
      const double ratio = (marker.dash + marker.gap) / (other.dash + other.gap);
      if (!same_pattern && std::max(ratio, 1 / ratio) < SquareDetector::kMinPeriodRatio - 1e-9) {
        throw std::invalid_argument("square markers '" + marker.name + "' and '" + other.name +
                                    "': dash patterns too alike to tell apart (equal, or dash + gap at least 1.5 times "
                                    "the other's)");
      }
    }
  }
  return {markers.begin(), markers.end()};
}

double ceiling_above_camera(const SquareMarker& marker, const RigidTransform& base_from_camera) {
  const double height = ceiling_z_of(marker) - base_from_camera.translation.z();
  if (!(height > 0.1)) throw std::invalid_argument("square marker '" + marker.name + "': not above the camera");
  return height;
}

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

// The solid side by the whole dash model, or -1 when not exactly one side reads solid and at
// least two others dashed (the fourth, crossed by clutter or mostly hidden, may read neither, but
// not solid). The solid side shows at most solid_max_gap_rate gaps per dash period, is
// covered along at least solid_min_fill of its visible length and keeps no dash phase; a dashed
// side shows at least dashed_min_gap_rate gaps per period and keeps the pattern's phase read from
// its start corner (forward: side k starts at corner k - 1) by at least min_dash_coherence. Far
// solid tape seen by few pixels has sampling holes that read as a few gaps, but no phase; a
// strip of clutter read as a side keeps no phase either. out_of_phase: the gaps alone would have
// classified the sides, the phases did not agree.
int solid_side_of(const std::array<DashPattern, 4>& patterns, bool forward, const SquareConfig& config,
                  bool& out_of_phase) {
  int solid = -1, by_gaps = -1;
  int dashed = 0, dashed_by_gaps = 0;
  for (int k = 0; k < 4; ++k) {
    const DashPattern& pattern = patterns[static_cast<std::size_t>(k)];
    const double phase = forward ? pattern.phase_from_start : pattern.phase_from_end;
    if (pattern.gap_rate <= config.solid_max_gap_rate && pattern.fill >= config.solid_min_fill) {
      by_gaps = by_gaps < 0 ? k : 4;  // 4: a second solid side
      if (phase < config.min_dash_coherence) solid = solid < 0 ? k : 4;
    } else if (pattern.gap_rate >= config.dashed_min_gap_rate) {
      ++dashed_by_gaps;
      if (phase >= config.min_dash_coherence) ++dashed;
    }
  }
  if (dashed >= 2 && solid >= 0 && solid < 4 && by_gaps == solid) return solid;
  out_of_phase = dashed_by_gaps == 3 && by_gaps >= 0 && by_gaps < 4;
  return -1;
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

std::string_view to_string(SquareOutcome outcome) {
  switch (outcome) {
    case SquareOutcome::found: return "found";
    case SquareOutcome::bad_frames: return "bad_frames";
    case SquareOutcome::no_square: return "no_square";
    case SquareOutcome::sides_too_thin: return "sides_too_thin";
    case SquareOutcome::side_hidden: return "side_hidden";
    case SquareOutcome::solid_ambiguous: return "solid_ambiguous";
    case SquareOutcome::inconsistent: return "inconsistent";
    case SquareOutcome::ambiguous: return "ambiguous";
    case SquareOutcome::unidentified: return "unidentified";
  }
  return "?";
}

SquareDetector::SquareDetector(const CameraIntrinsics& camera, int pixel_bits, const RigidTransform& base_from_camera,
                               Dof dof, std::span<const SquareMarker> markers, const SquareConfig& config)
    : config_(config),
      dof_(dof),
      markers_(checked(markers)),
      base_from_camera_(base_from_camera),
      side_(mean_side(markers_.front())),
      ceiling_z_(ceiling_z_of(markers_.front())),
      camera_(camera),
      plane_(camera_, base_from_camera, ceiling_above_camera(markers_.front(), base_from_camera), config.max_ray_angle),
      tape_mask_(mapped(plane_).x, mapped(plane_).y, mapped(plane_).width, mapped(plane_).height,
                 element_radius_for(plane_, markers_.front().tape_width), pixel_bits),
      tape_points_(plane_, markers_.front().tape_width / 2, kMaxTapePoints, TapePoints::kTapePatchCells,
                  base_from_camera.translation.head<2>()),
      refiner_(kMaxTapePoints),
      hough_(hough_config(plane_, markers_.front(), side_)) {
  element_radius_ = element_radius_for(plane_, markers_.front().tape_width);
  if (dof_ == Dof::full6) level_points_.resize(kMaxTapePoints);
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
  SquareDetection detection;
  detection.points = tape_points_.collect(mask, x0, y0, rows);
  view_levelled_ = false;
  ridge_refits_left_ = kMaxRidgeRefits;
  failed_count_ = 0;
  detection.hough = hough_.detect(tape_points_.vote_points(), peaks_);

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
  std::size_t found = score_candidates(prior, 0, detection);
  if (dof_ == Dof::full6) {
    find_square_candidates(
        peaks_, {side_, config_.tilted_side_tolerance, config_.tilted_angle_tolerance, false}, candidates_);
    const SquareOutcome level_outcome = detection.outcome;
    found = score_candidates(prior, found, detection);
    if (found == 0 && level_outcome != SquareOutcome::no_square) detection.outcome = level_outcome;
  }
  // None passed: the refined hypotheses, strongest first, are refitted on the other ridges beside
  // their sides (a frame with a pose pays nothing for it).
  for (std::size_t f = 0; f < failed_count_ && found == 0; ++f) {
    found = refit_on_other_ridges(failed_fits_[f], detection, prior, found);
  }
  detection.hypotheses_found = static_cast<std::uint32_t>(found);
  if (found == 0) return detection;
  // The best hypothesis, and the other squares that put the robot at the same pose: they are
  // fused (one fit over all their corners). The best wins only when it is clearly better than the
  // best hypothesis at another pose.
  std::size_t best = 0;
  for (std::size_t k = 1; k < found; ++k) {
    if (found_[k].confidence > found_[best].confidence) best = k;
  }
  std::array<IdentifiedSquare, kMaxSquaresInView> seen;
  std::size_t seen_count = 0;
  double rival = 0;
  for (std::size_t k = 0; k < found; ++k) {
    const std::size_t candidate = k == 0 ? best : (k == best ? 0 : k);  // the best first
    if (!same_pose(found_[candidate], found_[best])) {
      rival = std::max(rival, found_[candidate].confidence);
      continue;
    }
    const std::size_t square = identified_[candidate].square;
    const bool known = std::any_of(seen.begin(), seen.begin() + static_cast<std::ptrdiff_t>(seen_count),
                                   [&](const IdentifiedSquare& other) { return other.square == square; });
    if (!known && seen_count < seen.size()) seen[seen_count++] = identified_[candidate];
  }
  if (rival > 0 && found_[best].confidence < config_.clear_win_ratio * rival) {
    detection.outcome = SquareOutcome::ambiguous;
    return detection;
  }
  SquareDetection result = found_[best];
  if (seen_count > 1) {
    SquareDetection fused = solve({seen.data(), seen_count}, found_[best]);
    if (fused.found()) {
      fused.confidence = found_[best].confidence;
      result = fused;
    }
  }
  result.hypotheses_found = detection.hypotheses_found;
  result.hypotheses_merged = detection.hypotheses_merged;
  return result;
}

std::size_t SquareDetector::score_candidates(const RigidTransform* prior, std::size_t found, SquareDetection& detection) {
  if (found == 0) detection.outcome = SquareOutcome::no_square;
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
  const bool none_before = found == 0;
  for (std::size_t c = 0; c < candidates_.size(); ++c) {
    if (2 * candidates_[c].votes < candidates_[0].votes) break;
    bool variant = false;
    for (std::size_t k = 0; k < found && !variant; ++k) {
      variant = found_[k].corner_rms <= kCloseFitCornerRms * config_.max_corner_residual &&
                traces_corner(candidates_[c], found_fits_[k], 2 * tape_width);
    }
    if (variant) {
      ++detection.hypotheses_merged;
      continue;
    }
    SquareFit fit;
    SquareDetection attempt = detection;
    attempt.outcome = SquareOutcome::sides_too_thin;
    const bool refined =
        refiner_.refine(tape_points_.all(), candidates_[c], tape_width, kRefinementPasses, min_side_points_, fit);
    if (refined) attempt = evaluate(fit, detection, prior, identified_[found]);
    if (c == 0 && none_before) detection.outcome = attempt.outcome;
    if (refined && !attempt.found() && failed_count_ < failed_fits_.size()) failed_fits_[failed_count_++] = fit;
    if (!attempt.found()) continue;
    pose_on_straight_sides(fit, attempt, identified_[found]);
    found_fits_[found] = fit;
    found_[found++] = attempt;
  }
  return found;
}

std::size_t SquareDetector::refit_on_other_ridges(const SquareFit& fit, const SquareDetection& detection,
                                                  const RigidTransform* prior, std::size_t found) {
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
  for (std::size_t choice = 0; choice < (std::size_t{1} << ambiguous) && ridge_refits_left_ > 0; ++choice) {
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
    --ridge_refits_left_;
    SquareFit refit;
    if (!refiner_.refine(tape_points_.all(), coarse, tape_width, kRefinementPasses, min_side_points_, refit)) continue;
    SquareDetection attempt = evaluate(refit, detection, prior, identified_[found]);
    if (!attempt.found()) continue;
    pose_on_straight_sides(refit, attempt, identified_[found]);
    found_fits_[found] = refit;
    found_[found++] = attempt;
  }
  return found;
}

SquareDetection SquareDetector::evaluate(const SquareFit& fit, SquareDetection detection, const RigidTransform* prior,
                                         IdentifiedSquare& identified) {
  if (dof_ != Dof::full6) {
    // The points each side's dash pattern counts are among those the refinement gathered for it.
    const SidePoints sides{refiner_.near(0), refiner_.near(1), refiner_.near(2), refiner_.near(3)};
    return classify(fit, fit.corners, sides, detection, prior, identified);
  }
  // Tilted (dof 6): the patterns are measured on the tape as a level camera would have seen it,
  // levelled at the hypothesis' own tilt (the 6-dof fit of its corners to the map's square). A
  // hypothesis that takes a strip for a side can fit a square at another tilt; read at that tilt,
  // the true square's dashes lose their phase. The tape is levelled again only when the tilt
  // differs; a hypothesis posed at another tilt than its probe's is measured again at that one.
  RollPitchYaw probed;
  if (!probe_tilt(fit.corners, probed)) {
    detection.outcome = SquareOutcome::inconsistent;
    return detection;
  }
  if (!view_levelled_ || std::abs(probed.roll - view_tilt_.roll) > kTiltAgreement ||
      std::abs(probed.pitch - view_tilt_.pitch) > kTiltAgreement) {
    level_view(probed);
  }
  const SidePoints level{level_points(), level_points(), level_points(), level_points()};
  SquareDetection result = classify(fit, levelled(fit.corners), level, detection, prior, identified);
  if (result.found()) {
    const RollPitchYaw tilt = rpy_from_rotation(result.world_from_base.rotation);
    if (std::abs(tilt.roll - view_tilt_.roll) > kTiltAgreement || std::abs(tilt.pitch - view_tilt_.pitch) > kTiltAgreement) {
      level_view(tilt);
      result = classify(fit, levelled(fit.corners), level, detection, prior, identified);
    }
  }
  return result;
}

void SquareDetector::pose_on_straight_sides(SquareFit& fit, SquareDetection& attempt, IdentifiedSquare& identified) {
  if (attempt.corner_rms <= kCloseFitCornerRms * config_.max_corner_residual) return;  // a close fit already
  SquareFit straight = fit;
  if (!refiner_.straighten(markers_.front().tape_width, min_side_points_, straight)) return;
  const IdentifiedSquare square{identified.square,
                                order_corners(straight.corners, attempt.solid_side, map_turns_[identified.square])};
  SquareDetection unposed = attempt;
  unposed.confidence = seen_fraction(attempt.patterns);  // as classify() left it for solve()
  const SquareDetection posed = solve({&square, 1}, unposed);
  if (!posed.found() || posed.corner_rms > kStraightCornerRms * attempt.corner_rms) return;
  fit = straight;
  identified = square;
  attempt = posed;
}

SquareDetection SquareDetector::classify(const SquareFit& fit, const std::array<Eigen::Vector2d, 4>& measured,
                                         const SidePoints& points, const SquareDetection& detection,
                                         const RigidTransform* prior, IdentifiedSquare& identified) {
  // The dash pattern under each of the map's patterns: exactly one side solid, the other three
  // dashed and in the pattern's phase from the map's start corners (solid_side_of); with several
  // patterns in the map only one pattern may match.
  SquareDetection classified = detection;
  classified.outcome = SquareOutcome::solid_ambiguous;
  std::size_t options = 0;
  const PatternGroup* matched_group = nullptr;
  bool several_groups = false;
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
    SquareDetection attempt = detection;
    for (std::size_t k = 0; k < 4; ++k) {
      attempt.patterns[k] = measure_dash_pattern(points[k], measured[(k + 3) % 4], measured[k], geometry);
    }
    const double min_visible = seen_fraction(attempt.patterns);
    if (min_visible < config_.min_visible_fraction) {
      if (classified.outcome == SquareOutcome::solid_ambiguous) classified.outcome = SquareOutcome::side_hidden;
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
        classified.outcome = out_of_phase && groups_.size() > 1 ? SquareOutcome::unidentified
                                                                : SquareOutcome::solid_ambiguous;
        continue;
      }
      attempt.solid_side = solid;
      const std::array<Eigen::Vector2d, 4> corners = order_corners(fit.corners, solid, map_turns_[member]);
      const IdentifiedSquare square{member, corners};
      const SquareDetection posed = solve({&square, 1}, attempt);
      if (!posed.found()) {
        classified = posed;
        continue;
      }
      several_groups |= matched_group != nullptr && matched_group != &group;
      matched_group = &group;
      options_[options] = {square, posed};
      ++options;
    }
  }
  if (options == 0) return classified;
  classified.outcome = SquareOutcome::unidentified;
  if (several_groups) return classified;
  // Which square: with several in the map and a recent pose, the one (and only one) that puts the
  // robot near it; without a recent pose, the only square of its pattern.
  std::size_t chosen = options;
  if (markers_.size() > 1 && prior != nullptr) {
    for (std::size_t k = 0; k < options; ++k) {
      const Eigen::Vector3d offset = options_[k].detection.world_from_base.translation - prior->translation;
      if (offset.head<2>().norm() > config_.max_prior_distance) continue;
      if (chosen != options) return classified;  // two squares near the last pose
      chosen = k;
    }
  } else if (options == 1) {
    chosen = 0;
  }
  if (chosen == options) return classified;
  identified = options_[chosen].square;
  return options_[chosen].detection;
}

SquareDetection SquareDetector::solve(std::span<const IdentifiedSquare> seen, SquareDetection detection) const {
  // Pose from the corners' rays (plane points at the table's nominal height h0).
  const double h0 = plane_.ceiling_above_camera();
  const Eigen::Matrix3d camera_from_base = base_from_camera_.rotation.transpose();
  std::array<Eigen::Vector3d, kMaxCorners> bearings;
  std::array<Eigen::Vector3d, kMaxCorners> world;
  const std::size_t corners = 4 * seen.size();
  for (std::size_t k = 0; k < corners; ++k) {
    const Eigen::Vector2d& plane = seen[k / 4].corners[k % 4];
    bearings[k] = camera_from_base * Eigen::Vector3d(plane.x(), plane.y(), h0);
    world[k] = markers_[seen[k / 4].square].corners[k % 4];
  }
  if (dof_ == Dof::full6) return solve_tilted(seen, {world.data(), corners}, {bearings.data(), corners}, detection);
  if (!level_pose_from_ceiling({world.data(), corners}, {bearings.data(), corners}, ceiling_z_, base_from_camera_,
                               dof_, detection.world_from_base)) {
    detection.outcome = SquareOutcome::inconsistent;
    return detection;
  }
  // The measured corners, scaled to the found height and carried into W.
  const RigidTransform& pose = detection.world_from_base;
  const double scale = (ceiling_z_ - pose.translation.z() - base_from_camera_.translation.z()) / h0;
  const Eigen::Vector2d camera_xy = base_from_camera_.translation.head<2>();
  std::array<Eigen::Vector2d, kMaxCorners> corners_in_base, on_ceiling, pixels;
  for (std::size_t k = 0; k < corners; ++k) {
    corners_in_base[k] = camera_xy + scale * seen[k / 4].corners[k % 4];
    on_ceiling[k] = (pose * Eigen::Vector3d(corners_in_base[k].x(), corners_in_base[k].y(), 0)).head<2>();
    pixels[k] = Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
    camera_.project(bearings[k], pixels[k]);
  }
  // The covariance is that of the rigid fit of the corners.
  const Eigen::Matrix<double, 6, 6> unit_covariance = level_fit_covariance(
      {corners_in_base.data(), corners}, camera_xy, scale * h0, rpy_from_rotation(pose.rotation).yaw, 1.0, dof_);
  return finish_pose(seen, {on_ceiling.data(), corners}, {pixels.data(), corners}, unit_covariance, detection);
}

TapeMotionFit SquareDetector::fit_motion(const SquareDetection& detection, double line_time) {
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
                            line_time, detection.world_from_base);
}

// A tilting robot (dof 6): the square was found on the level table, where a few degrees of tilt
// only skew it a little; the pose is the full 6-dof fit of the corners' pixels (the dot path's
// solver: among the planar target's two poses the nearer to level). The checks are those of the
// level fit, on the corners' rays carried to the ceiling from the fitted pose.
SquareDetection SquareDetector::solve_tilted(std::span<const IdentifiedSquare> seen, std::span<const Eigen::Vector3d> world,
                                             std::span<const Eigen::Vector3d> bearings, SquareDetection detection) const {
  std::array<Eigen::Vector2d, kMaxCorners> pixels;
  const std::size_t corners = world.size();
  for (std::size_t k = 0; k < corners; ++k) {
    if (!camera_.project(bearings[k], pixels[k])) {
      detection.outcome = SquareOutcome::inconsistent;
      return detection;
    }
  }
  RefinementOptions options;
  options.dof = Dof::full6;
  options.loss = RobustLoss::none;  // four corners: nothing to outvote
  const PoseFit fit = estimate_pose(world, {pixels.data(), corners}, camera_, base_from_camera_, options);
  if (!fit.ok) {
    detection.outcome = SquareOutcome::inconsistent;
    return detection;
  }
  detection.world_from_base = fit.world_from_base;
  const RigidTransform world_from_camera = fit.world_from_base * base_from_camera_;
  std::array<Eigen::Vector2d, kMaxCorners> on_ceiling;
  for (std::size_t k = 0; k < corners; ++k) {
    const Eigen::Vector3d ray = world_from_camera.rotation * bearings[k];
    if (ray.z() <= 0) {
      detection.outcome = SquareOutcome::inconsistent;
      return detection;
    }
    on_ceiling[k] = (world_from_camera.translation + ray * ((ceiling_z_ - world_from_camera.translation.z()) / ray.z())).head<2>();
  }
  // The fit's covariance is for its assumed pixel sigma; per m^2 of corner noise on the ceiling it
  // is scaled by the pixels per metre at the ceiling's distance on the axis.
  const double pixels_per_metre = camera_.intrinsics().fx / plane_.ceiling_above_camera();
  const Eigen::Matrix<double, 6, 6> unit_covariance =
      fit.covariance * (pixels_per_metre * pixels_per_metre / (options.pixel_sigma * options.pixel_sigma));
  return finish_pose(seen, {on_ceiling.data(), corners}, {pixels.data(), corners}, unit_covariance, detection);
}

SquareDetection SquareDetector::finish_pose(std::span<const IdentifiedSquare> seen, std::span<const Eigen::Vector2d> on_ceiling,
                                            std::span<const Eigen::Vector2d> pixels,
                                            const Eigen::Matrix<double, 6, 6>& unit_covariance, SquareDetection detection) const {
  // Consistency: the measured corners against the map's, each side against d.
  const std::size_t corners = on_ceiling.size();
  double squared = 0;
  double worst_side_error = 0;
  for (std::size_t k = 0; k < corners; ++k) {
    const std::size_t next = 4 * (k / 4) + (k + 1) % 4;
    squared += (on_ceiling[k] - markers_[seen[k / 4].square].corners[k % 4].head<2>()).squaredNorm();
    worst_side_error = std::max(worst_side_error, std::abs((on_ceiling[next] - on_ceiling[k]).norm() - side_) / side_);
  }
  detection.corner_rms = std::sqrt(squared / static_cast<double>(corners));
  if (detection.corner_rms > config_.max_corner_residual || worst_side_error > config_.max_side_error) {
    detection.outcome = SquareOutcome::inconsistent;
    return detection;
  }
  // Confidence: how much of the square was seen (set by evaluate()), times how well it matches
  // the map.
  const double fit_quality = 1 - detection.corner_rms / config_.max_corner_residual;
  detection.confidence = std::clamp(detection.confidence * fit_quality, 0.0, 1.0);
  // Corner noise sigma ~ corner_rms * sqrt(4 / (4 - 3)) (three pose parameters from eight
  // numbers), at least 2 mm.
  const double corner_sigma = std::max(detection.corner_rms * 2.0, 0.002);
  detection.covariance = unit_covariance * (corner_sigma * corner_sigma);
  detection.square_count = seen.size();
  for (std::size_t k = 0; k < corners; ++k) {
    detection.squares[k / 4] = static_cast<int>(seen[k / 4].square);
    detection.corner_pixels[k / 4][k % 4] = pixels[k];
  }
  detection.outcome = SquareOutcome::found;
  return detection;
}

// The tilt, from the 6-dof fit of the quadrilateral to the first map square in any of its four
// turns (they differ by a quarter turn about the square's vertical axis: the same tilt). False
// when no fit.
bool SquareDetector::probe_tilt(const std::array<Eigen::Vector2d, 4>& corners, RollPitchYaw& tilt) const {
  const IdentifiedSquare probe{0, order_corners(corners, 0, map_turns_[0])};
  SquareDetection attempt;
  attempt.confidence = 1;
  const SquareDetection posed = solve({&probe, 1}, attempt);
  if (!posed.found()) return false;
  tilt = rpy_from_rotation(posed.world_from_base.rotation);
  return true;
}

// The frame's tape points as a level camera would have mapped them, at this tilt.
void SquareDetector::level_view(const RollPitchYaw& tilt) {
  view_tilt_ = tilt;
  level_from_base_ = rotation_from_rpy(tilt.roll, tilt.pitch, 0);
  const std::span<const Eigen::Vector2d> all = tape_points_.all();
  for (std::size_t k = 0; k < all.size(); ++k) level_points_[k] = levelled(all[k]);
  view_levelled_ = true;
}

Eigen::Vector2d SquareDetector::levelled(const Eigen::Vector2d& point) const {
  const double h0 = plane_.ceiling_above_camera();
  const Eigen::Vector3d ray = level_from_base_ * Eigen::Vector3d(point.x(), point.y(), h0);
  return ray.head<2>() * (h0 / ray.z());
}

std::array<Eigen::Vector2d, 4> SquareDetector::levelled(const std::array<Eigen::Vector2d, 4>& corners) const {
  std::array<Eigen::Vector2d, 4> level;
  for (std::size_t k = 0; k < 4; ++k) level[k] = levelled(corners[k]);
  return level;
}

}  // namespace irloc
