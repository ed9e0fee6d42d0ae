#include "algo/markers/square/square_search.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "algo/core/static_vector.hpp"
#include "algo/markers/square/ceiling_plane_map.hpp"

namespace irloc::square {
namespace {

struct ParallelPair {
  std::size_t first = 0, second = 0;
};

// Angle between two line directions, in [0, pi/2].
double line_angle(double theta_a, double theta_b) {
  const double difference = std::fmod(std::abs(theta_a - theta_b), std::numbers::pi);
  return std::min(difference, std::numbers::pi - difference);
}

// Distance between two (nearly) parallel lines given in Hough form with theta in [0, pi).
double parallel_distance(const HoughLine& a, const HoughLine& b) {
  const bool flipped = std::abs(a.theta - b.theta) > std::numbers::pi / 2;  // b is a's normal reversed
  return std::abs(flipped ? a.rho + b.rho : a.rho - b.rho) / kPlaneUnitsPerMetre;
}

PlaneLine plane_line(const HoughLine& line) {
  return {line.theta, line.rho / kPlaneUnitsPerMetre, line.votes};
}

// Whether two lines (theta in [0, pi)) are one: within 2 degrees and 5 cm (either normal).
bool same_line(const PlaneLine& a, const PlaneLine& b) {
  constexpr double kAngle = 2 * std::numbers::pi / 180, kDistance = 0.05;
  const double turn = std::abs(a.theta - b.theta);
  if (turn <= kAngle) return std::abs(a.rho - b.rho) <= kDistance;
  return turn >= std::numbers::pi - kAngle && std::abs(a.rho + b.rho) <= kDistance;
}

// Whether two hypotheses have the same four lines (in any order).
bool same_square(const SquareSides& a, const SquareSides& b) {
  return std::all_of(a.sides.begin(), a.sides.end(), [&](const PlaneLine& line) {
    return std::any_of(b.sides.begin(), b.sides.end(), [&](const PlaneLine& other) { return same_line(line, other); });
  });
}

// Inserts into the list kept sorted by votes, most first; the weakest falls off the end. A
// hypothesis already in the list (the same square seen from another orientation's columns) is
// kept once, with its most votes.
void insert_by_votes(const SquareSides& sides, SquareCandidates& found) {
  if (found.size() == kMaxSquareCandidates && sides.votes <= found[kMaxSquareCandidates - 1].votes) return;
  for (std::size_t k = 0; k < found.size(); ++k) {
    if (!same_square(found[k], sides)) continue;
    if (found[k].votes >= sides.votes) return;
    for (std::size_t j = k + 1; j < found.size(); ++j) found[j - 1] = found[j];
    found.pop_back();
    break;
  }
  if (found.size() == kMaxSquareCandidates && sides.votes <= found[kMaxSquareCandidates - 1].votes) return;
  if (found.size() < kMaxSquareCandidates) found.push_back(sides);
  std::size_t k = found.size() - 1;
  for (; k > 0 && found[k - 1].votes < sides.votes; --k) found[k] = found[k - 1];
  found[k] = sides;
}

// The votes of cell (theta_bin, rho_bin), theta_bin taken modulo the half turn (theta + pi is the
// line with rho negated).
std::uint32_t votes_at(const HoughLines& hough, int theta_bin, int rho_bin) {
  const int bins = hough.theta_bins();
  if (theta_bin < 0 || theta_bin >= bins) {
    theta_bin = (theta_bin % bins + bins) % bins;
    rho_bin = hough.rho_bins() - 1 - rho_bin;
  }
  return hough.votes(theta_bin, rho_bin);
}

// The strongest lines of the accumulator's column theta_bin: its rho maxima (a plateau's first
// cell) with at least min_votes, in metres, most votes first. A level square's four sides fall
// within a bin of one orientation, where a 2 m side keeps most of its votes in one or two rho
// bins; a strip of tape two or more bins beside a side does not hide it.
using FamilyLines = StaticVector<PlaneLine, 2 * kMaxLinesPerFamily>;

void column_lines(const HoughLines& hough, int theta_bin, std::uint32_t min_votes, FamilyLines& lines) {
  lines.clear();
  const auto full = [&] { return lines.size() == kMaxLinesPerFamily; };
  const int rho_bins = hough.rho_bins();
  const double theta = std::numbers::pi * theta_bin / hough.theta_bins();
  std::uint32_t before = 0;
  std::uint32_t here = votes_at(hough, theta_bin, 0);
  for (int r = 0; r < rho_bins; ++r) {
    const std::uint32_t after = r + 1 < rho_bins ? votes_at(hough, theta_bin, r + 1) : 0;
    if (here >= min_votes && here > before && here >= after && (!full() || here > lines.back().votes)) {
      if (full()) lines.pop_back();
      lines.push_back({theta, hough.rho_of(r) / kPlaneUnitsPerMetre, here});
      for (std::size_t i = lines.size() - 1; i > 0 && lines[i - 1].votes < lines[i].votes; --i) {
        std::swap(lines[i - 1], lines[i]);
      }
    }
    before = here;
    here = after;
  }
}

// With the height known (dof 3) the opposite side lies d from each line: the cell there is a
// candidate line too, maximum or not (a stronger strip a bin or two beside a side takes the
// maximum). Added for every line of the column that has none within a bin of that place, if it
// has at least a quarter of that line's votes (beyond the square lies little tape).
void add_opposite_lines(const HoughLines& hough, int theta_bin, double side, std::uint32_t min_votes,
                        FamilyLines& lines) {
  const double bin_metres = (hough.rho_of(1) - hough.rho_of(0)) / kPlaneUnitsPerMetre;
  const double zero = hough.rho_of(0) / kPlaneUnitsPerMetre;
  const std::size_t maxima = lines.size();
  for (std::size_t i = 0; i < maxima; ++i) {
    for (const double rho : {lines[i].rho - side, lines[i].rho + side}) {
      const auto r = static_cast<int>(std::lround((rho - zero) / bin_metres));
      if (r < 0 || r >= hough.rho_bins() || lines.full()) continue;
      const std::uint32_t v = votes_at(hough, theta_bin, r);
      const bool known = std::any_of(lines.begin(), lines.end(), [&](const PlaneLine& line) {
        return std::abs(line.rho - rho) <= 1.5 * bin_metres;
      });
      if (v >= std::max(min_votes, lines[i].votes / 4) && !known) lines.push_back({lines[i].theta, hough.rho_of(r) / kPlaneUnitsPerMetre, v});
    }
  }
}

}  // namespace

void find_level_square_candidates(const HoughLines& hough, const HoughLineList& peaks, const SquareSearchParams& params,
                                  SquareCandidates& found) {
  found.clear();
  const int bins = hough.theta_bins();
  const int quarter = bins / 2;
  // Distinct orientations modulo a right angle, strongest first.
  StaticVector<int, kMaxSquareOrientations> orientations;
  for (const HoughLine& peak : peaks) {
    if (orientations.full()) break;
    const int bin = peak.theta_bin % quarter;
    const bool known = std::find(orientations.begin(), orientations.end(), bin) != orientations.end();
    if (!known) orientations.push_back(bin);
  }
  const std::uint32_t min_votes = peaks.empty() ? 1 : std::max<std::uint32_t>(1, peaks.back().votes / 4);
  std::array<FamilyLines, 2> families;
  for (const int orientation : orientations) {
    column_lines(hough, orientation, min_votes, families[0]);
    column_lines(hough, orientation + quarter, min_votes, families[1]);
    if (params.exact_side) {
      add_opposite_lines(hough, orientation, params.side, 2 * min_votes, families[0]);
      add_opposite_lines(hough, orientation + quarter, params.side, 2 * min_votes, families[1]);
    }
    // The pairs of each family d apart.
    std::array<StaticVector<ParallelPair, kMaxLinesPerFamily*(2 * kMaxLinesPerFamily - 1)>, 2> pairs;
    for (std::size_t f = 0; f < 2; ++f) {
      const FamilyLines& lines = families[f];
      for (std::size_t i = 0; i < lines.size(); ++i) {
        for (std::size_t j = i + 1; j < lines.size(); ++j) {
          const double distance = std::abs(lines[i].rho - lines[j].rho);  // one column: parallel
          if (std::abs(distance - params.side) <= params.side_tolerance * params.side) pairs[f].push_back({i, j});
        }
      }
    }
    for (const ParallelPair& a : pairs[0]) {
      for (const ParallelPair& b : pairs[1]) {
        SquareSides sides;
        sides.sides = {families[0][a.first], families[1][b.first], families[0][a.second], families[1][b.second]};
        sides.votes = 0;
        for (const PlaneLine& line : sides.sides) sides.votes += line.votes;
        insert_by_votes(sides, found);
      }
    }
  }
}

void find_square_candidates(const HoughLineList& peaks, const SquareSearchParams& params, SquareCandidates& found) {
  found.clear();
  StaticVector<ParallelPair, kMaxHoughLines*(kMaxHoughLines - 1) / 2> pairs;
  for (std::size_t i = 0; i < peaks.size(); ++i) {
    for (std::size_t j = i + 1; j < peaks.size(); ++j) {
      if (line_angle(peaks[i].theta, peaks[j].theta) > params.angle_tolerance) continue;
      const double distance = parallel_distance(peaks[i], peaks[j]);
      if (std::abs(distance - params.side) > params.side_tolerance * params.side) continue;
      pairs.push_back({i, j});
    }
  }
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    for (std::size_t q = p + 1; q < pairs.size(); ++q) {
      const ParallelPair& a = pairs[p];
      const ParallelPair& b = pairs[q];
      if (a.first == b.first || a.first == b.second || a.second == b.first || a.second == b.second) continue;
      const double angle = line_angle(peaks[a.first].theta, peaks[b.first].theta);
      if (std::abs(angle - std::numbers::pi / 2) > params.angle_tolerance) continue;
      SquareSides sides;
      sides.sides = {plane_line(peaks[a.first]), plane_line(peaks[b.first]), plane_line(peaks[a.second]),
                     plane_line(peaks[b.second])};
      sides.votes = peaks[a.first].votes + peaks[a.second].votes + peaks[b.first].votes + peaks[b.second].votes;
      insert_by_votes(sides, found);
    }
  }
}

}  // namespace irloc::square
