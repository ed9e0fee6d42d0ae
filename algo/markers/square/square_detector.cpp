#include "algo/markers/square/square_detector.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <variant>
#include <string>

#include "algo/geometry/planar_fit.hpp"
#include "algo/markers/square/corner_order.hpp"
#include "algo/markers/square/square_search.hpp"

namespace irloc {
namespace {

constexpr int kRefinementPasses = 3;
// Capacity of the tape point buffers; the Hough vote takes fewer than 2^16 points.
constexpr std::size_t kMaxTapePoints = 65535;

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
const SquareMarker& checked(const SquareMarker& marker, Dof dof) {
  const std::string name = "square marker '" + marker.name + "': ";
  if (dof == Dof::full6) throw std::invalid_argument(name + "the square path needs a level robot (robot.dof 3 or 4)");
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
  return marker;
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
  config.inlier_distance = static_cast<std::int32_t>(std::lround(marker.tape_width / 2 * kPlaneRawPerMetre));
  return config;
}

// Two hypotheses that put the robot at the same pose (within 5 cm and 2 degrees) are one.
bool same_pose(const SquareDetection& a, const SquareDetection& b) {
  const RigidTransform& p = a.world_from_base;
  const RigidTransform& q = b.world_from_base;
  const double turn = std::abs(wrap_angle(rpy_from_rotation(p.rotation).yaw - rpy_from_rotation(q.rotation).yaw));
  return (p.translation - q.translation).norm() < 0.05 && turn < 0.035;
}

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
  }
  return "?";
}

SquareDetector::SquareDetector(const CameraIntrinsics& camera, int pixel_bits, const RigidTransform& base_from_camera,
                               Dof dof, const SquareMarker& marker, const SquareConfig& config)
    : config_(config),
      dof_(dof),
      marker_(checked(marker, dof)),
      base_from_camera_(base_from_camera),
      side_(mean_side(marker)),
      ceiling_z_(ceiling_z_of(marker)),
      map_turn_(turn(marker.corners[0].head<2>(), marker.corners[1].head<2>(), marker.corners[2].head<2>())),
      camera_(camera),
      plane_(camera_, base_from_camera, ceiling_above_camera(marker, base_from_camera), config.max_ray_angle),
      tape_mask_(mapped(plane_).x, mapped(plane_).y, mapped(plane_).width, mapped(plane_).height,
                 element_radius_for(plane_, marker.tape_width), pixel_bits),
      tape_points_(plane_, marker.tape_width / 2, kMaxTapePoints),
      hough_(hough_config(plane_, marker, side_)) {
  element_radius_ = element_radius_for(plane_, marker.tape_width);
  // A side needs at least as many tape pixels as a Hough peak needs grid cells.
  min_side_points_ = hough_config(plane_, marker, side_).min_votes;
}

SquareDetection SquareDetector::detect(const GrayImageView& on, const GrayImageView& off, const DifferenceNoise& noise) {
  const int width = camera_.intrinsics().width;
  const int height = camera_.intrinsics().height;
  if (on.index() != off.index() || std::holds_alternative<ImageView16>(on) != tape_mask_.wide() ||
      width_of(on) != width || height_of(on) != height || width_of(off) != width || height_of(off) != height) {
    SquareDetection refused;
    refused.outcome = SquareOutcome::bad_frames;
    return refused;
  }
  const std::uint16_t threshold = config_.threshold > 0 ? config_.threshold : tape_threshold(noise);
  tape_mask_.extract(on, off, threshold);
  SquareDetection detection = detect_in_mask(tape_mask_.mask(), tape_mask_.x(), tape_mask_.y());
  detection.threshold = threshold;
  return detection;
}

SquareDetection SquareDetector::detect_in_mask(ImageView8 mask, int x0, int y0) {
  SquareDetection detection;
  detection.points = tape_points_.collect(mask, x0, y0);
  detection.hough = hough_.detect(tape_points_.vote_points(), peaks_);

  const SquareSearchParams search{side_, config_.side_tolerance, config_.angle_tolerance};
  find_square_candidates(peaks_, search, candidates_);
  if (candidates_.empty()) {
    detection.outcome = SquareOutcome::no_square;
    return detection;
  }
  // Every hypothesis with at least half the votes of the strongest is scored against the whole
  // tape model (refined sides, dash patterns, the map's corners: the confidence); the best wins
  // only when it is clearly better than the best hypothesis at another pose.
  std::optional<SquareDetection> best, rival;
  SquareOutcome strongest_outcome = SquareOutcome::no_square;
  for (std::size_t c = 0; c < candidates_.size(); ++c) {
    if (2 * candidates_[c].votes < candidates_[0].votes) break;
    const SquareDetection attempt = evaluate(candidates_[c], detection);
    if (c == 0) strongest_outcome = attempt.outcome;
    if (!attempt.found()) continue;
    ++detection.hypotheses_found;
    const auto keep_rival = [&](const SquareDetection& other) {
      if (!rival || other.confidence > rival->confidence) rival = other;
    };
    if (!best) {
      best = attempt;
    } else if (attempt.confidence > best->confidence) {
      if (!same_pose(*best, attempt)) keep_rival(*best);
      best = attempt;
    } else if (!same_pose(*best, attempt)) {
      keep_rival(attempt);
    }
  }
  if (!best) {
    detection.outcome = strongest_outcome;
    return detection;
  }
  if (rival && best->confidence < config_.clear_win_ratio * rival->confidence) {
    detection.outcome = SquareOutcome::ambiguous;
    return detection;
  }
  best->hypotheses_found = detection.hypotheses_found;
  return *best;
}

