#pragma once
// The square tape marker source: the map's square seen by the SquareDetector, reported in the
// shape of every source (algo/source/pose_source.hpp). Its observations are the four corners.

#include "algo/markers/square/square_config.hpp"
#include "algo/markers/square/square_detector.hpp"
#include "algo/source/pose_source.hpp"

namespace irloc {

class SquareMarkerSource final : public PoseSource {
 public:
  // Uses the map's first square marker. Throws std::invalid_argument for dof 6, or a marker that
  // is not a level square above the camera.
  SquareMarkerSource(const SourceSetup& setup, const SquareConfig& config);

  SourceKind kind() const override { return SourceKind::square; }
  void process(const SourceInput& input, SourceResult& result) override;

  const SquareDetector& detector() const { return detector_; }
  // The detector's result for the last pair (outcome no_square when there was no LED-off frame).
  const SquareDetection& last_detection() const { return detection_; }

 private:
  SquareDetector detector_;
  SquareDetection detection_;
};

}  // namespace irloc
