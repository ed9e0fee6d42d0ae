#include "algo/markers/square/side_refinement.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <optional>
#include <utility>

#include "algo/markers/square/ceiling_plane_map.hpp"

namespace irloc::square {
namespace {

// The wide-band passes end when no corner moves further than this (metres).
constexpr double kSettledCorner = 0.0005;

Eigen::Vector2d normal_of(const PlaneLine& line) { return {std::cos(line.theta), std::sin(line.theta)}; }

bool corners_of(const std::array<SideFit, 4>& sides, std::array<Eigen::Vector2d, 4>& corners) {
  for (std::size_t k = 0; k < 4; ++k) {
    if (!intersect(sides[k].line, sides[(k + 1) % 4].line, corners[k])) return false;
  }
  return true;
}

// The line n . p = rho with its normal evaluated once.
struct NormalForm {
  Eigen::Vector2d normal;
  double rho;
  explicit NormalForm(const PlaneLine& line) : normal(normal_of(line)), rho(line.rho) {}
  double distance(const Eigen::Vector2d& p) const { return normal.dot(p) - rho; }
};

// The four side lines of a fit, each with the sign of its normal toward the square's centre. A
// side's points lie at least a tape width inside both its neighbours (corner patches and the
// crossing tape left out).
struct FitLines {
  std::array<NormalForm, 4> lines;
  std::array<double, 4> inward{};
  explicit FitLines(const SquareFit& fit)
      : lines{NormalForm(fit.sides[0].line), NormalForm(fit.sides[1].line), NormalForm(fit.sides[2].line),
              NormalForm(fit.sides[3].line)} {
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();
    for (const Eigen::Vector2d& corner : fit.corners) centre += corner / 4.0;
    for (std::size_t k = 0; k < 4; ++k) inward[k] = lines[k].distance(centre) > 0 ? 1.0 : -1.0;
  }
  // Whether a point at these distances from the lines before and after side k lies between them.
  bool between_neighbours(std::size_t k, double from_before, double from_after, double tape_width) const {
    return inward[(k + 3) % 4] * from_before >= tape_width && inward[(k + 1) % 4] * from_after >= tape_width;
  }
};

// Total least squares over the points of side k; sums are taken relative to the current line's
// foot point so that they stay well conditioned.
bool refit_side(std::span<const Eigen::Vector2d> points, const SquareFit& current, const FitLines& current_lines,
                std::size_t k, double tape_width, double band, std::uint32_t min_inliers, SideFit& out) {
  const PlaneLine& current_line = current.sides[k].line;
  const NormalForm& line = current_lines.lines[k];
  const NormalForm& before = current_lines.lines[(k + 3) % 4];
  const NormalForm& after = current_lines.lines[(k + 1) % 4];
  const Eigen::Vector2d origin = line.normal * line.rho;

  std::uint32_t n = 0;
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  Eigen::Matrix2d sum_squares = Eigen::Matrix2d::Zero();
  for (const Eigen::Vector2d& p : points) {
    if (std::abs(line.distance(p)) > band) continue;
    if (!current_lines.between_neighbours(k, before.distance(p), after.distance(p), tape_width)) continue;
    const Eigen::Vector2d d = p - origin;
    ++n;
    sum += d;
    sum_squares += d * d.transpose();
  }
  if (n < std::max<std::uint32_t>(min_inliers, 2)) return false;
  const Eigen::Vector2d mean = sum / n;
  const Eigen::Matrix2d covariance = sum_squares / n - mean * mean.transpose();
  // The normal is the direction of least spread.
  const double major = 0.5 * std::atan2(2.0 * covariance(0, 1), covariance(0, 0) - covariance(1, 1));
  Eigen::Vector2d normal(-std::sin(major), std::cos(major));
  if (normal.dot(line.normal) < 0) normal = -normal;
  out.line.theta = std::atan2(normal.y(), normal.x());
  out.line.rho = normal.dot(origin + mean);
  out.line.votes = current_line.votes;
  out.inliers = n;
  out.rms = std::sqrt(std::max(0.0, normal.dot(covariance * normal)));
  return true;
}

// A side's stretch between its neighbours in kSegments segments, each with a profile of its points'
// offsets from the side's line in bins of an eighth of a tape width, out to kStraightReach tape
// widths either side: a tape-wide window centred within the final pass's band (3/4 tape width).
constexpr std::size_t kSegments = 16;
constexpr int kOffsetBinsPerWidth = 8;
constexpr double kStraightReach = 1.25;
constexpr int kOffsetBins = static_cast<int>(2 * kStraightReach * kOffsetBinsPerWidth);
// A segment's tape lies on a line when its centre is within this many tape widths of it.
constexpr double kOnLineWidths = 0.15;
// A side is refitted when another line carries at least 1/kMinStraightGain more of its points.
constexpr std::uint32_t kMinStraightGain = 16;

// Where the tape crosses one segment: the tape-wide window of its profile with the most points.
struct SegmentCentre {
  double t = 0;       // along the side, 0 at its start corner, 1 at its end
  double offset = 0;  // from the side's line, metres
  std::uint32_t points = 0;
};

// A side's frame for its segments: t along it from its start corner (0) to its end corner (1).
struct SideFrame {
  Eigen::Vector2d start;
  Eigen::Vector2d along;
  double length_squared = 0;

