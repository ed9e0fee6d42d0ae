#include "algo/markers/square/square_search.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "algo/core/static_vector.hpp"
#include "algo/markers/square/ceiling_plane_map.hpp"

namespace irloc {
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

// Inserts into the list kept sorted by votes, most first; the weakest falls off the end.
void insert_by_votes(const SquareSides& sides, SquareCandidates& found) {
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

// The strongest lines near the orientation theta_bin: the rho maxima of each of the columns
// theta_bin - 1, theta_bin, theta_bin + 1 (a side falls in one of them or between two), one line
// kept where two columns have a maximum at the same place; in metres, most votes first.
struct ColumnLine {
  PlaneLine line;
  int theta_bin = 0, rho_bin = 0;
};
using FamilyLines = StaticVector<ColumnLine, kMaxLinesPerFamily>;

void add_line(const ColumnLine& line, FamilyLines& lines) {
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (std::abs(lines[i].rho_bin - line.rho_bin) > 1) continue;
    if (lines[i].line.votes >= line.line.votes) return;  // the same line, seen better in another column
    for (std::size_t j = i + 1; j < lines.size(); ++j) lines[j - 1] = lines[j];
    lines.pop_back();
    break;
  }
  if (lines.full()) {
    if (lines.back().line.votes >= line.line.votes) return;
    lines.pop_back();
  }
  lines.push_back(line);
  for (std::size_t i = lines.size() - 1; i > 0 && lines[i - 1].line.votes < lines[i].line.votes; --i) {
    std::swap(lines[i - 1], lines[i]);
  }
}

void column_lines(const HoughLines& hough, int theta_bin, std::uint32_t min_votes, FamilyLines& lines) {
  lines.clear();
  const int rho_bins = hough.rho_bins();
  for (int k = theta_bin - 1; k <= theta_bin + 1; ++k) {
    const double theta = std::numbers::pi * k / hough.theta_bins();
    std::uint32_t before = 0;
    std::uint32_t here = votes_at(hough, k, 0);
    for (int r = 0; r < rho_bins; ++r) {
      const std::uint32_t after = r + 1 < rho_bins ? votes_at(hough, k, r + 1) : 0;
      // A maximum (a plateau's first cell) with enough votes.
      if (here >= min_votes && here > before && here >= after) {
        add_line({{theta, hough.rho_of(r) / kPlaneUnitsPerMetre, here}, k, r}, lines);
      }
      before = here;
      here = after;
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
    const bool known = std::any_of(orientations.begin(), orientations.end(), [&](int other) {
      const int apart = std::abs(other - bin);
      return std::min(apart, quarter - apart) <= 1;  // its columns are searched
    });
    if (!known) orientations.push_back(bin);
  }
  const std::uint32_t min_votes = peaks.empty() ? 1 : std::max<std::uint32_t>(1, peaks.back().votes / 4);
  std::array<FamilyLines, 2> families;
  for (const int orientation : orientations) {
    column_lines(hough, orientation, min_votes, families[0]);
    column_lines(hough, orientation + quarter, min_votes, families[1]);
    // The pairs of each family d apart.
    std::array<StaticVector<ParallelPair, kMaxLinesPerFamily*(kMaxLinesPerFamily - 1) / 2>, 2> pairs;
    for (std::size_t f = 0; f < 2; ++f) {
      const FamilyLines& lines = families[f];
      for (std::size_t i = 0; i < lines.size(); ++i) {
        for (std::size_t j = i + 1; j < lines.size(); ++j) {
          // Both in the same turn of theta (within a bin of each other): rho is comparable.
          const double distance = std::abs(lines[i].line.rho - lines[j].line.rho);
          if (std::abs(distance - params.side) <= params.side_tolerance * params.side) pairs[f].push_back({i, j});
        }
      }
    }
    for (const ParallelPair& a : pairs[0]) {
      for (const ParallelPair& b : pairs[1]) {
        SquareSides sides;
        sides.sides = {families[0][a.first].line, families[1][b.first].line, families[0][a.second].line,
                       families[1][b.second].line};
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

}  // namespace irloc
