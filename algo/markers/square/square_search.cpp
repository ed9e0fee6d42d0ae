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

}  // namespace

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
      // Insertion into the list kept sorted by votes, most first; the weakest falls off the end.
      if (found.size() == kMaxSquareCandidates && sides.votes <= found[kMaxSquareCandidates - 1].votes) continue;
      if (found.size() < kMaxSquareCandidates) found.push_back(sides);
      std::size_t k = found.size() - 1;
      for (; k > 0 && found[k - 1].votes < sides.votes; --k) found[k] = found[k - 1];
      found[k] = sides;
    }
  }
}

}  // namespace irloc
