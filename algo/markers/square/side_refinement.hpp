#pragma once
// The four sides of a found square, refined by least squares on the tape points along each side
// (all mapped tape pixels, not the thinned Hough set), and the corners where they meet.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "algo/markers/square/square_search.hpp"

namespace irloc::square {

struct SideFit {
  PlaneLine line;              // refined; theta in (-pi, pi], the normal kept as the coarse one
  std::uint32_t inliers = 0;   // points used by the last fit
  double rms = 0;              // their RMS distance from the refined line, metres
};

// corners[k] = sides[k] meets sides[(k + 1) % 4], metres on the ceiling plane (camera-centred).
struct SquareFit {
  std::array<SideFit, 4> sides;
  std::array<Eigen::Vector2d, 4> corners;
};

// The refinement of a square hypothesis's four sides, with its scratch sized at start-up.
class SquareRefiner {
 public:
  // capacity: the most points refine() is given. The only allocations.
  explicit SquareRefiner(std::size_t capacity);

  // points: metres on the ceiling plane, at most capacity of them. The points of side k are
  // those within tape_width of its line and at least tape_width inside both neighbouring sides
  // (corner patches and the crossing tape are left out). Each pass refits all four lines by total
  // least squares on those points: up to iterations - 1 passes until the corners move less than
  // half a millimetre (a coarse line some degrees off takes several), then one on the points
  // within 3/4 tape_width. The passes read only the points within kGatherWidths tape widths of
  // each coarse line and of the coarse square's corners' bounding box, gathered once (a line the
  // passes move further than two tape widths was no side). false when a side has fewer than
  // min_inliers points or two neighbouring sides do not meet. Allocates nothing.
  bool refine(std::span<const Eigen::Vector2d> points, const SquareSides& coarse, double tape_width, int iterations,
              std::uint32_t min_inliers, SquareFit& fit);

  // The points the last refine() gathered for coarse side k: within kGatherWidths tape widths of
  // its line and of the coarse square's bounding box.
  std::span<const Eigen::Vector2d> near(std::size_t k) const { return {near_[k].data(), near_count_[k]}; }

  static constexpr double kGatherWidths = 3;
  // The wide passes read at most this many of a side's gathered points: every stride-th, stride
  // ceil(count / kWidePassPoints), and min_inliers / stride of them in the band (rounded up).
  static constexpr std::size_t kWidePassPoints = 512;

  // The ridges of tape points parallel to each side of fit, within kRidgeWidths tape widths of
  // it, on the stretch between its neighbouring sides (as refine() takes them): offsets[k] holds
  // the offsets (metres along side k's normal from its line) of its strongest ridge and, when
  // there is one, of a second at least 1.5 tape widths away, beyond a valley under half of it,
  // with at least min_points points and an eighth of the first's (a strip of tape beside the side;
  // the side may be either, and the refined line, pulled by both, between them); count[k] is 1 or
  // 2 (0: no points). One pass over the points; allocates nothing.
  struct SideRidges {
    std::array<std::array<double, 2>, 4> offsets{};
    std::array<std::size_t, 4> count{};
  };
  static SideRidges side_ridges(std::span<const Eigen::Vector2d> points, const SquareFit& fit, double tape_width,
                                std::uint32_t min_points);

  static constexpr double kRidgeWidths = 4;

  // fit, as refine() left it, with each side whose tape does not all lie on its line refitted on
  // the stretches that do: a strip touching the side at an angle pulls one end of the refined line
  // into a compromise between the two. Each side's stretch between its neighbours is cut into 16
  // segments; in each, the tape-wide window of the points' offsets from the line that holds the
  // most points is where the tape crosses it. The line through two segments' crossings that most
  // points agree with (within 0.15 tape widths), when it carries more than half of them and a
  // sixteenth more than the refined line, is refitted on the points of its segments as refine()'s
  // last pass does. Reads the points refine() gathered; false, fit unchanged, when no side moves
  // (or two neighbouring sides no longer meet). Allocates nothing.
  bool straighten(double tape_width, std::uint32_t min_inliers, SquareFit& fit);

 private:
  std::array<std::vector<Eigen::Vector2d>, 4> near_;     // the points near each coarse side
  std::vector<Eigen::Vector2d> kept_;                    // straighten()'s points
  std::array<std::size_t, 4> near_count_{};
  std::array<std::vector<Eigen::Vector2d>, 4> samples_;  // every stride-th of them
};

// Whether two neighbouring lines of coarse each pass within distance of both ends of a side of
// fit. A corner and the side d fix a square: coarse is fit's square, seen through other lines for
// its sides or with weaker or stray lines for the other two. (Two squares in a row share two
// parallel lines, never a corner.)
bool traces_corner(const SquareSides& coarse, const SquareFit& fit, double distance);

// Where two lines meet; false for (nearly) parallel lines.
bool intersect(const PlaneLine& a, const PlaneLine& b, Eigen::Vector2d& point);

}  // namespace irloc::square
