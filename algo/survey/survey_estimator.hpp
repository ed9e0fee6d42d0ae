#pragma once
// Map building during localization (docs/survey.md): per frame, the dot source's observations in;
// the estimated pose and uncertainty of every dot marker out, with the markers that moved, the
// ones that were learned and the IDs seen at two places reported as events.
//
//   SurveyEstimator survey(camera, base_from_camera, map, config);  // start-up
//   survey.observe(result.observations);                            // per frame, no heap
//   MarkerMap estimate = survey.estimated_map();                    // when writing the map
//
// Per frame: each marker's dots give the robot's pose in that marker's level frame
// (marker_sighting.hpp); each pair of markers seen together gives a relative sighting that is
// tested against the solved graph and added to it (marker_graph.hpp); the graph takes a
// Gauss-Newton step. Memory and work per frame are bounded by the capacities in SurveyConfig.

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "algo/core/static_vector.hpp"
#include "algo/geometry/camera_model.hpp"
#include "algo/geometry/rigid_transform.hpp"
#include "algo/map/marker_map.hpp"
#include "algo/source/source_result.hpp"
#include "algo/survey/marker_bias.hpp"
#include "algo/survey/marker_candidate.hpp"
#include "algo/survey/marker_graph.hpp"
#include "algo/survey/marker_sighting.hpp"
#include "algo/survey/repeated_share.hpp"
#include "algo/survey/survey_config.hpp"

namespace irloc::survey {

struct SurveyEvent {
  enum class Kind { moved, added, conflict };
  Kind kind = Kind::moved;
  int id = -1;
  Eigen::Vector3d old_origin = Eigen::Vector3d::Zero();  // moved: where the map had it; conflict: first place
  Eigen::Vector3d new_origin = Eigen::Vector3d::Zero();  // moved, added: where it is now; conflict: second place
};
inline constexpr std::size_t kMaxEventsBetweenReads = 32;
using SurveyEvents = StaticVector<SurveyEvent, kMaxEventsBetweenReads>;

// Counters of what the survey could not use; they only grow.
struct SurveyReport {
  std::uint64_t frames = 0;
  std::uint64_t sightings = 0;
  std::uint64_t too_few_dots = 0;        // a marker's dots could not be fitted
  std::uint64_t poor_fits = 0;           // a marker's dots fitted far worse than the pooled pixel noise
  std::uint64_t repeated_cells = 0;      // one ID's cell twice in a frame: two markers with one ID
  std::uint64_t gated_sightings = 0;     // pair sightings that disagreed with the graph
  std::uint64_t unanchored_sightings = 0;  // an unmapped ID seen with no established marker
  std::uint64_t graph_full = 0;
  std::uint64_t candidates_full = 0;
  std::uint64_t misread_candidates = 0;  // a new ID's place on another marker: its dots misread
  std::uint64_t sightings_dropped = 0;   // more markers in one frame than kMaxMarkersPerFrame
};

class SurveyEstimator {
 public:
  static constexpr std::size_t kMaxMarkersPerFrame = 8;

  // The map's dot markers become the graph's nodes (fixed ones exact). Allocates everything.
  SurveyEstimator(const CameraIntrinsics& camera, const RigidTransform& base_from_camera, const MarkerMap& map,
                  const SurveyConfig& config);

  // One frame's observations (dot markers: landmark = ID, point = cell). Allocates nothing.
  void observe(const PointObservationList& observations);

  // Events since the last clear_events(); an event beyond the capacity is counted as dropped.
  const SurveyEvents& events() const { return events_; }
  void clear_events() { events_.clear(); }
  const SurveyReport& report() const { return report_; }