  SideFrame(std::size_t k, const SquareFit& fit)
      : start(fit.corners[(k + 3) % 4]), along(fit.corners[k] - start), length_squared(along.squaredNorm()) {}
  double t_of(const Eigen::Vector2d& p) const { return (p - start).dot(along) / length_squared; }
  std::size_t segment_of(double t) const {
    return std::min(kSegments - 1, static_cast<std::size_t>(std::max(0.0, t * kSegments)));
  }
};

// Per segment, the offset profile of side k's points: counts, and the sums of offset and t per bin.
struct SegmentProfiles {
  std::array<std::array<std::uint32_t, kOffsetBins>, kSegments> counts{};
  std::array<std::array<double, kOffsetBins>, kSegments> offset_sums{}, t_sums{};
};

void profile_segments(std::size_t k, const FitLines& lines, const SideFrame& side, std::span<const Eigen::Vector2d> near,
                      double tape_width, SegmentProfiles& profiles) {
  const NormalForm& line = lines.lines[k];
  const double bin = tape_width / kOffsetBinsPerWidth;
  const double reach = kStraightReach * tape_width;
  for (const Eigen::Vector2d& p : near) {
    const double offset = line.distance(p);
    if (std::abs(offset) >= reach) continue;
    const double from_before = lines.lines[(k + 3) % 4].distance(p), from_after = lines.lines[(k + 1) % 4].distance(p);
    if (!lines.between_neighbours(k, from_before, from_after, tape_width)) continue;
    const double t = side.t_of(p);
    const std::size_t segment = side.segment_of(t);
    const auto b = static_cast<std::size_t>(std::clamp(static_cast<int>((offset + reach) / bin), 0, kOffsetBins - 1));
    ++profiles.counts[segment][b];
    profiles.offset_sums[segment][b] += offset;
    profiles.t_sums[segment][b] += t;
  }
}

// Each segment's centre (no points: none); total: the points of all of them.
std::array<SegmentCentre, kSegments> segment_centres(const SegmentProfiles& profiles, std::uint32_t& total) {
  std::array<SegmentCentre, kSegments> centres{};
  total = 0;
  for (std::size_t s = 0; s < kSegments; ++s) {
    std::uint32_t window = 0, best = 0;
    std::size_t best_end = 0;
    for (std::size_t b = 0; b < kOffsetBins; ++b) {
      window += profiles.counts[s][b];
      if (b >= kOffsetBinsPerWidth) window -= profiles.counts[s][b - kOffsetBinsPerWidth];
      if (window > best) best = window, best_end = b;
    }
    if (best == 0) continue;
    double offset_sum = 0, t_sum = 0;
    for (std::size_t b = best_end + 1 - std::min<std::size_t>(best_end + 1, kOffsetBinsPerWidth); b <= best_end; ++b) {
      offset_sum += profiles.offset_sums[s][b];
      t_sum += profiles.t_sums[s][b];
    }
    centres[s] = {t_sum / best, offset_sum / best, best};
    total += best;
  }
  return centres;
}

// A line in (t, offset); a segment lies on it when its centre is within `within` of it.
struct SegmentLine {
  double at_start = 0, slope = 0;  // offset = at_start + slope * t
  bool holds(const SegmentCentre& centre, double within) const {
    return centre.points > 0 && std::abs(centre.offset - at_start - slope * centre.t) <= within;
  }
};

// Of the lines through two segments' centres, the one that most of the side's points agree with,
// if it carries most of them and enough more than the side's line (offset 0) does.
std::optional<SegmentLine> straightest_line(const std::array<SegmentCentre, kSegments>& centres, std::uint32_t total,
                                            double on_line) {
  const auto support = [&](const SegmentLine& segment_line) {
    std::uint32_t sum = 0;
    for (const SegmentCentre& centre : centres) sum += segment_line.holds(centre, on_line) ? centre.points : 0;
    return sum;
  };
  const std::uint32_t current = support({});
  if (current == total) return std::nullopt;
  std::uint32_t best = current;
  std::optional<SegmentLine> straight;
  for (std::size_t i = 0; i < kSegments; ++i) {
    for (std::size_t j = i + 1; j < kSegments; ++j) {
      if (centres[i].points == 0 || centres[j].points == 0) continue;
      const double slope = (centres[j].offset - centres[i].offset) / (centres[j].t - centres[i].t);
      const SegmentLine candidate{centres[i].offset - slope * centres[i].t, slope};
      const std::uint32_t agree = support(candidate);
      if (agree > best) best = agree, straight = candidate;
    }
  }
  if (!straight || 2 * best <= total || kMinStraightGain * (best - current) < total) return std::nullopt;
  return straight;
}

// Side k of fit straightened (SquareRefiner::straighten) on near, its gathered points; kept: scratch
// for as many points. false: the side stays.
bool straighten_side(std::size_t k, const SquareFit& fit, const FitLines& lines, std::span<const Eigen::Vector2d> near,
                     std::span<Eigen::Vector2d> kept, double tape_width, std::uint32_t min_inliers, SideFit& out) {
  const NormalForm& line = lines.lines[k];
  const SideFrame side(k, fit);
  SegmentProfiles profiles;
  profile_segments(k, lines, side, near, tape_width, profiles);
  std::uint32_t total = 0;
  const std::array<SegmentCentre, kSegments> centres = segment_centres(profiles, total);
  const double on_line = kOnLineWidths * tape_width;
  const std::optional<SegmentLine> straight = straightest_line(centres, total, on_line);
  if (!straight) return false;
  // Refit on the points of the segments on that line, from that line.
  const Eigen::Vector2d a = side.start + straight->at_start * line.normal;
  const Eigen::Vector2d direction = (side.along + straight->slope * line.normal).normalized();
  Eigen::Vector2d normal(-direction.y(), direction.x());
  if (normal.dot(line.normal) < 0) normal = -normal;
  SquareFit guess = fit;
  guess.sides[k].line.theta = std::atan2(normal.y(), normal.x());
  guess.sides[k].line.rho = normal.dot(a);
  std::size_t count = 0;
  for (const Eigen::Vector2d& p : near) {
    if (straight->holds(centres[side.segment_of(side.t_of(p))], on_line)) kept[count++] = p;
  }
  return refit_side(kept.first(count), guess, FitLines(guess), k, tape_width, 0.75 * tape_width, min_inliers, out);
}

// Profiles of tape points' distances from a side's line, in bins of a quarter tape width, out to
// kRidgeWidths tape widths either side.
constexpr int kRidgeBinsPerWidth = 4;
constexpr int kRidgeBins = 2 * static_cast<int>(SquareRefiner::kRidgeWidths) * kRidgeBinsPerWidth;
struct OffsetProfile {
  std::array<std::uint32_t, kRidgeBins> counts{};
  std::array<double, kRidgeBins> offset_sums{};
};

// The bins within half a tape width of bin b.
int ridge_lo(int b) { return std::max(0, b - kRidgeBinsPerWidth / 2); }
int ridge_hi(int b) { return std::min(kRidgeBins - 1, b + kRidgeBinsPerWidth / 2); }

// The strongest ridge's bin (-1: none) and the second's, a crest apart from it by a valley.
std::array<int, 2> strongest_ridges(const OffsetProfile& profile) {
  const auto& counts = profile.counts;
  // A ridge's strength: its points within half a tape width of the bin (a tape's width).
  std::array<std::uint32_t, kRidgeBins> strength{};
  for (int b = 0; b < kRidgeBins; ++b) {
    for (int j = ridge_lo(b); j <= ridge_hi(b); ++j) strength[static_cast<std::size_t>(b)] += counts[static_cast<std::size_t>(j)];
  }
  const auto at = [&](int b) { return strength[static_cast<std::size_t>(b)]; };
  int first = 0;
  for (int b = 1; b < kRidgeBins; ++b) {
    if (at(b) > at(first)) first = b;
  }
  if (at(first) == 0) return {-1, -1};
  int second = -1;
  for (int b = 0; b < kRidgeBins; ++b) {
    if (std::abs(b - first) < 3 * kRidgeBinsPerWidth / 2) continue;
    if ((b > 0 && at(b - 1) > at(b)) || (b + 1 < kRidgeBins && at(b + 1) > at(b))) continue;  // not a crest
    // The valley, in the profile itself: tape and a strip 2-3 cm apart are one ridge at the
    // strength's width.
    std::uint32_t valley = counts[static_cast<std::size_t>(b)], crest = 0;
    for (int j = std::min(b, first); j <= std::max(b, first); ++j) valley = std::min(valley, counts[static_cast<std::size_t>(j)]);
    for (int j = ridge_lo(b); j <= ridge_hi(b); ++j) crest = std::max(crest, counts[static_cast<std::size_t>(j)]);
    if (2 * valley >= crest) continue;
    if (second < 0 || at(b) > at(second)) second = b;
  }
  return {first, second};
}

// A ridge's points within half a tape width of its crest, and their mean distance.
std::uint32_t ridge_points(const OffsetProfile& profile, int crest) {
  std::uint32_t n = 0;
  for (int j = ridge_lo(crest); j <= ridge_hi(crest); ++j) n += profile.counts[static_cast<std::size_t>(j)];
  return n;
}
double ridge_offset(const OffsetProfile& profile, int crest) {
  double sum = 0;
  for (int j = ridge_lo(crest); j <= ridge_hi(crest); ++j) sum += profile.offset_sums[static_cast<std::size_t>(j)];
  return sum / ridge_points(profile, crest);
}

}  // namespace

SquareRefiner::SideRidges SquareRefiner::side_ridges(std::span<const Eigen::Vector2d> points, const SquareFit& fit,
                                                     double tape_width, std::uint32_t min_points) {
  const double bin = tape_width / kRidgeBinsPerWidth;
  const double reach = kRidgeWidths * tape_width;
  std::array<OffsetProfile, 4> profiles{};
  const FitLines fit_lines(fit);
  for (const Eigen::Vector2d& p : points) {
    std::array<double, 4> distance{};
    for (std::size_t k = 0; k < 4; ++k) distance[k] = fit_lines.lines[k].distance(p);
    for (std::size_t k = 0; k < 4; ++k) {
      if (std::abs(distance[k]) >= reach) continue;
      if (!fit_lines.between_neighbours(k, distance[(k + 3) % 4], distance[(k + 1) % 4], tape_width)) continue;
      const auto b = static_cast<std::size_t>(std::clamp(static_cast<int>(std::floor((distance[k] + reach) / bin)), 0, kRidgeBins - 1));
      ++profiles[k].counts[b];
      profiles[k].offset_sums[b] += distance[k];
    }
  }
  SideRidges ridges;
  for (std::size_t k = 0; k < 4; ++k) {
    const auto [first, second] = strongest_ridges(profiles[k]);
    if (first < 0) continue;
    ridges.offsets[k][0] = ridge_offset(profiles[k], first);
    ridges.count[k] = 1;
    // The second ridge's strength, as the first's: its points within half a tape width.
    if (second >= 0 && ridge_points(profiles[k], second) >= std::max(min_points, ridge_points(profiles[k], first) / 8)) {
      ridges.offsets[k][1] = ridge_offset(profiles[k], second);
      ridges.count[k] = 2;
    }
  }
  return ridges;
}

bool traces_corner(const SquareSides& coarse, const SquareFit& fit, double distance) {
  std::array<bool, 4> traces{};
  for (std::size_t j = 0; j < 4; ++j) {
    const NormalForm line(coarse.sides[j]);
    for (std::size_t k = 0; k < 4 && !traces[j]; ++k) {
      traces[j] = std::abs(line.distance(fit.corners[(k + 3) % 4])) <= distance &&
                  std::abs(line.distance(fit.corners[k])) <= distance;
    }
  }
  for (std::size_t j = 0; j < 4; ++j) {
    if (traces[j] && traces[(j + 1) % 4]) return true;
  }
  return false;
}

bool intersect(const PlaneLine& a, const PlaneLine& b, Eigen::Vector2d& point) {
  Eigen::Matrix2d normals;
  normals.row(0) = normal_of(a).transpose();
  normals.row(1) = normal_of(b).transpose();
  const double determinant = normals.determinant();
  if (std::abs(determinant) < 0.1) return false;  // closer than ~6 degrees to parallel
  point = normals.inverse() * Eigen::Vector2d(a.rho, b.rho);
  return true;
}

SquareRefiner::SquareRefiner(std::size_t capacity) : kept_(capacity) {
  for (std::vector<Eigen::Vector2d>& near : near_) near.resize(capacity);
  for (std::vector<Eigen::Vector2d>& sample : samples_) sample.resize(kWidePassPoints);
}

bool SquareRefiner::refine(std::span<const Eigen::Vector2d> points, const SquareSides& coarse, double tape_width,
                           int iterations, std::uint32_t min_inliers, SquareFit& fit) {
  for (std::size_t k = 0; k < 4; ++k) fit.sides[k] = {coarse.sides[k], 0, 0};
  if (!corners_of(fit.sides, fit.corners)) return false;
  assert(points.size() <= near_[0].size());
  const std::array<NormalForm, 4> lines{NormalForm(coarse.sides[0]), NormalForm(coarse.sides[1]),
                                        NormalForm(coarse.sides[2]), NormalForm(coarse.sides[3])};
  near_count_.fill(0);
  const double gather = kGatherWidths * tape_width;
  // Only points within the gather width of the coarse square can lie between a side's neighbours
  // (the passes move a line at most two tape widths): the tape of other squares on the same lines
  // is not gathered.
  Eigen::Vector2d low = fit.corners[0], high = fit.corners[0];
  for (const Eigen::Vector2d& corner : fit.corners) {
    low = low.cwiseMin(corner);
    high = high.cwiseMax(corner);
  }
  low.array() -= gather;
  high.array() += gather;
  for (const Eigen::Vector2d& p : points) {
    if (p.x() < low.x() || p.y() < low.y() || p.x() > high.x() || p.y() > high.y()) continue;
    for (std::size_t k = 0; k < 4; ++k) {
      if (std::abs(lines[k].distance(p)) <= gather) near_[k][near_count_[k]++] = p;
    }
  }
  // The wide passes only bring the lines to the tape: every stride-th point of a side will do.
  std::array<std::size_t, 4> sample_count{};
  std::array<std::uint32_t, 4> sample_min_inliers{};
  for (std::size_t k = 0; k < 4; ++k) {
    if (near_count_[k] < std::max<std::uint32_t>(min_inliers, 2)) return false;
    const std::size_t stride = (near_count_[k] + kWidePassPoints - 1) / kWidePassPoints;
    for (std::size_t i = 0; i < near_count_[k]; i += stride) samples_[k][sample_count[k]++] = near_[k][i];
    sample_min_inliers[k] = static_cast<std::uint32_t>((min_inliers + stride - 1) / stride);
  }
  // The coarse line may be half a Hough bin and some degrees off: the passes take a tape width
  // either side until the corners settle; the last, on a converged line, three quarters of it, so
  // that clutter beside the tape (a strip a few centimetres off) does not pull the line.
  for (int pass = 0; pass < iterations; ++pass) {
    const bool last = pass + 1 == iterations;
    const double band = last ? 0.75 * tape_width : tape_width;
    std::array<SideFit, 4> refined;
    const FitLines current_lines(fit);
    for (std::size_t k = 0; k < 4; ++k) {
      const std::span<const Eigen::Vector2d> side = last ? std::span<const Eigen::Vector2d>(near_[k].data(), near_count_[k])
                                                         : std::span<const Eigen::Vector2d>(samples_[k].data(), sample_count[k]);
      if (!refit_side(side, fit, current_lines, k, tape_width, band, last ? min_inliers : sample_min_inliers[k], refined[k])) {
        return false;
      }
    }
    const std::array<Eigen::Vector2d, 4> before = fit.corners;
    fit.sides = refined;
    if (!corners_of(fit.sides, fit.corners)) return false;
    if (last) break;
    double moved = 0;
    for (std::size_t k = 0; k < 4; ++k) moved = std::max(moved, (fit.corners[k] - before[k]).norm());
    if (pass > 0 && moved < kSettledCorner) pass = iterations - 2;  // settled: the last pass next
  }
  return true;
}

bool SquareRefiner::straighten(double tape_width, std::uint32_t min_inliers, SquareFit& fit) {
  std::array<SideFit, 4> straightened = fit.sides;
  bool moved = false;
  const FitLines lines(fit);
  for (std::size_t k = 0; k < 4; ++k) {
    moved |= straighten_side(k, fit, lines, near(k), kept_, tape_width, min_inliers, straightened[k]);
  }
  if (!moved) return false;
  SquareFit result = fit;
  result.sides = straightened;
  if (!corners_of(result.sides, result.corners)) return false;
  fit = result;
  return true;
}


}  // namespace irloc::square
