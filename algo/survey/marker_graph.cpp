#include "algo/survey/marker_graph.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Cholesky>

#include "algo/geometry/pose.hpp"

namespace irloc::survey {

RelativeSighting relative_sighting(const CeilingPose& base_in_a, const CeilingCovariance& covariance_a,
                                   const CeilingPose& base_in_b, const CeilingCovariance& covariance_b) {
  // L_b in L_a = T_La_B T_B_Lb: translation p_a - Rz(d) p_b, yaw d = yaw_a - yaw_b.
  const double d = wrap_angle(base_in_a[3] - base_in_b[3]);
  const double c = std::cos(d), s = std::sin(d);
  const Eigen::Vector3d& p_b = base_in_b.head<3>();
  RelativeSighting result;
  result.b_in_a << base_in_a[0] - (c * p_b.x() - s * p_b.y()), base_in_a[1] - (s * p_b.x() + c * p_b.y()),
      base_in_a[2] - p_b.z(), d;
  // d Rz(d) p_b / d d
  const Eigen::Vector2d turned_derivative(-s * p_b.x() - c * p_b.y(), c * p_b.x() - s * p_b.y());
  CeilingJacobian d_a = CeilingJacobian::Identity();
  d_a.block<2, 1>(0, 3) = -turned_derivative;
  CeilingJacobian d_b = CeilingJacobian::Zero();
  d_b.block<2, 2>(0, 0) << -c, s, -s, -c;
  d_b(2, 2) = -1;
  d_b.block<2, 1>(0, 3) = turned_derivative;
  d_b(3, 3) = -1;
  result.covariance = d_a * covariance_a * d_a.transpose() + d_b * covariance_b * d_b.transpose();
  return result;
}

MarkerGraph::MarkerGraph(std::size_t capacity, std::size_t connected_capacity, const SurveyConfig& config)
    : capacity_(capacity),
      connected_capacity_(std::min(connected_capacity, capacity)),
      config_(config),
      slot_(capacity, -1),
      poses_(capacity, CeilingPose::Zero()),
      priors_(capacity, CeilingPose::Zero()),
      prior_information_(capacity, CeilingPose::Zero()),
      fixed_(capacity, false),
      node_sightings_(capacity, 0),
      marker_sighting_responses_(capacity),
      marker_sighting_counts_(capacity, 0),
      fixed_bias_(connected_capacity_, CeilingCovariance::Zero()),
      edges_(connected_capacity_ * connected_capacity_),
      hessian_(4 * connected_capacity_, 4 * connected_capacity_),
      step_(4 * connected_capacity_),
      unit_columns_(4 * connected_capacity_, 4),
      response_(4 * connected_capacity_, 4) {
  connected_nodes_.reserve(connected_capacity_);
}

bool MarkerGraph::connect(int node) {
  const auto n = static_cast<std::size_t>(node);
  if (slot_[n] >= 0) return true;
  if (connected_nodes_.size() == connected_capacity_) return false;
  slot_[n] = static_cast<int>(connected_nodes_.size());
  connected_nodes_.push_back(node);  // reserved: no heap
  return true;
}

CeilingCovariance MarkerGraph::prior_covariance(std::size_t node) const {
  if (fixed_[node]) return CeilingCovariance::Zero();
  return prior_information_[node].cwiseInverse().asDiagonal();
}

int MarkerGraph::add_node(const CeilingPose& pose, bool fixed, const std::optional<CeilingPose>& prior_sigma) {
  if (size_ == capacity_) return -1;
  const std::size_t node = size_++;
  poses_[node] = pose;
  priors_[node] = pose;
  const CeilingPose weak(config_.prior_sigma_m, config_.prior_sigma_m, config_.prior_sigma_m, config_.prior_sigma_yaw);
  prior_information_[node] = prior_sigma.value_or(weak).cwiseAbs2().cwiseInverse();
  fixed_[node] = fixed;
  node_sightings_[node] = 0;
  return static_cast<int>(node);
}

void MarkerGraph::restart_node(int node, const CeilingPose& pose) {
  const auto n = static_cast<std::size_t>(node);
  if (connected(node)) {
    for (const int other : connected_nodes_) {
      if (other == node) continue;
      Edge& dropped = other < node ? edge(other, node) : edge(node, other);
      node_sightings_[static_cast<std::size_t>(other)] -= dropped.sightings;
      dropped = Edge{};
    }
  }
  node_sightings_[n] = 0;
  marker_sighting_responses_[n] = PixelErrorResponse{};
  marker_sighting_counts_[n] = 0;
  poses_[n] = pose;
  release_prior(node);
  // Without its edges the graph may fall apart into pieces that only the priors hold: each stays
  // where it was solved, not where the drawing had it.
  for (std::size_t other = 0; other < size_; ++other) priors_[other] = poses_[other];
}

double MarkerGraph::prior_distance(int node) const {
  const auto n = static_cast<std::size_t>(node);
  const CeilingPose difference = pose_difference(poses_[n], priors_[n]);
  return difference.dot(prior_information_[n].cwiseProduct(difference));
}

void MarkerGraph::release_prior(int node) {
  const auto n = static_cast<std::size_t>(node);
  priors_[n] = poses_[n];
  const CeilingPose weak(config_.prior_sigma_m, config_.prior_sigma_m, config_.prior_sigma_m, config_.prior_sigma_yaw);
  prior_information_[n] = weak.cwiseAbs2().cwiseInverse();
}

double MarkerGraph::sighting_distance(int a, int b, const RelativeSighting& sighting,
                                      const CeilingCovariance& covariance_a, const CeilingCovariance& covariance_b) const {
  CeilingJacobian d_a, d_b;
  const CeilingPose innovation = pose_difference(sighting.b_in_a, relative_pose(pose(a), pose(b), &d_a, &d_b));
  const CeilingCovariance covariance = sighting.covariance + d_a * covariance_a * d_a.transpose() +
                                       d_b * covariance_b * d_b.transpose();
  return innovation.dot(covariance.ldlt().solve(innovation));
}

namespace {

// Distance of `point` from the line through a and b (from a when they coincide).
double distance_from_line(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& point) {
  const Eigen::Vector2d along = b - a, off = point - a;
  const double length = along.norm();
  if (length == 0) return off.norm();
  return std::abs(along.x() * off.y() - along.y() * off.x()) / length;
}

// How far the track a-b strays from the line through p-q: its farther end's distance (a track of
// one point: the line's distance from it, when the line is the longer).
double track_distance(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p,
                      const Eigen::Vector2d& q) {
  if ((q - p).squaredNorm() < (b - a).squaredNorm()) {
    return std::max(distance_from_line(a, b, p), distance_from_line(a, b, q));
  }
  return std::max(distance_from_line(p, q, a), distance_from_line(p, q, b));
}

}  // namespace

std::ptrdiff_t MarkerGraph::line_of_visit(const Edge& pair) {
  if (pair.visit.sightings == 0) return -1;
  std::ptrdiff_t nearest = -1;
  double nearest_distance = 0;
  for (std::size_t l = 0; l < pair.line_count; ++l) {
    const Line& line = pair.lines[l];
    const double distance = track_distance(pair.visit.start, pair.visit.end, line.start, line.end);
    if (nearest < 0 || distance < nearest_distance) {
      nearest = static_cast<std::ptrdiff_t>(l);
      nearest_distance = distance;
    }
  }
  if (nearest >= 0 && (nearest_distance <= pair.same_line_m || pair.line_count == kMaxLines)) return nearest;
  return static_cast<std::ptrdiff_t>(pair.line_count);
}

void MarkerGraph::close_visit(Edge& pair) {
  const std::ptrdiff_t index = line_of_visit(pair);
  if (index < 0) return;
  const auto l = static_cast<std::size_t>(index);
  if (l == pair.line_count) {
    pair.lines[l] = Line{};
    pair.lines[l].start = pair.visit.start;
    pair.lines[l].end = pair.visit.end;
    ++pair.line_count;
  }
  Line& line = pair.lines[l];
  line.sightings += pair.visit.sightings;
  line.weights += pair.visit.weights;
  line.offsets += pair.visit.offsets;
  pair.visit = Line{};
}

double MarkerGraph::line_share(const Edge& pair) {
  const std::ptrdiff_t open = line_of_visit(pair);
  double sizes = open == static_cast<std::ptrdiff_t>(pair.line_count) ? std::pow(pair.visit.sightings, 2) : 0.0;
  for (std::size_t l = 0; l < pair.line_count; ++l) {
    const int joined = static_cast<std::ptrdiff_t>(l) == open ? pair.visit.sightings : 0;
    sizes += std::pow(pair.lines[l].sightings + joined, 2);
  }
  return sizes / std::pow(pair.sightings, 2);
}

void MarkerGraph::add_sighting(int a, int b, const RelativeSighting& sighting, std::uint64_t frame) {
  if (!connected(a) || !connected(b)) return;  // the caller connects them first
  Edge& pair = edge(a, b);
  if (pair.sightings == 0) pair.reference = sighting.b_in_a;
  const CeilingCovariance information = sighting.covariance.inverse();
  const CeilingPose offset = pose_difference(sighting.b_in_a, pair.reference);
  pair.information += information;
  pair.information_offset += information * offset;
  if (pair.visit.sightings > 0 && frame > pair.last_frame + 1) close_visit(pair);
  pair.last_frame = frame;
  const CeilingPose weights = sighting.covariance.diagonal().cwiseInverse();
  if (pair.visit.sightings == 0) {
    pair.visit.start = sighting.camera_in_a;
    pair.same_line_m = sighting.same_line_m;
  }
  pair.visit.end = sighting.camera_in_a;
  pair.same_line_m = std::min(pair.same_line_m, sighting.same_line_m);
  ++pair.visit.sightings;
  pair.visit.weights += weights;
  pair.visit.offsets += weights.cwiseProduct(offset);
  ++pair.sightings;
  ++node_sightings_[static_cast<std::size_t>(a)];
  ++node_sightings_[static_cast<std::size_t>(b)];
}

MarkerGraph::EdgeTerm MarkerGraph::edge_term(const Edge& pair, std::size_t a, std::size_t b) const {
  EdgeTerm term;
  const CeilingPose predicted = relative_pose(poses_[a], poses_[b], &term.d_a, &term.d_b);
  const CeilingPose mean = pair.reference + pair.information.ldlt().solve(pair.information_offset);
  term.residual = pose_difference(mean, predicted);
  // Huber on the distance in units of one sighting's spread (the mean's, times sqrt(n)).
  const double distance = std::sqrt(term.residual.dot(pair.information * term.residual) / pair.sightings);
  const double weight = distance <= config_.edge_huber ? 1.0 : config_.edge_huber / distance;
  const double share = line_share(pair);
  const double repeated = 1 + repeated_share_ * (pair.sightings * share - 1);
  const CeilingCovariance covariance =
      repeated * pair.information.inverse() + CeilingCovariance(share * shared_variance_.asDiagonal());
  term.information = weight * covariance.inverse();
  return term;
}

void MarkerGraph::add_marker_sighting(int node, const CeilingPose& base_in_node, const PixelErrorResponse& response) {
  const auto n = static_cast<std::size_t>(node);
  // The sighting's error as a displacement of the node: base_in_node = relative_pose(node, base).
  CeilingJacobian d_node;
  relative_pose(poses_[n], compose(poses_[n], base_in_node), &d_node, nullptr);
  const CeilingJacobian to_node = d_node.inverse();
  PixelErrorResponse& sums = marker_sighting_responses_[n];
  sums.along_u += to_node * response.along_u * to_node.transpose();
  sums.along_v += to_node * response.along_v * to_node.transpose();
  sums.coupling += to_node * response.coupling * to_node.transpose();
  ++marker_sighting_counts_[n];
}

CeilingCovariance MarkerGraph::marker_bias(int node) const {
  const auto n = static_cast<std::size_t>(node);
  if (marker_sighting_counts_[n] == 0) return CeilingCovariance::Zero();
  return marker_sighting_responses_[n].covariance(marker_pixel_error_) / marker_sighting_counts_[n];
}

void MarkerGraph::add_fixed_bias_response(const Eigen::Ref<const Eigen::MatrixXd>& lower,
                                          Eigen::Ref<Eigen::MatrixXd> workspace,
                                          std::span<CeilingCovariance> per_slot) const {
  const std::size_t count = connected_nodes_.size();
  for (std::size_t sf = 0; sf < count; ++sf) {
    const auto fixed = static_cast<std::size_t>(connected_nodes_[sf]);
    if (!fixed_[fixed]) continue;
    const CeilingCovariance bias = marker_bias(static_cast<int>(fixed));
    if (bias.isZero()) continue;
    workspace.setZero();
    bool coupled = false;
    for (std::size_t so = 0; so < count; ++so) {
      const auto other = static_cast<std::size_t>(connected_nodes_[so]);
      if (fixed_[other]) continue;
      const bool fixed_first = fixed < other;
      const Edge& pair = fixed_first ? edges_[sf * connected_capacity_ + so] : edges_[so * connected_capacity_ + sf];
      if (pair.sightings == 0) continue;
      const EdgeTerm term = fixed_first ? edge_term(pair, fixed, other) : edge_term(pair, other, fixed);
      const CeilingJacobian& d_fixed = fixed_first ? term.d_a : term.d_b;
      const CeilingJacobian& d_other = fixed_first ? term.d_b : term.d_a;
      workspace.block<4, 4>(static_cast<Eigen::Index>(4 * so), 0) = d_other.transpose() * term.information * d_fixed;
      coupled = true;
    }
    if (!coupled) continue;
    // K = L^-T L^-1 G, one column at a time (a vector solve needs no workspace).
    const auto factor = lower.triangularView<Eigen::Lower>();
    for (Eigen::Index k = 0; k < 4; ++k) {
      auto column = workspace.col(k);
      factor.solveInPlace(column);
      factor.transpose().solveInPlace(column);
    }
    for (std::size_t so = 0; so < count; ++so) {
      if (fixed_[static_cast<std::size_t>(connected_nodes_[so])]) continue;
      const CeilingJacobian response = workspace.block<4, 4>(static_cast<Eigen::Index>(4 * so), 0);
      per_slot[so] += response * bias * response.transpose();
    }
  }
}

void MarkerGraph::build_normal_equations(Eigen::Ref<Eigen::MatrixXd> hessian, Eigen::Ref<Eigen::VectorXd> gradient) const {
  hessian.setZero();
  gradient.setZero();
  const std::size_t count = connected_nodes_.size();
  for (std::size_t s = 0; s < count; ++s) {
    const auto node = static_cast<std::size_t>(connected_nodes_[s]);
    const auto i = static_cast<Eigen::Index>(4 * s);
    if (fixed_[node]) {
      hessian.block<4, 4>(i, i).setIdentity();  // not estimated: the step stays zero
      continue;
    }
    const double distance = std::sqrt(prior_distance(static_cast<int>(node)));
    const double weight = distance <= config_.prior_huber ? 1.0 : config_.prior_huber / distance;
    const CeilingPose information = weight * prior_information_[node];
    hessian.block<4, 4>(i, i) += information.asDiagonal();
    gradient.segment<4>(i) += information.cwiseProduct(pose_difference(priors_[node], poses_[node]));
  }
  for (std::size_t sa = 0; sa < count; ++sa) {
    for (std::size_t sb = 0; sb < count; ++sb) {
      const auto a = static_cast<std::size_t>(connected_nodes_[sa]), b = static_cast<std::size_t>(connected_nodes_[sb]);
      if (a >= b) continue;  // each edge once, stored low -> high
      const Edge& pair = edges_[sa * connected_capacity_ + sb];
      if (pair.sightings == 0 || (fixed_[a] && fixed_[b])) continue;
      const EdgeTerm term = edge_term(pair, a, b);
      const CeilingJacobian& d_a = term.d_a;
      const CeilingJacobian& d_b = term.d_b;
      const CeilingCovariance& information = term.information;
      const CeilingPose& residual = term.residual;
      const auto ia = static_cast<Eigen::Index>(4 * sa), ib = static_cast<Eigen::Index>(4 * sb);
      if (!fixed_[a]) {
        hessian.block<4, 4>(ia, ia) += d_a.transpose() * information * d_a;
        gradient.segment<4>(ia) += d_a.transpose() * information * residual;
      }
      if (!fixed_[b]) {
        hessian.block<4, 4>(ib, ib) += d_b.transpose() * information * d_b;
        gradient.segment<4>(ib) += d_b.transpose() * information * residual;
      }
      if (!fixed_[a] && !fixed_[b]) {
        hessian.block<4, 4>(ia, ib) += d_a.transpose() * information * d_b;
        hessian.block<4, 4>(ib, ia) += d_b.transpose() * information * d_a;
      }
    }
  }
}

// The lines' means of one pair scatter about their mean by (L - 1) shared_variance plus (1 - 1/L)
// times the sum of their variances, each (1 + rho (n_l - 1)) / weights (a moment estimate; the
// open visit counts).
void MarkerGraph::measure_shared_variance() {
  CeilingPose excess = CeilingPose::Zero();
  int degrees = 0;
  const std::size_t count = connected_nodes_.size();
  for (std::size_t sa = 0; sa < count; ++sa) {
    for (std::size_t sb = 0; sb < count; ++sb) {
      const Edge& stored = edges_[sa * connected_capacity_ + sb];
      if (stored.sightings < 2) continue;
      Edge pair = stored;  // its open visit closed, as if it ended now
      close_visit(pair);
      if (pair.line_count < 2) continue;
      const double lines = static_cast<double>(pair.line_count);
      CeilingPose means = CeilingPose::Zero(), squares = CeilingPose::Zero(), variances = CeilingPose::Zero();
      for (std::size_t l = 0; l < pair.line_count; ++l) {
        const Line& line = pair.lines[l];
        const CeilingPose mean = line.offsets.cwiseQuotient(line.weights);
        means += mean;
        squares += mean.cwiseAbs2();
        variances += (1 + repeated_share_ * (line.sightings - 1)) * line.weights.cwiseInverse();
      }
      excess += squares - means.cwiseAbs2() / lines - (1.0 - 1.0 / lines) * variances;
      degrees += static_cast<int>(pair.line_count) - 1;
    }
  }
  if (degrees < config_.shared_error_min_lines) {
    shared_variance_.setZero();
    return;
  }
  shared_variance_ = (excess / degrees).cwiseMax(0.0);
}

void MarkerGraph::solve(int iterations) {
  measure_shared_variance();
  const auto n = static_cast<Eigen::Index>(4 * connected_nodes_.size());
  for (int iteration = 0; iteration < iterations && n > 0; ++iteration) {
    Eigen::Ref<Eigen::MatrixXd> hessian = hessian_.topLeftCorner(n, n);
    Eigen::Ref<Eigen::VectorXd> step = step_.head(n);
    build_normal_equations(hessian, step);
    const Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>> factor(hessian);  // in place: no heap
    factored_size_ = factor.info() == Eigen::Success ? connected_nodes_.size() : 0;
    if (factored_size_ == 0) return;
    factor.solveInPlace(step);
    if (iteration + 1 == iterations) {
      std::fill(fixed_bias_.begin(), fixed_bias_.end(), CeilingCovariance::Zero());
      add_fixed_bias_response(hessian, response_.topRows(n), std::span<CeilingCovariance>(fixed_bias_));
    }
    for (std::size_t s = 0; s < factored_size_; ++s) {
      const auto node = static_cast<std::size_t>(connected_nodes_[s]);
      if (fixed_[node]) continue;
      poses_[node] += step_.segment<4>(static_cast<Eigen::Index>(4 * s));
      poses_[node][3] = wrap_angle(poses_[node][3]);
    }
  }
}

CeilingPose MarkerGraph::last_step(int node) const {
  const int s = slot_[static_cast<std::size_t>(node)];
  if (s < 0 || static_cast<std::size_t>(s) >= factored_size_ || fixed_[static_cast<std::size_t>(node)]) {
    return CeilingPose::Zero();
  }
  return step_.segment<4>(static_cast<Eigen::Index>(4 * s));
}

bool MarkerGraph::factored_covariance(int node, CeilingCovariance& covariance) {
  const auto n = static_cast<std::size_t>(node);
  const int s = slot_[n];
  if (s < 0 || fixed_[n]) {
    covariance = prior_covariance(n);
    return true;
  }
  if (static_cast<std::size_t>(s) >= factored_size_) return false;
  // The node's block of H^-1 = L^-T L^-1 is Y^T Y with Y = L^-1 [e_4s .. e_4s+3], solved one
  // column at a time (a vector solve needs no workspace).
  const auto size = static_cast<Eigen::Index>(4 * factored_size_);
  const auto lower = hessian_.topLeftCorner(size, size).triangularView<Eigen::Lower>();
  for (Eigen::Index k = 0; k < 4; ++k) {
    auto column = unit_columns_.col(k).head(size);
    column.setZero();
    column[static_cast<Eigen::Index>(4 * s) + k] = 1;
    lower.solveInPlace(column);
  }
  for (Eigen::Index r = 0; r < 4; ++r) {
    for (Eigen::Index c = 0; c < 4; ++c) {
      covariance(r, c) = unit_columns_.col(r).head(size).dot(unit_columns_.col(c).head(size));
    }
  }
  covariance += marker_bias(node) + fixed_bias_[static_cast<std::size_t>(s)];
  return true;
}

std::vector<CeilingCovariance> MarkerGraph::covariances() const {
  std::vector<CeilingCovariance> result(size_);
  for (std::size_t node = 0; node < size_; ++node) result[node] = prior_covariance(node);
  const auto n = static_cast<Eigen::Index>(4 * connected_nodes_.size());
  if (n == 0) return result;
  Eigen::MatrixXd hessian(n, n);
  Eigen::VectorXd gradient(n);
  build_normal_equations(hessian, gradient);
  const Eigen::LLT<Eigen::MatrixXd> factor(hessian);
  std::vector<CeilingCovariance> fixed_bias(connected_nodes_.size(), CeilingCovariance::Zero());
  if (factor.info() == Eigen::Success) {
    Eigen::MatrixXd workspace(n, 4);
    add_fixed_bias_response(factor.matrixLLT(), workspace, std::span<CeilingCovariance>(fixed_bias));
  }
  for (std::size_t s = 0; s < connected_nodes_.size(); ++s) {
    const auto node = static_cast<std::size_t>(connected_nodes_[s]);
    if (fixed_[node]) continue;
    if (factor.info() != Eigen::Success) {
      result[node].setZero();
      continue;
    }
    // The node's block of H^-1 = (L^-1 E)^T (L^-1 E), E its four unit columns.
    Eigen::Matrix<double, Eigen::Dynamic, 4> unit = Eigen::Matrix<double, Eigen::Dynamic, 4>::Zero(n, 4);
    unit.block<4, 4>(static_cast<Eigen::Index>(4 * s), 0).setIdentity();
    factor.matrixL().solveInPlace(unit);
    result[node] = unit.transpose() * unit + marker_bias(static_cast<int>(node)) + fixed_bias[s];
  }
  return result;
}

}  // namespace irloc::survey