  // estimated_map() and established_markers() list the markers in node order: the input map's
  // markers as they stand there, then the learned ones in the order they were learned.
  //
  // The input map with every dot marker's estimate and sigma, and the learned markers appended
  // once established; an ID found at two places is left out.
  // Allocates: call between frames.
  MarkerMap estimated_map() const;
  // The markers whose poses the survey has established (fixed ones, and those placed by enough
  // consistent sightings within the established sigmas), with their current marginal sigma, for
  // localization during the survey: a marker learned along a chain of new ones carries the chain's
  // uncertainty into the pose covariance. Fills `markers` (cleared first); allocates nothing once
  // it has room for every marker.
  void established_markers(std::vector<DotMarker>& markers) const;
  // The current estimate of one marker as a map entry (no sigma); false when unknown or conflicted.
  bool estimate(int id, DotMarker& marker) const;
  // Per axis: the variance of the error a pair's sightings share (MarkerGraph::shared_variance()).
  CeilingPose shared_error_variance() const;

 private:
  struct FrameMarker {
    MarkerSighting sighting;
    int node = -1;  // -1: not in the graph
    double best_distance = -1;  // smallest sighting distance to an established partner this frame
    bool returned = false;      // placed back where it was before its last move
  };

  int node_of(int id) const;
  bool established(int node) const;
  void collect_sightings(const PointObservationList& observations);
  void drop_poor_fits();
  void measure_shared_errors();
  // The relative sighting of b in a from one frame, with the camera's place in a's frame.
  RelativeSighting pair_sighting(const MarkerSighting& a, const MarkerSighting& b) const;
  void update_graph();
  void test_for_moves();
  void test_survey_priors();
  void update_candidates();
  void add_candidate_sighting(const MarkerSighting& sighting, int anchor_node, const RelativeSighting& relative);
  bool within_established_sigma(const CeilingCovariance& covariance) const;
  bool near_another_marker(const CeilingPose& pose) const;
  bool learn(MarkerCandidate& candidate);
  void update_covariances();
  void emit(const SurveyEvent& event);
  void check_return(FrameMarker& marker, const FrameMarker& partner);
  DotMarker marker_entry(int node) const;

  CameraModel camera_;
  RigidTransform base_from_camera_;
  SurveyConfig config_;
  MarkerMap input_map_;
  MarkerGraph graph_;
  double pixel_variance_ = -1;  // px^2: the running a-posteriori pixel noise of all sightings (-1: none yet)
  int pooled_sightings_ = 0;    // the sightings it holds
  double move_threshold_ = 0;  // chi-square(4 * move_window) quantile
  double prior_move_threshold_ = 0;  // chi-square(4) quantile at the same false-alarm probability
  double candidate_normal_quantile_ = 0;  // the standard normal's at candidate_false_alarm
  double poor_fit_normal_quantile_ = 0;   // the standard normal's at poor_fit_false_alarm
  // What the survey keeps of one graph node beside the graph (the index is the node's).
  struct NodeState {
    int id = -1;
    CeilingCovariance covariance = CeilingCovariance::Zero();  // marginal, from the last solve that held it
    bool learned = false;  // not in the input map
    double pitch = 0, radius = 0;
    // The move test's ring of its last move_window sighting distances, and how many went in.
    std::vector<double> move_statistics;
    int move_count = 0;
    // After a move: the place the marker left, and how many sightings put it back there since (an
    // ID at two places, not a move); -1: not moved.
    CeilingPose vacated = CeilingPose::Zero();
    int returns = -1;
    bool conflicted = false;          // frozen and left out of the map
    bool holds_survey_prior = false;  // a marker with a map sigma, not (yet) found moved
  };
  NodeState& state(int node) { return nodes_[static_cast<std::size_t>(node)]; }
  const NodeState& state(int node) const { return nodes_[static_cast<std::size_t>(node)]; }

  std::vector<NodeState> nodes_;
  std::vector<int> node_by_id_;  // [id]: its node, -1: none
  std::vector<MarkerCandidate> candidates_;
  StaticVector<FrameMarker, kMaxMarkersPerFrame> frame_;
  SurveyEvents events_;
  SurveyReport report_;
  RepeatedShare repeated_share_;
  MarkerBias marker_bias_;
};

}  // namespace irloc::survey
