#include "algo/geometry/p3p.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>
#include <Eigen/LU>

namespace irloc {
namespace {

// Adjugate (transposed cofactor matrix) of a symmetric 3x3 matrix.
Eigen::Matrix3d adjugate_symmetric(const Eigen::Matrix3d& a) {
  Eigen::Matrix3d b;
  b(0, 0) = a(1, 1) * a(2, 2) - a(1, 2) * a(1, 2);
  b(1, 1) = a(0, 0) * a(2, 2) - a(0, 2) * a(0, 2);
  b(2, 2) = a(0, 0) * a(1, 1) - a(0, 1) * a(0, 1);
  b(0, 1) = b(1, 0) = a(0, 2) * a(1, 2) - a(0, 1) * a(2, 2);
  b(0, 2) = b(2, 0) = a(0, 1) * a(1, 2) - a(0, 2) * a(1, 1);
  b(1, 2) = b(2, 1) = a(0, 1) * a(0, 2) - a(0, 0) * a(1, 2);
  return b;
}

// Real roots of x^3 + b x^2 + c x + d, each polished by Newton steps. Returns their count.
int solve_monic_cubic(double b, double c, double d, std::array<double, 3>& roots) {
  const double shift = b / 3;
  const double p = c - b * shift;                        // depressed cubic t^3 + p t + q
  const double q = d - c * shift + 2 * shift * shift * shift;
  const double half_q = 0.5 * q, third_p = p / 3;
  const double discriminant = half_q * half_q + third_p * third_p * third_p;
  int count = 0;
  if (discriminant > 0) {
    const double root = std::sqrt(discriminant);
    const double u = std::cbrt(-half_q + (half_q < 0 ? root : -root));  // no cancellation
    roots[count++] = (u != 0 ? u - third_p / u : 0) - shift;
  } else {
    const double radius = std::sqrt(std::max(0.0, -third_p));
    const double cos_arg = radius > 0 ? std::clamp(-half_q / (radius * radius * radius), -1.0, 1.0) : 0;
    const double angle = std::acos(cos_arg) / 3;
    for (int k = 0; k < 3; ++k) roots[count++] = 2 * radius * std::cos(angle - 2.0943951023931953 * k) - shift;
  }
  for (int i = 0; i < count; ++i) {
    double& x = roots[i];
    for (int k = 0; k < 2; ++k) {
      const double value = ((x + b) * x + c) * x + d;
      const double slope = (3 * x + 2 * b) * x + c;
      if (slope != 0) x -= value / slope;
    }
  }
  return count;
}

// How well a rank-2 symmetric matrix splits into two real lines: -s1 s2 / (s1^2 + s2^2) for its
// nonzero eigenvalues s1, s2, in (0, 0.5] when they have opposite signs, <= 0 otherwise.
double line_pair_quality(const Eigen::Matrix3d& conic) {
  const double product = adjugate_symmetric(conic).trace();  // s1 s2 (the third eigenvalue is 0)
  const double sum = conic.trace();
  const double squares = sum * sum - 2 * product;
  return squares > 0 ? -product / squares : 0;
}

// The two lines l, m of a degenerate conic C ~ l m^T + m l^T. false when they are not real.
bool split_line_pair(const Eigen::Matrix3d& conic, Eigen::Vector3d& l, Eigen::Vector3d& m) {
  // adj(C) = -(l x m)(l x m)^T, and C + [l x m]_x = 2 m l^T has rank one.
  const Eigen::Matrix3d adjugate = adjugate_symmetric(conic);
  int i = 0;
  adjugate.diagonal().cwiseAbs().maxCoeff(&i);
  if (!(adjugate(i, i) < 0)) return false;
  const Eigen::Vector3d p = adjugate.col(i) / std::sqrt(-adjugate(i, i));
  Eigen::Matrix3d rank_one = conic;
  rank_one(0, 1) -= p.z(); rank_one(0, 2) += p.y();
  rank_one(1, 0) += p.z(); rank_one(1, 2) -= p.x();
  rank_one(2, 0) -= p.y(); rank_one(2, 1) += p.x();
  int row = 0, col = 0;
  rank_one.cwiseAbs().maxCoeff(&row, &col);
  l = rank_one.row(row).transpose();
  m = rank_one.col(col);
  return true;
}

struct Problem {
  std::array<Eigen::Vector3d, 3> bearings;  // unit
  int longest_from, longest_to, other;      // vertices: the longest side, the third one
  Eigen::Matrix3d world_frame_transposed;   // of triangle_frame() on the world points
  Eigen::Vector3d world_centroid;
  double a12, a13, a23;                     // squared world distances
  double b12, b13, b23;                     // -2 cos of the angles between bearings
};

Eigen::Vector3d distance_residuals(const Problem& pr, const Eigen::Vector3d& l) {
  return {l(0) * l(0) + l(1) * l(1) + pr.b12 * l(0) * l(1) - pr.a12,
          l(0) * l(0) + l(2) * l(2) + pr.b13 * l(0) * l(2) - pr.a13,
          l(1) * l(1) + l(2) * l(2) + pr.b23 * l(1) * l(2) - pr.a23};
}

// Gauss-Newton on the three distance equations (a square system: Newton).
void refine_depths(const Problem& pr, Eigen::Vector3d& depths) {
  const double scale = pr.a12 + pr.a13 + pr.a23;
  const double converged = 1e-26 * scale * scale;  // relative 1e-13: far below any pixel noise
  Eigen::Vector3d residual = distance_residuals(pr, depths);
  for (int iteration = 0; iteration < 3 && residual.squaredNorm() > converged; ++iteration) {
    const Eigen::Vector3d& l = depths;
    Eigen::Matrix3d jacobian;
    jacobian << 2 * l(0) + pr.b12 * l(1), 2 * l(1) + pr.b12 * l(0), 0,  //
        2 * l(0) + pr.b13 * l(2), 0, 2 * l(2) + pr.b13 * l(0),         //
        0, 2 * l(1) + pr.b23 * l(2), 2 * l(2) + pr.b23 * l(1);
    const Eigen::Vector3d next = depths - jacobian.inverse() * residual;
    const Eigen::Vector3d next_residual = distance_residuals(pr, next);
    // Also stops on a singular Jacobian: the comparison is false for NaN.
    if (!(next_residual.squaredNorm() < residual.squaredNorm())) return;
    depths = next;
    residual = next_residual;
  }
}

// An orthonormal frame (columns) of a triangle: first axis along its longest side from
// vertex `from`, third along its normal.
Eigen::Matrix3d triangle_frame(const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                               const Eigen::Vector3d& other) {
  Eigen::Matrix3d frame;
  frame.col(0) = (to - from).normalized();
  frame.col(2) = (to - from).cross(other - from).normalized();
  frame.col(1) = frame.col(2).cross(frame.col(0));
  return frame;
}

// Depths on the ray pencil direction `direction` (any scale) scaled to the world distances;
// appended as a pose when all are positive.
void add_solution(const Problem& pr, const Eigen::Vector3d& direction, P3PSolutions& solutions) {
  const Eigen::Vector3d& d = direction;
  // Depths must share one sign (flipped below when negative).
  if (!((d(0) > 0 && d(1) > 0 && d(2) > 0) || (d(0) < 0 && d(1) < 0 && d(2) < 0))) return;
  const double camera_sum = d(0) * d(0) + d(1) * d(1) + pr.b12 * d(0) * d(1) + d(0) * d(0) + d(2) * d(2) +
                            pr.b13 * d(0) * d(2) + d(1) * d(1) + d(2) * d(2) + pr.b23 * d(1) * d(2);
  if (!(camera_sum > 0)) return;
  Eigen::Vector3d depths = d * std::sqrt((pr.a12 + pr.a13 + pr.a23) / camera_sum);
  if (depths.sum() < 0) depths = -depths;
  if (!(depths.minCoeff() > 0)) return;
  refine_depths(pr, depths);
  if (!(depths.minCoeff() > 0)) return;

  std::array<Eigen::Vector3d, 3> camera;
  for (int i = 0; i < 3; ++i) camera[i] = depths(i) * pr.bearings[i];
  const Eigen::Matrix3d rotation =
      triangle_frame(camera[pr.longest_from], camera[pr.longest_to], camera[pr.other]) *
      pr.world_frame_transposed;
  const Eigen::Vector3d translation = (camera[0] + camera[1] + camera[2]) / 3 - rotation * pr.world_centroid;
  if (!rotation.allFinite() || !translation.allFinite()) return;
  for (const RigidTransform& existing : solutions) {  // a double root gives the same pose twice
    if ((existing.translation - translation).norm() <= 1e-9 * translation.norm() &&
        (existing.rotation - rotation).norm() <= 1e-9) {
      return;
    }
  }
  solutions.push_back({rotation, translation});
}

// The (at most two) rays of the line n . lambda = 0 on the conic lambda^T Q lambda = 0.
void intersect_line_with_conic(const Eigen::Vector3d& n, const Eigen::Matrix3d& conic, const Problem& pr,
                               P3PSolutions& solutions) {
  int k = 0;
  n.cwiseAbs().maxCoeff(&k);
  if (!(std::abs(n(k)) > 0)) return;
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  // The line is spanned by u = e_i - (n_i / n_k) e_k and v = e_j - (n_j / n_k) e_k.
  Eigen::Vector3d u = Eigen::Vector3d::Zero(), v = Eigen::Vector3d::Zero();
  u(i) = 1;
  u(k) = -n(i) / n(k);
  v(j) = 1;
  v(k) = -n(j) / n(k);
  const Eigen::Vector3d conic_u = conic * u, conic_v = conic * v;
  const double a = u.dot(conic_u), b = u.dot(conic_v), c = v.dot(conic_v);  // a x^2 + 2 b x y + c y^2
  double discriminant = b * b - a * c;
  if (discriminant < 0) {
    if (discriminant < -1e-10 * (b * b + std::abs(a * c))) return;
    discriminant = 0;  // a double root blurred by rounding
  }
  const double q = -(b + std::copysign(std::sqrt(discriminant), b));
  if (q == 0) return;
  if (std::abs(a) >= std::abs(c)) {  // x / y = q / a or c / q
    add_solution(pr, (q / a) * u + v, solutions);
    add_solution(pr, (c / q) * u + v, solutions);
  } else {  // y / x = q / c or a / q
    add_solution(pr, u + (q / c) * v, solutions);
    add_solution(pr, u + (a / q) * v, solutions);
  }
}

// The problem's invariants: unit bearings, squared side lengths, the bearings' cosines, the
// longest side and the world triangle's frame. False when the three points or bearings are
// degenerate (coincident points, a zero or non-finite bearing).
bool set_up_problem(const std::array<Eigen::Vector3d, 3>& world, const std::array<Eigen::Vector3d, 3>& bearings,
                    Problem& pr) {
  for (int i = 0; i < 3; ++i) {
    if (!(bearings[i].squaredNorm() > 0)) return false;
    pr.bearings[i] = bearings[i].normalized();
  }
  pr.a12 = (world[0] - world[1]).squaredNorm();
  pr.a13 = (world[0] - world[2]).squaredNorm();
  pr.a23 = (world[1] - world[2]).squaredNorm();
  pr.b12 = -2 * pr.bearings[0].dot(pr.bearings[1]);
  pr.b13 = -2 * pr.bearings[0].dot(pr.bearings[2]);
  pr.b23 = -2 * pr.bearings[1].dot(pr.bearings[2]);
  if (!(pr.a12 > 0 && pr.a13 > 0 && pr.a23 > 0) || !pr.bearings[0].allFinite() ||
      !pr.bearings[1].allFinite() || !pr.bearings[2].allFinite()) {
    return false;
  }
  pr.longest_from = 0, pr.longest_to = 1;
  if (pr.a13 > pr.a12 && pr.a13 >= pr.a23) pr.longest_to = 2;
  if (pr.a23 > pr.a12 && pr.a23 > pr.a13) pr.longest_from = 1, pr.longest_to = 2;
  pr.other = 3 - pr.longest_from - pr.longest_to;
  pr.world_frame_transposed =
      triangle_frame(world[pr.longest_from], world[pr.longest_to], world[pr.other]).transpose();
  pr.world_centroid = (world[0] + world[1] + world[2]) / 3;
  return true;
}

}  // namespace

int solve_p3p(const std::array<Eigen::Vector3d, 3>& world, const std::array<Eigen::Vector3d, 3>& bearings,
              P3PSolutions& solutions) {
  solutions.clear();
  Problem pr;
  if (!set_up_problem(world, bearings, pr)) return 0;

  // lambda^T D1 lambda = 0 and lambda^T D2 lambda = 0: distance ratios with the scale removed.
  Eigen::Matrix3d d1, d2;
  d1 << pr.a23, 0.5 * pr.a23 * pr.b12, 0,                      //
      0.5 * pr.a23 * pr.b12, pr.a23 - pr.a12, -0.5 * pr.a12 * pr.b23,  //
      0, -0.5 * pr.a12 * pr.b23, -pr.a12;
  d2 << pr.a23, 0, 0.5 * pr.a23 * pr.b13,  //
      0, -pr.a13, -0.5 * pr.a13 * pr.b23,  //
      0.5 * pr.a23 * pr.b13, -0.5 * pr.a13 * pr.b23, pr.a23 - pr.a13;

  // det(D1 + g D2) = c3 g^3 + c2 g^2 + c1 g + c0. Solve in g, or for the pencil m D1 + D2 in
  // m = 1 / g (reversed coefficients), whichever keeps the roots bounded.
  const double c0 = d1.determinant(), c3 = d2.determinant();
  const double c1 = adjugate_symmetric(d1).cwiseProduct(d2).sum();
  const double c2 = adjugate_symmetric(d2).cwiseProduct(d1).sum();
  const bool in_g = std::abs(c3) >= std::abs(c0);
  if (!(std::abs(in_g ? c3 : c0) > 0)) return 0;
  std::array<double, 3> roots;
  const int root_count = in_g ? solve_monic_cubic(c2 / c3, c1 / c3, c0 / c3, roots)
                              : solve_monic_cubic(c1 / c0, c2 / c0, c3 / c0, roots);
  // The degenerate member whose line pair is best conditioned; its lines hold every solution.
  Eigen::Matrix3d best;
  double best_quality = 0;
  for (int r = 0; r < root_count; ++r) {
    const Eigen::Matrix3d member = in_g ? Eigen::Matrix3d(d1 + roots[r] * d2) : Eigen::Matrix3d(roots[r] * d1 + d2);
    const double quality = line_pair_quality(member);
    if (quality > best_quality) best_quality = quality, best = member;
  }
  if (!(best_quality > 0)) return 0;
  Eigen::Vector3d line1, line2;
  if (!split_line_pair(best, line1, line2)) return 0;
  // On the member D1 + g D2, the points of D2 are the points of D1 too (and vice versa).
  const Eigen::Matrix3d& other_conic = in_g ? d2 : d1;
  intersect_line_with_conic(line1, other_conic, pr, solutions);
  intersect_line_with_conic(line2, other_conic, pr, solutions);
  return static_cast<int>(solutions.size());
}

}  // namespace irloc
