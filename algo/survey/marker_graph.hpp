#pragma once
// The least-squares graph over marker poses (docs/survey.md). Nodes: markers' level frames in W,
// (x, y, z, yaw) each; a fixed node is exact. Edges: one per pair of markers seen together,
// holding the sufficient statistics of every sighting of that pair's relative pose (information
// matrix and information-weighted mean), so memory never grows with the length of the run. Solved
// by Gauss-Newton with a Huber weight per edge and a prior per node (weak, or a surveyed marker's
// sigma, also under Huber: a marker that moved since is outvoted by its sightings).
//
// Bounds: a node without edges (a mapped marker the run has not seen with another) is decoupled
// from the rest: it stays at its prior with its prior's covariance and costs O(1). Only connected
// nodes, at most `connected_capacity`, enter the dense normal equations; their edges
// (connected_capacity^2) and matrix ((4 connected_capacity)^2) are sized at start-up. So memory is
// O(capacity + connected_capacity^2), a solve O(connected^3) and all marginal covariances
// (covariances()) O(capacity + connected^3), whatever the map's size.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "algo/survey/ceiling_pose.hpp"
#include "algo/survey/marker_sighting.hpp"
#include "algo/survey/survey_config.hpp"

namespace irloc::survey {

// One sighting of marker b's level frame in marker a's, from one frame: the robot's pose in each
// (marker_sighting.hpp) combined. The covariance is that of the two independent fits, propagated.
struct RelativeSighting {
  CeilingPose b_in_a = CeilingPose::Zero();
  CeilingCovariance covariance = CeilingCovariance::Zero();
  // Where the camera was in a's level frame (x, y), and how near another sighting's camera must be
  // to the line of this one's visit to see the dots at the same places on the pixel grid (a quarter
  // of a pixel's footprint at the marker).
  Eigen::Vector2d camera_in_a = Eigen::Vector2d::Zero();
  double same_line_m = 0;
};
RelativeSighting relative_sighting(const CeilingPose& base_in_a, const CeilingCovariance& covariance_a,
                                   const CeilingPose& base_in_b, const CeilingCovariance& covariance_b);

class MarkerGraph {
 public:
  MarkerGraph(std::size_t capacity, std::size_t connected_capacity, const SurveyConfig& config);  // allocates everything

  std::size_t capacity() const { return capacity_; }
  std::size_t size() const { return size_; }
  // Connected nodes: those that may hold edges. connect() makes a node one (true when it is or
  // there was room); add_sighting() needs both its nodes connected.
  bool connect(int node);
  bool connected(int node) const { return slot_[static_cast<std::size_t>(node)] >= 0; }
  std::size_t free_connections() const { return connected_capacity_ - connected_nodes_.size(); }
  // A new node at `pose` (also its prior); -1 when the graph is full. The prior's sigma is the
  // config's weak one unless given (a marker surveyed before: its map sigma).
  int add_node(const CeilingPose& pose, bool fixed, const std::optional<CeilingPose>& prior_sigma = std::nullopt);
  // Mahalanobis distance squared of the node's solved pose from its prior.
  double prior_distance(int node) const;
  const CeilingPose& prior(int node) const { return priors_[static_cast<std::size_t>(node)]; }
  // The node no longer holds to its prior (a surveyed marker that moved): a weak prior at its
  // solved pose.
  void release_prior(int node);
  // Forgets every edge of the node and restarts it at `pose` (a moved marker).
  void restart_node(int node, const CeilingPose& pose);

  const CeilingPose& pose(int node) const { return poses_[static_cast<std::size_t>(node)]; }
  bool fixed(int node) const { return fixed_[static_cast<std::size_t>(node)]; }
  // Sightings held by the node's edges.
  int sightings(int node) const { return node_sightings_[static_cast<std::size_t>(node)]; }

