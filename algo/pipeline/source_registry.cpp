#include "algo/pipeline/source_registry.hpp"

#include "algo/markers/dot/dot_marker_source.hpp"
#include "algo/markers/led/led_landmark_source.hpp"
#include "algo/markers/outside_in/outside_in_source.hpp"
#include "algo/markers/square/square_marker_source.hpp"

namespace irloc {

std::vector<std::unique_ptr<PoseSource>> make_pose_sources(const LocalizerSetup& setup, const SourceSetup& common) {
  std::vector<std::unique_ptr<PoseSource>> sources;
  if (setup.outside_in) {
    sources.push_back(std::make_unique<outside_in::OutsideInSource>(common, *setup.outside_in));
    return sources;
  }
  if (!setup.map.dot_markers.empty()) sources.push_back(std::make_unique<dot::DotMarkerSource>(common, setup.dot));
  if (!setup.map.square_markers.empty()) sources.push_back(std::make_unique<square::SquareMarkerSource>(common, setup.square));
  if (!setup.map.led_landmarks.empty()) sources.push_back(std::make_unique<led::LedLandmarkSource>(common, setup.led));
  return sources;
}

}  // namespace irloc
