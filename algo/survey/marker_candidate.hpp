#pragma once
// An unmapped ID's sightings at one place, in W, until they make it a marker (SurveyEstimator):
// information-weighted like an edge (relative to the first sighting, so yaw never wraps), with the
// weighted squares for their consistency, and the sightings at a second place (an ID at two
// places). Fixed size: a table of them is sized at start-up.

#include <Eigen/Core>

#include "algo/core/static_vector.hpp"
#include "algo/survey/ceiling_pose.hpp"
#include "algo/survey/marker_graph.hpp"

namespace irloc::survey {

struct MarkerCandidate {
  int id = -1;
  int sightings = 0;
  CeilingPose reference = CeilingPose::Zero();
  CeilingCovariance information = CeilingCovariance::Zero();
  CeilingPose information_offset = CeilingPose::Zero();
  double weighted_squares = 0;
  // The anchors' share of a sighting's covariance, common to sightings through one anchor: the
  // smallest seen, added to the mean's covariance.
  CeilingCovariance anchor_covariance = CeilingCovariance::Zero();
  Eigen::Vector2d view_min = Eigen::Vector2d::Zero(), view_max = Eigen::Vector2d::Zero();  // robot in L, m
  // The first sightings as relative sightings from their anchors: the learned marker's first
  // edges (its place in W moves with its anchors as the graph refines them).
  struct Anchored {
    int anchor = -1;
    RelativeSighting sighting;
  };
  StaticVector<Anchored, 16> kept;
  int other_sightings = 0;  // at a second place
  CeilingPose other_mean = CeilingPose::Zero();
  bool conflict = false;

  CeilingPose mean() const;
  CeilingCovariance covariance() const;
  // A sighting at this place: at `pose` in W with covariance own + anchor (anchor: the anchor
  // marker's share), relative from anchor_node, the robot at `robot` (x, y in L, m).
  void add_sighting(const CeilingPose& pose, const CeilingCovariance& own, const CeilingCovariance& anchor,
                    const Eigen::Vector2d& robot, int anchor_node, const RelativeSighting& relative);
  // A sighting at the second place: its running mean.
  void add_other_sighting(const CeilingPose& pose);
};

// compose(a, a_to_b)'s covariance to first order: the relative pose's share (turned into W) and
// the anchor a's share (its yaw turns the lever a_to_b).
CeilingCovariance rotated_covariance(const CeilingPose& a, const CeilingCovariance& relative);
CeilingCovariance anchor_share(const CeilingPose& a, const CeilingPose& a_to_b, const CeilingCovariance& anchor);

}  // namespace irloc::survey