  // Mahalanobis distance squared of a new sighting of b in a against the solved poses, whose
  // marginal covariances (a's and b's, taken as independent: a gate that errs toward letting a
  // sighting in) add to the sighting's.
  double sighting_distance(int a, int b, const RelativeSighting& sighting, const CeilingCovariance& covariance_a,
                           const CeilingCovariance& covariance_b) const;
  // frame: the frame's number; a pair's sightings in consecutive frames form one visit. Visits
  // whose camera tracks lie on one line (within the sightings' same_line_m) see the dots at the
  // same places on the pixel grid and repeat one error: together they are one line.
  void add_sighting(int a, int b, const RelativeSighting& sighting, std::uint64_t frame);
  // The share of a sighting's covariance that the next sighting of the same visit repeats (the
  // correlation of the dots' residuals from one sighting to the next, measured by the caller):
  // the sightings of one line share that part of their error.
  void set_repeated_share(double share) { repeated_share_ = share; }
  // Per axis (x, y, z, yaw) in the pairs' frames, m^2 or rad^2: the variance of an error that the
  // sightings of one line share beyond the repeated share of their own covariance (a dot's
  // centroid error fixed by where it falls on the pixel grid). Measured, as of the last solve,
  // from how far the lines' means of each pair scatter beyond their own covariance, pooled over
  // every pair; zero until the pairs hold shared_error_min_lines lines beyond each one's first.
  // An edge's mean of n sightings with covariance C / n as if independent, in lines of n_l, has
  // the covariance C / n (1 + rho (n S - 1)) + S times this, S = sum (n_l / n)^2, rho the
  // repeated share.
  const CeilingPose& shared_variance() const { return shared_variance_; }

  // The error every sighting of a marker repeats (marker_bias.hpp): a pixel error of every dot,
  // with a covariance in the image's axes measured by the caller, that moves the marker's node as
  // a whole, whatever the number of sightings. add_marker_sighting() takes one sighting of the
  // node's own marker (the robot's pose in its level frame, and how that pose answers a pixel
  // error of each dot) and keeps the mean of those answers as node displacements; the node's
  // marginal covariance then adds their covariance under the measured pixel error, and the free
  // nodes add what a fixed node's bias moves them by (the solve carries them along with a fixed
  // node that looks displaced).
  void add_marker_sighting(int node, const CeilingPose& base_in_node, const PixelErrorResponse& response);
  void set_marker_pixel_error(const Eigen::Matrix2d& covariance) { marker_pixel_error_ = covariance; }
  // The covariance of the node's displacement under the marker pixel error: the mean over its
  // sightings.
  CeilingCovariance marker_bias(int node) const;

  // Gauss-Newton steps on every free node. Allocates nothing.
  void solve(int iterations);
  // The node's marginal covariance from the last solve's factored normal matrix (its poses before
  // the step); a node without edges: its prior's. False when the node was connected since or the
  // factor failed. Allocates nothing.
  bool factored_covariance(int node, CeilingCovariance& covariance);
  // The step the last solve took on the node (zero for a node added since): a node whose sightings
  // still pull it (a marker that moved) takes large steps.
  CeilingPose last_step(int node) const;
  // Every node's marginal covariance at the current poses (a fixed node: zero), from one
  // factorization. Allocates: not for the per-frame path.
  std::vector<CeilingCovariance> covariances() const;

