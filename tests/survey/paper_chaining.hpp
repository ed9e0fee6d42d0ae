#pragma once
// The movable-marker paper's method (Yang et al., docs/survey.md), kept as the reference the
// graph is compared with: in every frame with two or more markers, a representative marker (the
// reference when seen, else the already placed marker nearest the reference) places the others
// by their relative vectors; each marker's place is the plain average of its placements since its
// last reset, and a placement farther than `reset_threshold` from the average restarts it.

#include <map>
#include <vector>

#include "algo/map/marker_map.hpp"
#include "algo/survey/ceiling_pose.hpp"
#include "algo/survey/marker_graph.hpp"
#include "algo/survey/marker_sighting.hpp"

namespace irloc::test {

class PaperChaining {
 public:
  PaperChaining(int reference_id, const survey::CeilingPose& reference_pose, double reset_threshold)
      : reference_id_(reference_id), reset_threshold_(reset_threshold) {
    places_[reference_id] = {reference_pose, 1};
  }

  void observe(const std::vector<survey::MarkerSighting>& sightings) {
    if (sightings.size() < 2) return;
    const survey::MarkerSighting* representative = nullptr;
    double nearest = 0;
    for (const survey::MarkerSighting& sighting : sightings) {
      const auto placed = places_.find(sighting.id);
      if (placed == places_.end()) continue;
      const double distance = (placed->second.mean.head<3>() - places_[reference_id_].mean.head<3>()).norm();
      if (representative == nullptr || distance < nearest) {
        representative = &sighting;
        nearest = distance;
      }
    }
    if (representative == nullptr) return;
    const survey::CeilingPose base = places_[representative->id].mean;
    for (const survey::MarkerSighting& sighting : sightings) {
      if (&sighting == representative || sighting.id == reference_id_) continue;
      const survey::RelativeSighting relative =
          survey::relative_sighting(representative->base_in_marker, representative->covariance,
                                    sighting.base_in_marker, sighting.covariance);
      add(sighting.id, survey::compose(base, relative.b_in_a));
    }
  }

  bool place(int id, survey::CeilingPose& pose) const {
    const auto found = places_.find(id);
    if (found == places_.end()) return false;
    pose = found->second.mean;
    return true;
  }
  int resets() const { return resets_; }

 private:
  struct Place {
    survey::CeilingPose mean;
    int samples = 0;
  };
  void add(int id, const survey::CeilingPose& placement) {
    Place& place = places_[id];
    if (place.samples > 0 && (placement.head<3>() - place.mean.head<3>()).norm() > reset_threshold_) {
      place.samples = 0;
      ++resets_;
    }
    if (place.samples == 0) place.mean = placement;
    ++place.samples;
    place.mean += survey::pose_difference(placement, place.mean) / place.samples;
  }

  int reference_id_;
  double reset_threshold_;
  std::map<int, Place> places_;
  int resets_ = 0;
};

}  // namespace irloc::test