SquareDetection SquareDetector::evaluate(const SquareSides& sides, SquareDetection detection) const {
  SquareFit fit;
  if (!refine_square(tape_points_.all(), sides, marker_.tape_width, kRefinementPasses, min_side_points_, fit)) {
    detection.outcome = SquareOutcome::sides_too_thin;
    return detection;
  }
  return solve(fit, detection);
}

SquareDetection SquareDetector::solve(const SquareFit& fit, SquareDetection detection) const {
  const DashGeometry dashes{marker_.tape_width, marker_.dash, marker_.gap};
  double min_visible = 1;
  for (std::size_t k = 0; k < 4; ++k) {
    detection.patterns[k] = measure_dash_pattern(tape_points_.all(), fit.corners[(k + 3) % 4], fit.corners[k], dashes);
    min_visible = std::min(min_visible, detection.patterns[k].visible_fraction);
  }
  if (min_visible < config_.min_visible_fraction) {
    detection.outcome = SquareOutcome::side_hidden;
    return detection;
  }
  // Exactly one side solid, the other three clearly dashed.
  int solid = -1;
  int dashed = 0;
  for (int k = 0; k < 4; ++k) {
    const DashPattern& pattern = detection.patterns[static_cast<std::size_t>(k)];
    if (pattern.gap_rate <= config_.solid_max_gap_rate && pattern.fill >= config_.solid_min_fill) {
      solid = solid < 0 ? k : 4;  // 4: a second solid side
    } else if (pattern.gap_rate >= config_.dashed_min_gap_rate) {
      ++dashed;
    }
  }
  if (dashed != 3) solid = -1;
  if (solid < 0 || solid > 3) {
    detection.outcome = SquareOutcome::solid_ambiguous;
    return detection;
  }
  detection.solid_side = solid;
  const std::array<Eigen::Vector2d, 4> corners = order_corners(fit.corners, solid, map_turn_);

  // Pose from the corners' rays (plane points at the table's nominal height h0).
  const double h0 = plane_.ceiling_above_camera();
  const Eigen::Matrix3d camera_from_base = base_from_camera_.rotation.transpose();
  std::array<Eigen::Vector3d, 4> bearings;
  std::array<Eigen::Vector3d, 4> world;
  for (std::size_t k = 0; k < 4; ++k) {
    bearings[k] = camera_from_base * Eigen::Vector3d(corners[k].x(), corners[k].y(), h0);
    world[k] = marker_.corners[k];
  }
  if (!level_pose_from_ceiling(world, bearings, ceiling_z_, base_from_camera_, dof_, detection.world_from_base)) {
    detection.outcome = SquareOutcome::inconsistent;
    return detection;
  }
  // Consistency: the measured corners, scaled to the found height and carried into W, against
  // the map; each refined side against d.
  const RigidTransform& pose = detection.world_from_base;
  const double scale = (ceiling_z_ - pose.translation.z() - base_from_camera_.translation.z()) / h0;
  const Eigen::Vector2d camera_xy = base_from_camera_.translation.head<2>();
  double squared = 0;
  double worst_side_error = 0;
  std::array<Eigen::Vector2d, 4> corners_in_base;
  for (std::size_t k = 0; k < 4; ++k) {
    const Eigen::Vector2d base_xy = camera_xy + scale * corners[k];
    corners_in_base[k] = base_xy;
    const Eigen::Vector3d in_world = pose * Eigen::Vector3d(base_xy.x(), base_xy.y(), 0);
    squared += (in_world.head<2>() - world[k].head<2>()).squaredNorm();
    const double length = scale * (corners[(k + 1) % 4] - corners[k]).norm();
    worst_side_error = std::max(worst_side_error, std::abs(length - side_) / side_);
  }
  detection.corner_rms = std::sqrt(squared / 4);
  if (detection.corner_rms > config_.max_corner_residual || worst_side_error > config_.max_side_error) {
    detection.outcome = SquareOutcome::inconsistent;
    return detection;
  }

  // Confidence: how much of the square was seen, times how well it matches the map.
  const double fit_quality = 1 - detection.corner_rms / config_.max_corner_residual;
  detection.confidence = std::clamp(min_visible * fit_quality, 0.0, 1.0);
  // Corner noise sigma ~ corner_rms * sqrt(4 / (4 - 3)) (three pose parameters from eight
  // numbers), at least 2 mm; the covariance is that of the rigid fit of the four corners.
  const double corner_sigma = std::max(detection.corner_rms * 2.0, 0.002);
  detection.covariance = level_fit_covariance(corners_in_base, camera_xy, scale * h0,
                                             rpy_from_rotation(pose.rotation).yaw, corner_sigma, dof_);
  for (std::size_t k = 0; k < 4; ++k) {
    detection.corner_pixels[k] = Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
    camera_.project(bearings[k], detection.corner_pixels[k]);
  }
  detection.outcome = SquareOutcome::found;
  return detection;
}

}  // namespace irloc