 private:
  // The sightings of one line: per axis the sums of their inverse variances and of their offsets
  // from the edge's reference so weighted.
  struct Line {
    Eigen::Vector2d start = Eigen::Vector2d::Zero(), end = Eigen::Vector2d::Zero();  // its first visit's camera track
    int sightings = 0;
    CeilingPose weights = CeilingPose::Zero();
    CeilingPose offsets = CeilingPose::Zero();
  };
  static constexpr std::size_t kMaxLines = 4;
  struct Edge {
    int sightings = 0;
    CeilingPose reference = CeilingPose::Zero();  // the first sighting: the others are summed relative to it
    CeilingCovariance information = CeilingCovariance::Zero();
    CeilingPose information_offset = CeilingPose::Zero();  // sum of information * (sighting - reference)
    // The open visit: its sightings, camera track and sums as a line's.
    std::uint64_t last_frame = 0;
    Line visit;
    double same_line_m = 0;  // the least of its sightings'
    // Its closed visits, by line; a visit that fits none when all are taken joins the nearest.
    std::array<Line, kMaxLines> lines{};
    std::size_t line_count = 0;
  };
  // One edge's term in the normal equations at the current poses: its mean's residual against
  // them, its Huber-weighted information and the Jacobians of the relative pose.
  struct EdgeTerm {
    CeilingPose residual = CeilingPose::Zero();
    CeilingCovariance information = CeilingCovariance::Zero();
    CeilingJacobian d_a = CeilingJacobian::Zero(), d_b = CeilingJacobian::Zero();
  };
  EdgeTerm edge_term(const Edge& pair, std::size_t a, std::size_t b) const;
  // Adds to per_slot[s] the covariance that the fixed nodes' marker biases give connected slot
  // s's solved pose: K B K^T with K = H^-1 G, G the fixed node's coupling to the free ones. lower:
  // the lower triangle of the factor of H over the connected nodes; workspace: 4 columns of its
  // size. Allocates nothing.
  void add_fixed_bias_response(const Eigen::Ref<const Eigen::MatrixXd>& lower, Eigen::Ref<Eigen::MatrixXd> workspace,
                               std::span<CeilingCovariance> per_slot) const;
  // The line the open visit belongs to (line_count: a new one; -1: no open visit).
  static std::ptrdiff_t line_of_visit(const Edge& pair);
  // A closed visit's sums enter its line's.
  static void close_visit(Edge& pair);
  // sum over the lines of (n_l / n)^2, the open visit in its line.
  static double line_share(const Edge& pair);
  // The edge of connected nodes a < b, stored by their slots.
  std::size_t edge_index(int a, int b) const {
    return static_cast<std::size_t>(slot_[static_cast<std::size_t>(a)]) * connected_capacity_ +
           static_cast<std::size_t>(slot_[static_cast<std::size_t>(b)]);
  }
  Edge& edge(int a, int b) { return edges_[edge_index(a, b)]; }
  const Edge& edge(int a, int b) const { return edges_[edge_index(a, b)]; }
  CeilingCovariance prior_covariance(std::size_t node) const;
  // The normal equations of the connected nodes, in slot order, into the top-left of hessian and
  // gradient.
  void build_normal_equations(Eigen::Ref<Eigen::MatrixXd> hessian, Eigen::Ref<Eigen::VectorXd> gradient) const;
  void measure_shared_variance();

  std::size_t capacity_;
  std::size_t connected_capacity_;
  SurveyConfig config_;
  CeilingPose shared_variance_ = CeilingPose::Zero();
  double repeated_share_ = 0;
  Eigen::Matrix2d marker_pixel_error_ = Eigen::Matrix2d::Zero();  // px^2, image axes
  std::size_t size_ = 0;
  std::vector<int> slot_;             // per node: its place among the connected ones, -1: none
  std::vector<int> connected_nodes_;  // per slot: the node (reserved at start-up)
  std::vector<CeilingPose> poses_;
  std::vector<CeilingPose> priors_;
  std::vector<CeilingPose> prior_information_;  // diagonal
  std::vector<bool> fixed_;
  std::vector<int> node_sightings_;
  std::vector<PixelErrorResponse> marker_sighting_responses_;  // per node: summed as node displacements
  std::vector<int> marker_sighting_counts_;
  std::vector<CeilingCovariance> fixed_bias_;  // per slot, from the last solve's factor
  std::vector<Edge> edges_;  // [slot(a) * connected_capacity + slot(b)], a < b: b seen in a
  // Sized for the connected capacity; each solve uses the top-left block of the connected nodes and factors it
  // in place (no heap): its lower triangle then holds L of H = L L^T.
  Eigen::MatrixXd hessian_;
  Eigen::VectorXd step_;
  std::size_t factored_size_ = 0;  // connected nodes in the factor the last solve left in hessian_
  Eigen::Matrix<double, Eigen::Dynamic, 4> unit_columns_;  // L^-1 e_k for a node's four k
  Eigen::MatrixXd response_;  // 4 columns: K = H^-1 G of one fixed node
};

}  // namespace irloc::survey
